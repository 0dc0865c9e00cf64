#include "integrators/lights/environment_light.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "integrators/sampling/warp.h"

namespace prism {
namespace {

int channel_index(const Image& image, const std::string& name) {
  for (int c = 0; c < image.channels(); ++c) {
    if (image.channel_names[size_t(c)] == name) return c;
  }
  throw Error(ErrorKind::kInput, "environment map has no channel '" + name + "'",
              {{}, 0, "environment map"});
}

}  // namespace

EnvironmentLight::EnvironmentLight(const Image& image, const Vec3& up, float scene_radius)
    : width_(image.width),
      height_(image.height),
      frame_(Frame::from_z(glm::normalize(up))),
      scene_radius_(scene_radius) {
  if (width_ <= 0 || height_ <= 0 ||
      image.pixels.size() != size_t(width_) * height_ * size_t(image.channels())) {
    throw Error(ErrorKind::kInput, "environment map is empty or malformed",
                {{}, 0, "environment map"});
  }
  const int r = channel_index(image, "R"), g = channel_index(image, "G"),
            b = channel_index(image, "B");
  pixels_.resize(size_t(width_) * height_);
  std::vector<float> weights(pixels_.size());
  double solid_angle_sum = 0.0;
  Rgb radiance_sum(0.0f);
  for (int y = 0; y < height_; ++y) {
    const float sin_theta = std::sin(kPi * (float(y) + 0.5f) / float(height_));
    for (int x = 0; x < width_; ++x) {
      Rgb c(image.at(x, y, r), image.at(x, y, g), image.at(x, y, b));
      // Negative or non-finite texels would make negative weights or NaN radiance.
      for (int k = 0; k < 3; ++k) c[k] = std::isfinite(c[k]) ? std::max(0.0f, c[k]) : 0.0f;
      const size_t i = size_t(y) * width_ + x;
      pixels_[i] = c;
      // Luminance of a non-negative colour is zero only when the colour is black.
      weights[i] = luminance(c) * sin_theta;
      radiance_sum += c * sin_theta;
      solid_angle_sum += sin_theta;
    }
  }
  pixel_distribution_ = DiscreteDistribution(weights);
  if (solid_angle_sum > 0.0) mean_radiance_ = radiance_sum / float(solid_angle_sum);
}

glm::ivec2 EnvironmentLight::pixel_of(const Vec3& w, float* sin_theta) const {
  const Vec3 local = glm::normalize(frame_.to_local(w));
  const float theta = std::acos(std::clamp(local.z, -1.0f, 1.0f));
  float phi = std::atan2(local.y, local.x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  const int x = std::clamp(int(phi / (2.0f * kPi) * float(width_)), 0, width_ - 1);
  const int y = std::clamp(int(theta / kPi * float(height_)), 0, height_ - 1);
  if (sin_theta) *sin_theta = std::sin(theta);
  return {x, y};
}

std::optional<LightLiSample> EnvironmentLight::sample_li(const Vec3& p, Vec2 u) const {
  if (pixel_distribution_.total() <= 0.0) return std::nullopt;
  float pmf = 0.0f, u_remapped = 0.0f;
  const size_t i = pixel_distribution_.sample(u.x, &pmf, &u_remapped);
  const int x = int(i % size_t(width_)), y = int(i / size_t(width_));
  // Uniform in (phi, theta) within the pixel.
  const float phi = 2.0f * kPi * (float(x) + u_remapped) / float(width_);
  const float theta = kPi * (float(y) + u.y) / float(height_);
  const float sin_theta = std::sin(theta);
  if (!(sin_theta > 0.0f) || !(pmf > 0.0f)) return std::nullopt;
  const Vec3 local(sin_theta * std::cos(phi), sin_theta * std::sin(phi), std::cos(theta));
  LightLiSample s;
  s.wi = glm::normalize(frame_.to_world(local));
  // Density in (u, v) is pmf * width * height; d(omega) = 2 pi^2 sin(theta) du dv.
  s.pdf = pmf * float(width_) * float(height_) / (2.0f * kPi * kPi * sin_theta);
  s.li = texel(x, y);
  s.distance = kInfinity;
  return s;
}

float EnvironmentLight::pdf_li_escaped(const Vec3& w) const {
  if (pixel_distribution_.total() <= 0.0) return 0.0f;
  float sin_theta = 0.0f;
  const glm::ivec2 px = pixel_of(w, &sin_theta);
  if (!(sin_theta > 0.0f)) return 0.0f;
  const float pmf = pixel_distribution_.pmf(size_t(px.y) * width_ + px.x);
  return pmf * float(width_) * float(height_) / (2.0f * kPi * kPi * sin_theta);
}

Rgb EnvironmentLight::le_escaped(const Vec3& w) const {
  const glm::ivec2 px = pixel_of(w, nullptr);
  return texel(px.x, px.y);
}

Rgb EnvironmentLight::power() const {
  return 4.0f * kPi * kPi * scene_radius_ * scene_radius_ * mean_radiance_;
}

}  // namespace prism
