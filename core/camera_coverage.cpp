#include "core/camera_coverage.h"

#include <algorithm>
#include <cmath>

namespace prism {
namespace {

using DVec3 = glm::dvec3;

/// Relative room for rounding: the box grows by this much of the largest camera-to-corner
/// distance, far more than the few float ulps of a generated ray and of a hit inside the box.
constexpr double kRelativeMargin = 1e-4;

}  // namespace

PixelRect pixels_seeing_bounds(const Camera& camera, const Bounds3& bounds, int width, int height) {
  const PixelRect whole{{0, 0}, {std::max(0, width), std::max(0, height)}};
  if (bounds.empty()) return PixelRect{};
  if (camera.uses_lens() || whole.empty()) return whole;
  const DVec3 position(camera.position);
  const DVec3 lower(bounds.lower);
  const DVec3 upper(bounds.upper);
  // The camera's basis and half-angle tangents as CameraRayGenerator makes them, in double.
  const DVec3 forward = glm::normalize(DVec3(camera.target) - position);
  const DVec3 right = glm::normalize(glm::cross(forward, DVec3(camera.up)));
  const DVec3 true_up = glm::cross(right, forward);
  const double tan_h = std::tan(double(radians(camera.hfov_deg)) * 0.5);
  const double tan_v = std::tan(double(radians(camera.vfov_deg)) * 0.5);

  double scale = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const DVec3 p(corner & 1 ? upper.x : lower.x, corner & 2 ? upper.y : lower.y,
                  corner & 4 ? upper.z : lower.z);
    scale =
        std::max({scale, glm::length(p - position), std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  }
  const double margin = kRelativeMargin * scale;
  if (!std::isfinite(margin) || !std::isfinite(tan_h) || !std::isfinite(tan_v)) return whole;

  // A convex box in front of the camera projects inside the rectangle its corners span.
  double min_x = INFINITY, max_x = -INFINITY, min_y = INFINITY, max_y = -INFINITY;
  for (int corner = 0; corner < 8; ++corner) {
    const DVec3 p(corner & 1 ? upper.x + margin : lower.x - margin,
                  corner & 2 ? upper.y + margin : lower.y - margin,
                  corner & 4 ? upper.z + margin : lower.z - margin);
    const DVec3 d = p - position;
    const double depth = glm::dot(d, forward);
    if (!(depth > margin)) return whole;
    // Film position as generate_ray() reads it, in pixels (x right, y down).
    const double x = 0.5 * (glm::dot(d, right) / (depth * tan_h) + 1.0) * width;
    const double y = 0.5 * (1.0 - glm::dot(d, true_up) / (depth * tan_v)) * height;
    min_x = std::min(min_x, x);
    max_x = std::max(max_x, x);
    min_y = std::min(min_y, y);
    max_y = std::max(max_y, y);
  }
  if (!std::isfinite(min_x + max_x + min_y + max_y)) return whole;
  // One more pixel on every side; pixel x covers film positions [x, x + 1) / width.
  const auto clamp_to = [](double v, int limit) { return int(std::clamp(v, 0.0, double(limit))); };
  PixelRect seeing;
  seeing.begin = {clamp_to(std::floor(min_x) - 1.0, width),
                  clamp_to(std::floor(min_y) - 1.0, height)};
  seeing.end = {clamp_to(std::ceil(max_x) + 1.0, width), clamp_to(std::ceil(max_y) + 1.0, height)};
  return seeing;
}

}  // namespace prism
