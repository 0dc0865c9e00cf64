#include "core/app/tile_messages.h"

#include <cstring>

#include "core/error.h"

namespace prism {
namespace {

size_t pixel_count(const Tile& tile) {
  return size_t(tile.end.x - tile.begin.x) * size_t(tile.end.y - tile.begin.y);
}

void append(std::vector<std::byte>& out, const void* data, size_t size) {
  const size_t at = out.size();
  out.resize(at + size);
  std::memcpy(out.data() + at, data, size);
}

/// Reads what append() wrote, checking that the bytes hold it.
class Reader {
 public:
  explicit Reader(const std::vector<std::byte>& bytes) : bytes_(bytes) {}
  void read(void* data, size_t size) {
    PRISM_CHECK(size <= bytes_.size() - offset_);
    std::memcpy(data, bytes_.data() + offset_, size);
    offset_ += size;
  }
  template <typename T>
  T value() {
    T v;
    read(&v, sizeof v);
    return v;
  }
  bool at_end() const { return offset_ == bytes_.size(); }

 private:
  const std::vector<std::byte>& bytes_;
  size_t offset_ = 0;
};

}  // namespace

std::vector<std::byte> encode_tiles(const TileBatch& tiles) {
  size_t size = sizeof(int32_t);
  for (const TileMessage& t : tiles) {
    size += 2 * sizeof(int32_t) + sizeof(uint64_t);
    if (t.pixels) size += t.pixels->size() * sizeof(FilmPixel);
  }
  std::vector<std::byte> out;
  out.reserve(size);
  const int32_t count = static_cast<int32_t>(tiles.size());
  append(out, &count, sizeof count);
  for (const TileMessage& t : tiles) {
    const int32_t index = t.index;
    const int32_t has_pixels = t.pixels ? 1 : 0;
    append(out, &index, sizeof index);
    append(out, &has_pixels, sizeof has_pixels);
    append(out, &t.non_finite_samples, sizeof t.non_finite_samples);
    if (t.pixels) append(out, t.pixels->data(), t.pixels->size() * sizeof(FilmPixel));
  }
  return out;
}

TileBatch decode_tiles(const std::vector<std::byte>& bytes, const RenderSchedule& schedule) {
  Reader in(bytes);
  const auto count = in.value<int32_t>();
  PRISM_CHECK(count >= 0 && count <= schedule.tile_count());
  TileBatch tiles(static_cast<size_t>(count));
  for (TileMessage& t : tiles) {
    t.index = in.value<int32_t>();
    PRISM_CHECK(t.index >= 0 && t.index < schedule.tile_count());
    const auto has_pixels = in.value<int32_t>();
    t.non_finite_samples = in.value<uint64_t>();
    if (has_pixels == 0) continue;
    t.pixels.emplace(pixel_count(schedule.tile(t.index)));
    in.read(t.pixels->data(), t.pixels->size() * sizeof(FilmPixel));
  }
  PRISM_CHECK(in.at_end());
  return tiles;
}

std::vector<std::byte> encode_int(int32_t value) {
  std::vector<std::byte> out;
  append(out, &value, sizeof value);
  return out;
}

int32_t decode_int(const std::vector<std::byte>& bytes) {
  Reader in(bytes);
  const auto value = in.value<int32_t>();
  PRISM_CHECK(in.at_end());
  return value;
}

std::vector<FilmPixel> tile_pixels(const Film& film, const Tile& tile) {
  std::vector<FilmPixel> pixels;
  pixels.reserve(pixel_count(tile));
  for (int y = tile.begin.y; y < tile.end.y; ++y) {
    for (int x = tile.begin.x; x < tile.end.x; ++x) pixels.push_back(film.pixel({x, y}));
  }
  return pixels;
}

void set_tile_pixels(Film& film, const Tile& tile, const std::vector<FilmPixel>& pixels) {
  PRISM_CHECK(pixels.size() == pixel_count(tile));
  size_t i = 0;
  for (int y = tile.begin.y; y < tile.end.y; ++y) {
    for (int x = tile.begin.x; x < tile.end.x; ++x) film.pixel({x, y}) = pixels[i++];
  }
}

bool tile_is_blank(const Film& film, const Tile& tile) {
  static const FilmPixel blank{};
  for (int y = tile.begin.y; y < tile.end.y; ++y) {
    for (int x = tile.begin.x; x < tile.end.x; ++x) {
      if (std::memcmp(&film.pixel({x, y}), &blank, sizeof blank) != 0) return false;
    }
  }
  return true;
}

}  // namespace prism
