#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/film.h"
#include "core/render_schedule.h"

namespace prism {

/// The messages of a distributed render (core/app/mpi_render.h) and their bytes. Every rank runs
/// the same binary on the same architecture, so FilmPixels travel as they are in memory.
enum class MessageTag : int {
  kRequest = 1,  ///< worker -> 0: "send me tiles": int32 how many
  kAssign,       ///< 0 -> worker: tiles to render (TileBatch, no tile: no more work)
  kResults,      ///< worker -> 0: tiles it is done with (TileBatch)
  kStopped,      ///< worker -> 0: it received a stop signal: int32 the signal
  kStop,         ///< 0 -> worker: stop after the tiles being rendered, return the others
  kDone,         ///< worker -> 0: every tile it had is returned; nothing follows
  kFinish,       ///< 0 -> worker: the render is over, exit with int32 this code
};

/// One tile of the schedule in a message, with the states of its pixels (row-major, as in a
/// Film whose window is the tile) or none: an assignment of a tile that has no samples yet, a
/// tile returned unrendered after a stop.
struct TileMessage {
  int index = 0;
  uint64_t non_finite_samples = 0;  ///< (results) NaN/Inf samples the tile's rendering counted
  std::optional<std::vector<FilmPixel>> pixels;
};

/// Tiles in one message. Encoding: int32 count, then per tile int32 index, int32 1 (pixels
/// follow) or 0, uint64 non-finite samples, and the pixels' bytes.
using TileBatch = std::vector<TileMessage>;

std::vector<std::byte> encode_tiles(const TileBatch& tiles);
/// Decodes what encode_tiles() made for tiles of `schedule`; throws Error(kInternal) on bytes
/// that do not fit (a tile index out of range, a wrong size).
TileBatch decode_tiles(const std::vector<std::byte>& bytes, const RenderSchedule& schedule);

/// One int32 (requests, signals, exit codes) as bytes, and back (Error(kInternal) unless the
/// bytes are one int32).
std::vector<std::byte> encode_int(int32_t value);
int32_t decode_int(const std::vector<std::byte>& bytes);

/// The states of `tile`'s pixels in `film` (row-major), and back.
std::vector<FilmPixel> tile_pixels(const Film& film, const Tile& tile);
void set_tile_pixels(Film& film, const Tile& tile, const std::vector<FilmPixel>& pixels);

/// Whether every pixel of `tile` in `film` is still as a new film has it (no sample, no state).
bool tile_is_blank(const Film& film, const Tile& tile);

}  // namespace prism
