#include "core/app/mpi_channel.h"

#include <mpi.h>

#include <chrono>
#include <climits>
#include <thread>

#include "core/error.h"

namespace prism {

struct MpiChannel::PendingSend {
  std::vector<std::byte> bytes;
  MPI_Request request = MPI_REQUEST_NULL;
};

MpiChannel::MpiChannel() = default;

MpiChannel::~MpiChannel() { flush(); }

void MpiChannel::send(int destination, MessageTag tag, std::vector<std::byte> bytes) {
  PRISM_CHECK(bytes.size() <= size_t(INT_MAX));
  auto pending = std::make_unique<PendingSend>();
  pending->bytes = std::move(bytes);
  bytes_sent_ += pending->bytes.size();
  MPI_Isend(pending->bytes.data(), static_cast<int>(pending->bytes.size()), MPI_BYTE, destination,
            static_cast<int>(tag), MPI_COMM_WORLD, &pending->request);
  pending_.push_back(std::move(pending));
}

std::optional<MpiMessage> MpiChannel::receive() {
  advance_sends();
  int arrived = 0;
  MPI_Status status;
  MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status);
  if (!arrived) return std::nullopt;
  int size = 0;
  MPI_Get_count(&status, MPI_BYTE, &size);
  MpiMessage message;
  message.source = status.MPI_SOURCE;
  message.tag = static_cast<MessageTag>(status.MPI_TAG);
  message.bytes.resize(size_t(size));
  MPI_Recv(message.bytes.data(), size, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
           MPI_STATUS_IGNORE);
  bytes_received_ += message.bytes.size();
  return message;
}

void MpiChannel::flush() {
  for (advance_sends(); !pending_.empty(); advance_sends()) poll_pause();
}

void MpiChannel::advance_sends() {
  for (auto it = pending_.begin(); it != pending_.end();) {
    int done = 0;
    MPI_Test(&(*it)->request, &done, MPI_STATUS_IGNORE);
    it = done ? pending_.erase(it) : std::next(it);
  }
}

void poll_pause() { std::this_thread::sleep_for(std::chrono::microseconds(500)); }

}  // namespace prism
