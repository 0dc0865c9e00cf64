#pragma once

#include "core/bounds.h"
#include "core/camera.h"
#include "core/film.h"

namespace prism {

/// The pixels of a width x height image whose camera rays may reach `bounds`, as a rectangle
/// inside [0, width) x [0, height). Conservative: every ray generate_ray() makes for a film
/// position inside a pixel outside the rectangle (any sample position, corners included) misses
/// `bounds`, with room for the rays' rounding. The rectangle is the whole image when this cannot
/// be shown cheaply: a camera with a lens, a box that reaches behind the camera, non-finite
/// values. An empty `bounds` gives an empty rectangle (no ray can hit anything).
PixelRect pixels_seeing_bounds(const Camera& camera, const Bounds3& bounds, int width, int height);

}  // namespace prism
