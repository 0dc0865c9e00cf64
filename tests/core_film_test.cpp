// core/film.h: per-pixel means, sample counts, the variance of the mean, AOV means, and the
// handling of non-finite samples, against hand computations.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/film.h"
#include "core/image.h"

namespace prism {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

AovSample aov(Rgb albedo, Vec3 normal, float depth) {
  AovSample a;
  a.albedo = albedo;
  a.normal = normal;
  a.depth = depth;
  return a;
}

/// The 14 resolved values of one pixel.
std::vector<float> pixel_values(const Image& image, int x, int y) {
  std::vector<float> out;
  for (int c = 0; c < image.channels(); ++c) out.push_back(image.at(x, y, c));
  return out;
}

TEST(CoreFilm, ChannelNamesMatchTheConstants) {
  const Film film(3, 2);
  const Image image = film.resolve();
  EXPECT_EQ(image.width, 3);
  EXPECT_EQ(image.height, 2);
  ASSERT_EQ(image.channels(), Film::kChannels);
  EXPECT_EQ(image.pixels.size(), size_t(3 * 2 * Film::kChannels));
  const std::vector<std::string> expected{
      "R",   "G",   "B", "albedo.R",      "albedo.G",   "albedo.B",   "N.X",
      "N.Y", "N.Z", "Z", "sampleCount.Y", "variance.R", "variance.G", "variance.B"};
  EXPECT_EQ(image.channel_names, expected);
  EXPECT_EQ(image.channel_names[0], "R");
  EXPECT_EQ(image.channel_names[Film::kAlbedoChannel], "albedo.R");
  EXPECT_EQ(image.channel_names[Film::kNormalChannel], "N.X");
  EXPECT_EQ(image.channel_names[Film::kDepthChannel], "Z");
  EXPECT_EQ(image.channel_names[Film::kSampleCountChannel], "sampleCount.Y");
  EXPECT_EQ(image.channel_names[Film::kVarianceChannel], "variance.R");
  EXPECT_EQ(image.channel_names[Film::kVarianceChannel + 2], "variance.B");
}

TEST(CoreFilm, UntouchedPixelsAreAllZero) {
  Film film(4, 3);
  film.add_sample({1, 2}, Rgb(0.5f), aov(Rgb(0.5f), Vec3(0, 0, 1), 3.0f));
  const Image image = film.resolve();
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 4; ++x) {
      if (x == 1 && y == 2) continue;
      EXPECT_EQ(film.sample_count({x, y}), 0u);
      for (int c = 0; c < Film::kChannels; ++c) {
        EXPECT_EQ(image.at(x, y, c), 0.0f) << x << "," << y << " " << image.channel_names[c];
      }
    }
  }
  EXPECT_EQ(image.at(1, 2, 0), 0.5f);
  EXPECT_EQ(image.count_non_finite(), 0u);
}

TEST(CoreFilm, RadianceIsTheMeanOfThePixelsSamples) {
  Film film(3, 2);
  film.add_sample({0, 0}, Rgb(1.0f, 0.0f, 2.0f));
  film.add_sample({0, 0}, Rgb(2.0f, 0.5f, 2.0f));
  film.add_sample({0, 0}, Rgb(4.0f, 1.0f, 2.0f));
  film.add_sample({2, 1}, Rgb(0.25f, 0.5f, 0.75f));
  // Row-major layout: (2, 1) is not (1, 2) and not (0, 0).
  film.add_sample({1, 0}, Rgb(8.0f));
  film.add_sample({1, 0}, Rgb(0.0f));
  EXPECT_EQ(film.sample_count({0, 0}), 3u);
  EXPECT_EQ(film.sample_count({2, 1}), 1u);
  EXPECT_EQ(film.sample_count({1, 0}), 2u);
  EXPECT_EQ(film.sample_count({0, 1}), 0u);

  const Image image = film.resolve();
  EXPECT_FLOAT_EQ(image.at(0, 0, 0), 7.0f / 3.0f);
  EXPECT_FLOAT_EQ(image.at(0, 0, 1), 0.5f);
  EXPECT_FLOAT_EQ(image.at(0, 0, 2), 2.0f);
  EXPECT_FLOAT_EQ(image.at(2, 1, 0), 0.25f);
  EXPECT_FLOAT_EQ(image.at(2, 1, 1), 0.5f);
  EXPECT_FLOAT_EQ(image.at(2, 1, 2), 0.75f);
  EXPECT_FLOAT_EQ(image.at(1, 0, 0), 4.0f);
  EXPECT_EQ(image.at(0, 0, Film::kSampleCountChannel), 3.0f);
  EXPECT_EQ(image.at(2, 1, Film::kSampleCountChannel), 1.0f);
  EXPECT_EQ(image.at(1, 0, Film::kSampleCountChannel), 2.0f);
  EXPECT_EQ(image.at(0, 1, Film::kSampleCountChannel), 0.0f);
}

TEST(CoreFilm, VarianceIsTheSampleVarianceOverN) {
  Film film(2, 2);
  // R: 1, 2, 4: mean 7/3, squared deviations 16/9 + 1/9 + 25/9 = 42/9, sample variance
  // 42/9 / 2 = 7/3, over n = 3: 7/9. G: constant: 0. B: 0, 0, 3: mean 1, deviations 1+1+4 = 6,
  // sample variance 3, over 3: 1.
  film.add_sample({1, 1}, Rgb(1.0f, 5.0f, 0.0f));
  film.add_sample({1, 1}, Rgb(2.0f, 5.0f, 0.0f));
  film.add_sample({1, 1}, Rgb(4.0f, 5.0f, 3.0f));
  // Two samples 1 and 3: sample variance 2, over 2: 1.
  film.add_sample({0, 1}, Rgb(1.0f, 3.0f, 1.0f));
  film.add_sample({0, 1}, Rgb(3.0f, 1.0f, 1.0f));
  // One sample: no variance estimate, 0.
  film.add_sample({1, 0}, Rgb(10.0f, 20.0f, 30.0f));

  const Image image = film.resolve();
  const int v = Film::kVarianceChannel;
  EXPECT_NEAR(image.at(1, 1, v + 0), 7.0f / 9.0f, 1e-6f);
  EXPECT_NEAR(image.at(1, 1, v + 1), 0.0f, 1e-6f);
  EXPECT_NEAR(image.at(1, 1, v + 2), 1.0f, 1e-6f);
  EXPECT_NEAR(image.at(0, 1, v + 0), 1.0f, 1e-6f);
  EXPECT_NEAR(image.at(0, 1, v + 1), 1.0f, 1e-6f);
  EXPECT_NEAR(image.at(0, 1, v + 2), 0.0f, 1e-6f);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(image.at(1, 0, v + k), 0.0f);
    EXPECT_EQ(image.at(0, 0, v + k), 0.0f);
  }
}

TEST(CoreFilm, VarianceMatchesADoubleComputationOnManySamples) {
  // Welford's update in float against the two-pass formula in double.
  std::mt19937 rng(1234);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  Film film(1, 1);
  std::vector<double> values;
  for (int i = 0; i < 1000; ++i) {
    const float x = 100.0f + uniform(rng);  // a large mean: naive sum-of-squares would cancel
    values.push_back(x);
    film.add_sample({0, 0}, Rgb(x));
  }
  double mean = 0.0;
  for (double x : values) mean += x;
  mean /= double(values.size());
  double m2 = 0.0;
  for (double x : values) m2 += (x - mean) * (x - mean);
  const double n = double(values.size());
  const double variance_of_mean = m2 / (n - 1.0) / n;  // ~ (1/12) / 1000

  const Image image = film.resolve();
  EXPECT_NEAR(image.at(0, 0, 0), mean, 1e-3);
  EXPECT_NEAR(image.at(0, 0, Film::kVarianceChannel), variance_of_mean, 1e-2 * variance_of_mean);
}

TEST(CoreFilm, AovsAreMeansOverAllSamples) {
  Film film(2, 1);
  film.add_sample({0, 0}, Rgb(1.0f), aov(Rgb(0.2f, 0.4f, 0.6f), Vec3(1, 0, 0), 2.0f));
  film.add_sample({0, 0}, Rgb(1.0f), aov(Rgb(0.4f, 0.8f, 0.0f), Vec3(0, 1, 0), 4.0f));
  // An escaped ray: AOVs are zero and count in the mean.
  film.add_sample({1, 0}, Rgb(1.0f), aov(Rgb(0.9f), Vec3(0, 0, -1), 6.0f));
  film.add_sample({1, 0}, Rgb(1.0f));

  const Image image = film.resolve();
  const int a = Film::kAlbedoChannel, n = Film::kNormalChannel, z = Film::kDepthChannel;
  EXPECT_FLOAT_EQ(image.at(0, 0, a + 0), 0.3f);
  EXPECT_FLOAT_EQ(image.at(0, 0, a + 1), 0.6f);
  EXPECT_FLOAT_EQ(image.at(0, 0, a + 2), 0.3f);
  // The mean normal is not renormalised: (0.5, 0.5, 0) has length 0.707.
  EXPECT_FLOAT_EQ(image.at(0, 0, n + 0), 0.5f);
  EXPECT_FLOAT_EQ(image.at(0, 0, n + 1), 0.5f);
  EXPECT_FLOAT_EQ(image.at(0, 0, n + 2), 0.0f);
  EXPECT_FLOAT_EQ(image.at(0, 0, z), 3.0f);

  EXPECT_FLOAT_EQ(image.at(1, 0, a + 0), 0.45f);
  EXPECT_FLOAT_EQ(image.at(1, 0, a + 1), 0.45f);
  EXPECT_FLOAT_EQ(image.at(1, 0, a + 2), 0.45f);
  EXPECT_FLOAT_EQ(image.at(1, 0, n + 0), 0.0f);
  EXPECT_FLOAT_EQ(image.at(1, 0, n + 2), -0.5f);
  EXPECT_FLOAT_EQ(image.at(1, 0, z), 3.0f);
}

TEST(CoreFilm, NonFiniteRadianceCountsAsZeroAndIsCounted) {
  Film film(3, 1);
  EXPECT_EQ(film.non_finite_samples(), 0u);
  // One bad sample of each kind, each beside a finite one; a bad component spoils the sample.
  film.add_sample({0, 0}, Rgb(2.0f, 4.0f, 6.0f));
  film.add_sample({0, 0}, Rgb(kNaN, 1.0f, 1.0f));
  film.add_sample({1, 0}, Rgb(kInf, kInf, kInf));
  film.add_sample({1, 0}, Rgb(3.0f));
  film.add_sample({2, 0}, Rgb(1.0f, -kInf, 1.0f));
  film.add_sample({2, 0}, Rgb(5.0f));
  film.add_sample({2, 0}, Rgb(1.0f));
  EXPECT_EQ(film.non_finite_samples(), 3u);
  // The bad samples are samples: they count in the number taken.
  EXPECT_EQ(film.sample_count({0, 0}), 2u);
  EXPECT_EQ(film.sample_count({1, 0}), 2u);
  EXPECT_EQ(film.sample_count({2, 0}), 3u);

  const Image image = film.resolve();
  EXPECT_EQ(image.count_non_finite(), 0u);
  EXPECT_FLOAT_EQ(image.at(0, 0, 0), 1.0f);
  EXPECT_FLOAT_EQ(image.at(0, 0, 1), 2.0f);
  EXPECT_FLOAT_EQ(image.at(0, 0, 2), 3.0f);
  EXPECT_FLOAT_EQ(image.at(1, 0, 0), 1.5f);
  EXPECT_FLOAT_EQ(image.at(2, 0, 0), 2.0f);
  EXPECT_FLOAT_EQ(image.at(2, 0, 1), 2.0f);
  // The variance sees the zero too: samples 0 and 3 give sample variance 4.5, over 2: 2.25.
  EXPECT_NEAR(image.at(1, 0, Film::kVarianceChannel), 2.25f, 1e-6f);
}

TEST(CoreFilm, EmptySamplesCountInTheMeanAndTheVariance) {
  // Samples of rays that left the scene (zero radiance, zero AOVs) take add_sample()'s short
  // path: they must still count as samples, and a non-finite one must still be counted.
  Film film(2, 1);
  film.add_sample({0, 0}, Rgb(4.0f), aov(Rgb(0.8f), Vec3(0, 0, 1), 2.0f));
  for (int i = 0; i < 3; ++i) film.add_sample({0, 0}, Rgb(0.0f));
  film.add_sample({1, 0}, Rgb(-0.0f, 0.0f, -0.0f));
  film.add_sample({1, 0}, Rgb(kNaN, kNaN, kNaN));
  EXPECT_EQ(film.sample_count({0, 0}), 4u);
  EXPECT_EQ(film.sample_count({1, 0}), 2u);
  EXPECT_EQ(film.non_finite_samples(), 1u);
  const Image image = film.resolve();
  EXPECT_FLOAT_EQ(image.at(0, 0, 0), 1.0f);
  EXPECT_FLOAT_EQ(image.at(0, 0, Film::kAlbedoChannel), 0.2f);
  EXPECT_FLOAT_EQ(image.at(0, 0, Film::kDepthChannel), 0.5f);
  // Samples 4, 0, 0, 0: sample variance 4, over 4 samples: 1.
  EXPECT_NEAR(image.at(0, 0, Film::kVarianceChannel), 1.0f, 1e-6f);
  EXPECT_EQ(image.at(1, 0, 0), 0.0f);
  EXPECT_EQ(image.count_non_finite(), 0u);
}

TEST(CoreFilm, NonFiniteAovsAreLeftOutOfTheSums) {
  Film film(1, 1);
  film.add_sample({0, 0}, Rgb(1.0f), aov(Rgb(0.8f), Vec3(0, 0, 1), 4.0f));
  // Each bad AOV is dropped (as a whole vector) without disturbing the other AOVs.
  film.add_sample({0, 0}, Rgb(1.0f), aov(Rgb(0.4f, kNaN, 0.4f), Vec3(0, 0, 1), 4.0f));
  film.add_sample({0, 0}, Rgb(1.0f), aov(Rgb(0.4f), Vec3(kInf, 0, 1), 4.0f));
  film.add_sample({0, 0}, Rgb(1.0f), aov(Rgb(0.4f), Vec3(0, 0, 1), -kInf));
  // A finite radiance with bad AOVs is not a non-finite sample.
  EXPECT_EQ(film.non_finite_samples(), 0u);
  EXPECT_EQ(film.sample_count({0, 0}), 4u);

  const Image image = film.resolve();
  EXPECT_EQ(image.count_non_finite(), 0u);
  // Sums over the finite values, divided by all four samples (a dropped AOV counts as zero,
  // as for an escaped ray).
  EXPECT_FLOAT_EQ(image.at(0, 0, Film::kAlbedoChannel + 0), (0.8f + 0.4f + 0.4f) / 4.0f);
  EXPECT_FLOAT_EQ(image.at(0, 0, Film::kAlbedoChannel + 1), (0.8f + 0.4f + 0.4f) / 4.0f);
  EXPECT_FLOAT_EQ(image.at(0, 0, Film::kNormalChannel + 0), 0.0f);
  EXPECT_FLOAT_EQ(image.at(0, 0, Film::kNormalChannel + 2), 0.75f);
  EXPECT_FLOAT_EQ(image.at(0, 0, Film::kDepthChannel), 3.0f);
  EXPECT_FLOAT_EQ(image.at(0, 0, 0), 1.0f);
}

TEST(CoreFilm, MeanVarianceAndNonFiniteSamples) {
  Film film(2, 1);
  const float values[] = {1.0f, 2.0f, 3.0f, 6.0f};
  for (float v : values) film.add_sample({0, 0}, Rgb(v), AovSample{Rgb(0.5f), Vec3(0, 0, 1), 2.0f});
  film.add_sample({1, 0}, Rgb(std::nanf("")));
  film.add_sample({1, 0}, Rgb(kInfinity));
  film.add_sample({1, 0}, Rgb(4.0f));
  EXPECT_EQ(film.non_finite_samples(), 2u);
  const Image image = film.resolve();
  EXPECT_EQ(image.count_non_finite(), 0u);
  EXPECT_FLOAT_EQ(image.at(0, 0, 0), 3.0f);
  // Sample variance (1 + 4 + 0 + 9) / 3 = 14/3; of the mean: / 4.
  EXPECT_NEAR(image.at(0, 0, Film::kVarianceChannel), 14.0f / 3.0f / 4.0f, 1e-5f);
  EXPECT_FLOAT_EQ(image.at(0, 0, Film::kAlbedoChannel), 0.5f);
  EXPECT_FLOAT_EQ(image.at(0, 0, Film::kNormalChannel + 2), 1.0f);
  EXPECT_FLOAT_EQ(image.at(0, 0, Film::kDepthChannel), 2.0f);
  EXPECT_FLOAT_EQ(image.at(0, 0, Film::kSampleCountChannel), 4.0f);
  // Non-finite samples count as zero radiance.
  EXPECT_FLOAT_EQ(image.at(1, 0, 0), 4.0f / 3.0f);
  EXPECT_FLOAT_EQ(image.at(1, 0, Film::kSampleCountChannel), 3.0f);
}

TEST(CoreFilm, RejectsAnEmptyFilm) {
  for (const auto& [w, h] : {std::pair{0, 4}, std::pair{4, 0}, std::pair{-1, 1}}) {
    try {
      Film film(w, h);
      ADD_FAILURE() << w << "x" << h << " must be rejected";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kInternal);
    }
  }
}

TEST(CoreFilm, ImageCountsNonFiniteValues) {
  Image image;
  image.width = 2;
  image.height = 2;
  image.channel_names = {"R", "G", "B"};
  image.pixels.assign(12, 1.0f);
  EXPECT_EQ(image.count_non_finite(), 0u);
  image.at(0, 0, 0) = kNaN;
  image.at(1, 0, 2) = kInf;
  image.at(0, 1, 1) = -kInf;
  image.at(1, 1, 0) = std::numeric_limits<float>::max();         // finite
  image.at(1, 1, 1) = std::numeric_limits<float>::denorm_min();  // finite
  image.at(1, 1, 2) = -0.0f;                                     // finite
  EXPECT_EQ(image.count_non_finite(), 3u);
  // at() is row-major and interleaved.
  EXPECT_TRUE(std::isnan(image.pixels[0]));
  EXPECT_EQ(image.pixels[(0 * 2 + 1) * 3 + 2], kInf);
  EXPECT_EQ(image.pixels[(1 * 2 + 0) * 3 + 1], -kInf);
  EXPECT_EQ(Image{}.count_non_finite(), 0u);
}

TEST(CoreFilm, ResolvesIntoABufferOfZerosMadeAheadOrIntoItsOwn) {
  // A crop window, with samples in some pixels only (the others stay zero in the image).
  Film film(6, 5, PixelRect{{1, 1}, {5, 4}});
  film.add_sample({2, 1}, Rgb(0.5f, 1.0f, 2.0f), aov(Rgb(0.25f), Vec3(0.0f, 0.0f, 1.0f), 3.0f));
  film.add_sample({2, 1}, Rgb(1.5f, 0.0f, 4.0f));
  film.add_sample({4, 3}, Rgb(0.0f));
  const Image reference = film.resolve();
  const size_t values = film.window().pixel_count() * Film::kChannels;
  ASSERT_EQ(reference.pixels.size(), values);
  ImagePixels ahead(values, 0.0f);
  const float* ahead_data = ahead.data();
  const Image into_ahead = film.resolve(std::move(ahead));
  EXPECT_EQ(into_ahead.pixels.data(), ahead_data) << "the buffer made ahead was not used";
  EXPECT_TRUE(into_ahead.pixels == reference.pixels);
  EXPECT_EQ(into_ahead.channel_names, reference.channel_names);
  // A buffer of another size is not the image's: the film makes its own.
  for (const size_t size : {values - 1, values + Film::kChannels}) {
    const Image own = film.resolve(ImagePixels(size, 0.0f));
    EXPECT_EQ(own.pixels.size(), values);
    EXPECT_TRUE(own.pixels == reference.pixels);
  }
}

TEST(CoreFilm, ConcurrentSamplesOnDifferentPixelsMatchSequential) {
  constexpr int kWidth = 37, kHeight = 23, kSamples = 16, kThreads = 4;
  // Every sample a pure function of (pixel, index), some of them non-finite.
  const auto sample = [](int x, int y, int i) {
    std::mt19937 rng(uint32_t(((y * kWidth + x) * kSamples + i) * 2654435761u));
    std::uniform_real_distribution<float> u(0.0f, 2.0f);
    Rgb radiance(u(rng), u(rng), u(rng));
    if ((x + y + i) % 53 == 0) radiance.g = kNaN;
    if ((x * y + i) % 71 == 0) radiance.b = kInf;
    const AovSample a =
        aov(Rgb(u(rng), u(rng), u(rng)) * 0.5f,
            glm::normalize(Vec3(u(rng) - 1.0f, u(rng) - 1.0f, 1.0f)), u(rng) * 10.0f);
    return std::pair{radiance, a};
  };
  const auto fill = [&](Film& film, int thread, int threads) {
    // Thread k takes the rows y % threads == k; each pixel is written by one thread.
    for (int y = thread; y < kHeight; y += threads) {
      for (int i = 0; i < kSamples; ++i) {
        for (int x = 0; x < kWidth; ++x) {
          const auto [radiance, a] = sample(x, y, i);
          film.add_sample({x, y}, radiance, a);
        }
      }
    }
  };

  Film sequential(kWidth, kHeight);
  fill(sequential, 0, 1);
  Film concurrent(kWidth, kHeight);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) threads.emplace_back(fill, std::ref(concurrent), t, kThreads);
  for (auto& t : threads) t.join();

  EXPECT_GT(sequential.non_finite_samples(), 0u);
  EXPECT_EQ(concurrent.non_finite_samples(), sequential.non_finite_samples());
  const Image a = sequential.resolve();
  const Image b = concurrent.resolve();
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  size_t differing = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) differing += a.pixels[i] != b.pixels[i];
  EXPECT_EQ(differing, 0u);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      ASSERT_EQ(concurrent.sample_count({x, y}), uint32_t(kSamples));
      ASSERT_EQ(pixel_values(a, x, y), pixel_values(b, x, y)) << x << "," << y;
    }
  }
}

}  // namespace
}  // namespace prism
