#include "accel/accelerator.h"

#include "core/error.h"

namespace prism {

void Accelerator::intersect(std::span<const Ray> rays, std::span<std::optional<Hit>> hits) const {
  PRISM_CHECK(rays.size() == hits.size());
  for (size_t i = 0; i < rays.size(); ++i) hits[i] = intersect(rays[i]);
}

}  // namespace prism
