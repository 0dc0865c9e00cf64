#pragma once

#include <vector>

#include <pugixml.hpp>

#include "core/light.h"
#include "core/material.h"
#include "core/scene_geometry.h"
#include "scenes/collada/document.h"

namespace prism::collada {

/// Converts the <light> named by `instance` (an <instance_light>) into a world-space Light,
/// placed by its node's `world` transform: in its own frame a light sits at the origin, points
/// down -Z, and (CGL area lights) spans the unit square of X and Y centred on the origin, so the
/// node's scale gives the area light's edges. The CGL <extra> overrides technique_common. Every
/// light's `up` is the world up axis (+Z). Throws Error(kInput) naming the element on unknown
/// types, bad values, or a transform that collapses the light.
Light parse_light(const Document& doc, pugi::xml_node instance, const DMat4& world);

/// The Cornell boxes carry both a CGL area light and an emissive `light` quad at the same place.
/// The emissive mesh is the emitter; an area light that coincides with an emissive mesh gets
/// duplicates_emissive_mesh = true, so it adds no energy of its own. "Coincides" means: areas
/// within 1%; facing the same way (cosine between the light's direction and the mesh's
/// area-weighted normal, oriented by its shading normals, >= 0.99); centres within
/// max(1e-3 x the scene's bounding-box diagonal, 1% of sqrt(light area)). The second term is
/// needed because Blender exported CBspheres' light quad 4.3 mm off the area light's centre:
/// 1e-3 of the 3.2 m box alone would miss it and double the light.
void mark_duplicate_area_lights(std::vector<Light>& lights, const SceneGeometry& geometry,
                                const std::vector<Material>& materials);

}  // namespace prism::collada
