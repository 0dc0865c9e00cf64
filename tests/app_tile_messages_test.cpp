// core/app/tile_messages.h: the bytes of a distributed render's messages, and the tile copies.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "core/app/tile_messages.h"
#include "core/error.h"

namespace prism {
namespace {

/// A 40 x 20 film whose window holds samples of distinct values.
Film sampled_film() {
  Film film(40, 20);
  for (int y = 0; y < 20; ++y) {
    for (int x = 0; x < 40; ++x) film.add_sample({x, y}, Rgb(float(x), float(y), 0.5f));
  }
  return film;
}

bool same_bytes(const FilmPixel& a, const FilmPixel& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

TEST(AppTileMessages, TilesRoundTripWithAndWithoutPixels) {
  const RenderSchedule schedule(PixelRect{{0, 0}, {40, 20}}, SampleRange{0, 4}, 1);
  const Film film = sampled_film();
  TileBatch batch;
  batch.push_back(TileMessage{3, 7, tile_pixels(film, schedule.tile(3))});  // 16 x 4, bottom
  batch.push_back(TileMessage{0, 0, std::nullopt});
  const TileBatch back = decode_tiles(encode_tiles(batch), schedule);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].index, 3);
  EXPECT_EQ(back[0].non_finite_samples, 7u);
  ASSERT_TRUE(back[0].pixels);
  ASSERT_EQ(back[0].pixels->size(), 16u * 4u);
  for (size_t i = 0; i < back[0].pixels->size(); ++i) {
    EXPECT_TRUE(same_bytes((*back[0].pixels)[i], (*batch[0].pixels)[i]));
  }
  EXPECT_EQ(back[1].index, 0);
  EXPECT_FALSE(back[1].pixels);
  EXPECT_TRUE(decode_tiles(encode_tiles({}), schedule).empty());
}

TEST(AppTileMessages, BytesThatDoNotFitAreAnInternalError) {
  const RenderSchedule schedule(PixelRect{{0, 0}, {40, 20}}, SampleRange{0, 4}, 1);
  const Film film = sampled_film();
  std::vector<std::byte> bytes =
      encode_tiles({TileMessage{1, 0, tile_pixels(film, schedule.tile(1))}});
  bytes.pop_back();
  EXPECT_THROW(decode_tiles(bytes, schedule), Error);
  EXPECT_THROW(decode_tiles(encode_tiles({TileMessage{6, 0, std::nullopt}}), schedule), Error);
  EXPECT_THROW(decode_int({}), Error);
  EXPECT_EQ(decode_int(encode_int(-143)), -143);
}

TEST(AppTileMessages, TilePixelsCopyIntoAFilmOfTheTileAndBack) {
  const Film film = sampled_film();
  const Tile tile{{16, 16}, {32, 20}};
  Film part(40, 20, PixelRect{tile.begin, tile.end});
  EXPECT_TRUE(tile_is_blank(part, tile));
  set_tile_pixels(part, tile, tile_pixels(film, tile));
  EXPECT_FALSE(tile_is_blank(part, tile));
  EXPECT_TRUE(same_bytes(part.pixel({20, 18}), film.pixel({20, 18})));
  Film whole(40, 20);
  set_tile_pixels(whole, tile, tile_pixels(part, tile));
  EXPECT_TRUE(same_bytes(whole.pixel({31, 19}), film.pixel({31, 19})));
  EXPECT_TRUE(tile_is_blank(whole, Tile{{0, 0}, {16, 16}}));
}

}  // namespace
}  // namespace prism
