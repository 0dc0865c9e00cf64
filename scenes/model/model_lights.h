#pragma once

// The lights of a model file, and the default lighting of models that have none
// (docs/SCENE_FORMAT.md, "Model files").

#include <filesystem>
#include <string>
#include <vector>

#include "core/scene.h"
#include "scenes/model/model_geometry.h"
#include "scenes/model/model_view.h"

struct aiScene;

namespace prism::model {

/// Radiance of the default lighting's ambient sky.
inline constexpr float kDefaultSkyRadiance = 0.4f;
/// Irradiance of the default lighting's directional key light, at normal incidence: 0.6 pi,
/// so that a white Lambertian surface facing it reflects a radiance of 0.6, and one lit by both
/// the key and the open sky 1.0.
inline constexpr float kDefaultKeyIrradiance = 0.6f * kPi;

/// The lights of `scene` in world space (their nodes' transforms applied): point, spot,
/// directional, ambient and area lights with Assimp's diffuse colour as their colour and its
/// attenuation (inverse square when it gives none); a spot light's cone is Assimp's outer cone
/// angle, the full angle, except in glTF files, whose half angle Assimp 5.2 passes on
/// unchanged. Lights of other types, or whose transform collapses them, are skipped with a
/// warning in `warnings`.
std::vector<Light> model_lights(const aiScene& scene, const NodeTransforms& transforms,
                                const ModelAxes& axes, const std::filesystem::path& file,
                                std::vector<std::string>& warnings);

/// Whether `scene` is lit: it has a light with a colour other than black, or an emissive mesh.
bool has_lighting(const Scene& scene);

/// Adds the default lighting to `scene` and says so in its warnings: an ambient sky of
/// radiance kDefaultSkyRadiance about axes.up, and a directional key light of irradiance
/// kDefaultKeyIrradiance arriving from up + 0.8 front + 0.5 right (normalised): above, in
/// front and to the right of the model, over the default camera's right shoulder.
void add_default_lighting(Scene& scene, const ModelAxes& axes, const std::filesystem::path& file);

}  // namespace prism::model
