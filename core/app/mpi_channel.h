#pragma once

#include <cstddef>
#include <cstdint>
#include <list>
#include <memory>
#include <optional>
#include <vector>

#include "core/app/tile_messages.h"

namespace prism {

/// A message from another rank.
struct MpiMessage {
  int source = 0;
  MessageTag tag = MessageTag::kRequest;
  std::vector<std::byte> bytes;
};

/// The point-to-point messages of a distributed render over MPI_COMM_WORLD, never blocking:
/// send() starts an MPI_Isend and keeps its buffer until it completed; receive() returns a
/// message that has arrived, if any. So two ranks sending each other large messages cannot
/// deadlock, and a rank never waits inside MPI (where Open MPI spins on a core). Counts the
/// bytes it sends and receives. Main thread only (MPI_THREAD_FUNNELED).
class MpiChannel {
 public:
  MpiChannel();
  /// Waits until every send completed.
  ~MpiChannel();
  MpiChannel(const MpiChannel&) = delete;
  MpiChannel& operator=(const MpiChannel&) = delete;

  void send(int destination, MessageTag tag, std::vector<std::byte> bytes);
  /// A message that has arrived from any rank, or nothing; also advances the sends.
  std::optional<MpiMessage> receive();
  /// Returns once every send completed (polling, with short sleeps).
  void flush();

  uint64_t bytes_sent() const { return bytes_sent_; }
  uint64_t bytes_received() const { return bytes_received_; }

 private:
  struct PendingSend;
  void advance_sends();

  std::list<std::unique_ptr<PendingSend>> pending_;
  uint64_t bytes_sent_ = 0;
  uint64_t bytes_received_ = 0;
};

/// Sleeps briefly: the wait of a polling loop with nothing to do.
void poll_pause();

}  // namespace prism
