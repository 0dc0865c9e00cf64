// Rank 0 of a distributed render: hands tiles out, renders some itself, takes them back whole.

#include <algorithm>
#include <chrono>
#include <deque>
#include <utility>
#include <vector>

#include "core/app/mpi_render.h"
#include "core/app/mpi_world.h"
#include "core/app/tile_lanes.h"
#include "core/error.h"
#include "core/timing.h"

namespace prism {
namespace {

using Clock = std::chrono::steady_clock;

/// Whether every pixel of `tile` has taken every sample of `samples`.
bool tile_complete(const Film& film, const Tile& tile, SampleRange samples) {
  for (int y = tile.begin.y; y < tile.end.y; ++y) {
    for (int x = tile.begin.x; x < tile.end.x; ++x) {
      if (film.pixel({x, y}).progress < samples.last) return false;
    }
  }
  return true;
}

class Coordinator {
 public:
  Coordinator(const TileRenderer& renderer, const RenderSchedule& schedule, Film& film,
              MpiChannel& channel, const DistributedOptions& options)
      : schedule_(schedule),
        film_(film),
        channel_(channel),
        options_(options),
        lanes_(renderer, schedule.samples(), options.lanes),
        done_(size_t(mpi::size()), false) {
    for (int t = 0; t < schedule.tile_count(); ++t) {
      if (!tile_complete(film, schedule.tile(t), schedule.samples())) pending_.push_back(t);
    }
  }

  DistributedResult run() {
    const Clock::time_point start = Clock::now();
    Clock::time_point last_checkpoint = start;
    while (!finished()) {
      bool busy = false;
      while (auto message = channel_.receive()) {
        handle(*message);
        busy = true;
      }
      for (TileJob& job : lanes_.take_finished()) {
        TileMessage tile{job.index, job.film.non_finite_samples(), std::nullopt};
        if (job.rendered) tile.pixels = tile_pixels(job.film, job.tile);
        take_back(tile);
        busy = true;
      }
      if (signal_ == 0 && options_.stop_signal && options_.stop_signal->load() != 0) {
        stop(options_.stop_signal->load());
      }
      answer_requests();
      feed_lanes();
      // Not while stopping: the checkpoint of the stop is written once every tile is back.
      if (options_.checkpoint && signal_ == 0 && !finished() &&
          seconds_since(last_checkpoint) >= options_.checkpoint_interval_seconds) {
        options_.checkpoint(film_);
        last_checkpoint = Clock::now();
      }
      if (!busy) poll_pause();
    }
    DistributedResult result;
    result.run.end = signal_ != 0 ? RenderEnd::kSignal : RenderEnd::kComplete;
    result.run.passes_complete = passes_complete(schedule_, film_);
    result.run.seconds = seconds_since(start);
    result.signal = signal_;
    result.bytes_exchanged = channel_.bytes_sent() + channel_.bytes_received();
    return result;
  }

 private:
  bool finished() const {
    if ((signal_ == 0 && !pending_.empty()) || outstanding_ > 0) return false;
    for (size_t rank = 1; rank < done_.size(); ++rank) {
      if (!done_[rank]) return false;
    }
    return true;
  }

  void handle(const MpiMessage& message) {
    switch (message.tag) {
      case MessageTag::kRequest:
        requests_.emplace_back(message.source, decode_int(message.bytes));
        return;
      case MessageTag::kResults:
        for (const TileMessage& tile : decode_tiles(message.bytes, schedule_)) take_back(tile);
        return;
      case MessageTag::kStopped:
        if (signal_ == 0) stop(decode_int(message.bytes));
        return;
      case MessageTag::kDone:
        done_.at(size_t(message.source)) = true;
        return;
      default:
        throw Error(ErrorKind::kInternal, "rank 0 received an unexpected message");
    }
  }

  /// A tile handed out comes back: rendered (it replaces the film's tile) or untouched.
  void take_back(const TileMessage& tile) {
    --outstanding_;
    if (!tile.pixels) return;
    const Tile rect = schedule_.tile(tile.index);
    if (options_.progress) {
      const SampleRange samples = schedule_.samples();
      const uint32_t done = std::max(film_.pixel(rect.begin).progress, samples.first);
      const uint64_t pixels = uint64_t(rect.end.x - rect.begin.x) * (rect.end.y - rect.begin.y);
      options_.progress->update(pixels * (samples.last - std::min(done, samples.last)));
    }
    set_tile_pixels(film_, rect, *tile.pixels);
    film_.set_non_finite_samples(film_.non_finite_samples() + tile.non_finite_samples);
  }

  /// Tile `index` as handed out: with its pixels' states when it has any.
  TileMessage hand_out(int index) {
    ++outstanding_;
    TileMessage tile{index, 0, std::nullopt};
    const Tile rect = schedule_.tile(index);
    if (!tile_is_blank(film_, rect)) tile.pixels = tile_pixels(film_, rect);
    return tile;
  }

  void answer_requests() {
    for (const auto& [rank, wanted] : requests_) {
      TileBatch batch;
      while (signal_ == 0 && !pending_.empty() && int(batch.size()) < wanted) {
        batch.push_back(hand_out(pending_.front()));
        pending_.pop_front();
      }
      // An empty batch: no more work for this worker.
      channel_.send(rank, MessageTag::kAssign, encode_tiles(batch));
    }
    requests_.clear();
  }

  void feed_lanes() {
    while (signal_ == 0 && !pending_.empty() && lanes_.load() < size_t(lanes_.lanes()) + 1) {
      const int index = pending_.front();
      pending_.pop_front();
      TileMessage tile = hand_out(index);
      const Tile rect = schedule_.tile(index);
      TileJob job{index, rect,
                  Film(film_.width(), film_.height(), PixelRect{rect.begin, rect.end})};
      if (tile.pixels) set_tile_pixels(job.film, rect, *tile.pixels);
      lanes_.push(std::move(job));
    }
  }

  void stop(int signal) {
    signal_ = signal;
    lanes_.halt();
    for (int rank = 1; rank < mpi::size(); ++rank) channel_.send(rank, MessageTag::kStop, {});
  }

  const RenderSchedule& schedule_;
  Film& film_;
  MpiChannel& channel_;
  const DistributedOptions& options_;
  TileLanes lanes_;
  std::deque<int> pending_;                    ///< tiles not handed out yet, in order
  std::vector<std::pair<int, int>> requests_;  ///< unanswered: rank, tiles wanted
  std::vector<bool> done_;                     ///< per rank: said it is done
  int outstanding_ = 0;                        ///< tiles handed out and not back
  int signal_ = 0;                             ///< the stop signal, once stopping
};

}  // namespace

DistributedResult coordinate_render(const TileRenderer& renderer, const RenderSchedule& schedule,
                                    Film& film, MpiChannel& channel,
                                    const DistributedOptions& options) {
  return Coordinator(renderer, schedule, film, channel, options).run();
}

void finish_workers(MpiChannel& channel, int exit_code) {
  for (int rank = 1; rank < mpi::size(); ++rank) {
    channel.send(rank, MessageTag::kFinish, encode_int(exit_code));
  }
  channel.flush();
}

}  // namespace prism
