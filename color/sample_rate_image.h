#pragma once

#include <optional>

#include "core/image.h"

namespace prism {

/// The "sample rate" picture of an adaptive render: each pixel's sample count divided
/// by the largest count, colour-mapped from blue (few samples) through green to red (many).
/// Returns display-ready RGB values in [0, 1] (write them through a Raw view), or nothing when
/// `image` has no "sampleCount.Y" channel.
std::optional<Image> make_sample_rate_image(const Image& image);

}  // namespace prism
