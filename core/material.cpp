#include "core/material.h"
#include "core/light.h"

namespace prism {

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
