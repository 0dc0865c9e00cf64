#pragma once

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <pugixml.hpp>

#include "core/material.h"
#include "scenes/collada/document.h"

namespace prism::collada {

/// Converts one <material> to a prism Material through its <instance_effect>. The effect's CGL
/// <extra> decides the type when present (its first child: emission, mirror, glass, refraction
/// or microfacet, with the parameters of docs/cs184-collada.md); otherwise the diffuse colour
/// of profile_COMMON's phong, lambert or blinn technique is a Lambertian reflectance; otherwise
/// 0.5 grey. Throws Error(kInput) on a dangling effect, an unknown CGL type or a bad value.
Material parse_material(const Document& doc, pugi::xml_node material);

/// The scene's material list, filled on demand so that each <material> becomes one Material,
/// in the order the scene first uses them.
class MaterialTable {
 public:
  MaterialTable(const Document& doc, std::vector<Material>& materials)
      : doc_(doc), materials_(materials) {}

  /// Index of the Material made from <material> element `material`.
  uint32_t index_of(pugi::xml_node material);
  /// Index of the 0.5 grey Lambertian used where nothing is bound (named "default").
  uint32_t default_index();

 private:
  const Document& doc_;
  std::vector<Material>& materials_;
  std::unordered_map<size_t, uint32_t> indices_;  // keyed by xml_node::hash_value()
  int64_t default_ = -1;
};

}  // namespace prism::collada
