#include "core/material.h"

#include <algorithm>
#include <cmath>

#include "core/light.h"

namespace prism {

void conductor_from_reflectance(const Rgb& reflectance, Rgb& eta, Rgb& k) {
  for (int c = 0; c < 3; ++c) {
    const float r = std::clamp(reflectance[c], 0.0f, 0.999f);
    // Gulbrandsen's n(r, g) with g = 1, and k(r, n).
    const float n = (1.0f - r) / (1.0f + r);
    const float k2 = (r * (n + 1.0f) * (n + 1.0f) - (n - 1.0f) * (n - 1.0f)) / (1.0f - r);
    eta[c] = n;
    k[c] = std::sqrt(std::max(k2, 0.0f));
  }
}

std::string_view to_string(MaterialType type) {
  switch (type) {
    case MaterialType::kDiffuse:
      return "diffuse";
    case MaterialType::kMirror:
      return "mirror";
    case MaterialType::kGlass:
      return "glass";
    case MaterialType::kRefraction:
      return "refraction";
    case MaterialType::kMicrofacet:
      return "microfacet";
    case MaterialType::kEmission:
      return "emission";
  }
  return "unknown";
}

std::string_view to_string(LightType type) {
  switch (type) {
    case LightType::kPoint:
      return "point";
    case LightType::kSpot:
      return "spot";
    case LightType::kDirectional:
      return "directional";
    case LightType::kAmbient:
      return "ambient";
    case LightType::kArea:
      return "area";
  }
  return "unknown";
}

}  // namespace prism
