// A worker rank of a distributed render: renders the tiles rank 0 hands out, sends them back.

#include <utility>

#include "core/app/mpi_render.h"
#include "core/app/tile_lanes.h"
#include "core/error.h"

namespace prism {
namespace {

class Worker {
 public:
  Worker(const TileRenderer& renderer, const RenderSchedule& schedule, int width, int height,
         MpiChannel& channel, int lanes, const std::atomic<int>* stop_signal)
      : schedule_(schedule),
        width_(width),
        height_(height),
        channel_(channel),
        stop_signal_(stop_signal),
        lanes_(renderer, schedule.samples(), lanes) {}

  int run() {
    // Double buffering: a request for more goes out while half the tiles held are left.
    const size_t target = 2 * size_t(lanes_.lanes());
    for (;;) {
      bool busy = false;
      while (auto message = channel_.receive()) {
        if (message->tag == MessageTag::kFinish) return decode_int(message->bytes);
        handle(*message);
        busy = true;
      }
      if (!stopping_ && !done_sent_ && stop_signal_ && stop_signal_->load() != 0) {
        channel_.send(0, MessageTag::kStopped, encode_int(stop_signal_->load()));
        stop();
      }
      busy |= send_finished();
      const size_t load = lanes_.load();
      if (!stopping_ && !no_more_ && !requesting_ && load <= target / 2) {
        channel_.send(0, MessageTag::kRequest, encode_int(int32_t(target - load)));
        requesting_ = true;
      }
      if ((stopping_ || no_more_) && !requesting_ && load == 0 && !done_sent_) {
        channel_.send(0, MessageTag::kDone, {});
        done_sent_ = true;
      }
      if (!busy) poll_pause();
    }
  }

 private:
  void handle(const MpiMessage& message) {
    switch (message.tag) {
      case MessageTag::kAssign: {
        requesting_ = false;
        TileBatch tiles = decode_tiles(message.bytes, schedule_);
        if (tiles.empty()) no_more_ = true;
        for (TileMessage& tile : tiles) {
          const Tile rect = schedule_.tile(tile.index);
          TileJob job{tile.index, rect, Film(width_, height_, PixelRect{rect.begin, rect.end})};
          if (tile.pixels) set_tile_pixels(job.film, rect, *tile.pixels);
          lanes_.push(std::move(job));
        }
        return;
      }
      case MessageTag::kStop:
        stop();
        return;
      default:
        throw Error(ErrorKind::kInternal, "a worker received an unexpected message");
    }
  }

  /// Sends the tiles the lanes are done with (rendered, or given back after a stop).
  bool send_finished() {
    std::vector<TileJob> finished = lanes_.take_finished();
    if (finished.empty()) return false;
    TileBatch batch;
    for (const TileJob& job : finished) {
      TileMessage tile{job.index, job.film.non_finite_samples(), std::nullopt};
      if (job.rendered) tile.pixels = tile_pixels(job.film, job.tile);
      batch.push_back(std::move(tile));
    }
    channel_.send(0, MessageTag::kResults, encode_tiles(batch));
    return true;
  }

  void stop() {
    stopping_ = true;
    lanes_.halt();
  }

  const RenderSchedule& schedule_;
  int width_, height_;
  MpiChannel& channel_;
  const std::atomic<int>* stop_signal_;
  TileLanes lanes_;
  bool requesting_ = false;  ///< a request is in flight
  bool no_more_ = false;     ///< rank 0 has no more tiles
  bool stopping_ = false;
  bool done_sent_ = false;
};

}  // namespace

int serve_render(const TileRenderer& renderer, const RenderSchedule& schedule, int width,
                 int height, MpiChannel& channel, int lanes, const std::atomic<int>* stop_signal) {
  return Worker(renderer, schedule, width, height, channel, lanes, stop_signal).run();
}

}  // namespace prism
