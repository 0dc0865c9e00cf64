#include "scenes/model/model_lights.h"

#include <assimp/light.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/strings.h"

namespace prism::model {
namespace {

Vec3 to_vec3(const aiVector3D& v) { return {v.x, v.y, v.z}; }

/// `v` transformed as a direction and normalised, or nothing when it collapses.
std::optional<Vec3> direction(const Mat4& m, const Vec3& v) {
  const Vec3 d(m * Vec4(v, 0.0f));
  const float length = glm::length(d);
  if (!(length > 0.0f) || !std::isfinite(length)) return std::nullopt;
  return d / length;
}

}  // namespace

std::vector<Light> model_lights(const aiScene& scene, const NodeTransforms& transforms,
                                const ModelAxes& axes, const std::filesystem::path& file,
                                std::vector<std::string>& warnings) {
  const std::string ext = lower_case_extension(file);
  const bool gltf = ext == ".gltf" || ext == ".glb";
  std::vector<Light> lights;
  for (unsigned i = 0; i < scene.mNumLights; ++i) {
    const aiLight& in = *scene.mLights[i];
    const auto skip = [&](const std::string& why) {
      warnings.push_back(fmt::format("{}: light '{}': {}; the light is left out", file.string(),
                                     in.mName.C_Str(), why));
    };
    const auto node = transforms.find(in.mName.C_Str());
    const Mat4 m = node != transforms.end() ? node->second : Mat4(1.0f);
    Light light;
    light.name = in.mName.C_Str();
    light.color =
        glm::max(Rgb(in.mColorDiffuse.r, in.mColorDiffuse.g, in.mColorDiffuse.b), Rgb(0.0f));
    if (!is_finite(light.color)) {
      skip("its colour is not finite");
      continue;
    }
    light.up = axes.up;
    light.position = Vec3(m * Vec4(to_vec3(in.mPosition), 1.0f));
    const std::optional<Vec3> dir = direction(m, to_vec3(in.mDirection));
    light.direction = dir.value_or(-axes.up);
    light.constant_attenuation = std::max(0.0f, in.mAttenuationConstant);
    light.linear_attenuation = std::max(0.0f, in.mAttenuationLinear);
    light.quadratic_attenuation = std::max(0.0f, in.mAttenuationQuadratic);
    if (!(light.constant_attenuation + light.linear_attenuation + light.quadratic_attenuation >
          0.0f)) {
      light.constant_attenuation = light.linear_attenuation = 0.0f;
      light.quadratic_attenuation = 1.0f;
    }
    if (!is_finite(light.position)) {
      skip("its transform is not finite");
      continue;
    }
    switch (in.mType) {
      case aiLightSource_POINT:
        light.type = LightType::kPoint;
        break;
      case aiLightSource_SPOT: {
        light.type = LightType::kSpot;
        const float full = (gltf ? 2.0f : 1.0f) * in.mAngleOuterCone;
        light.falloff_angle_deg = std::clamp(glm::degrees(full), 1e-3f, 180.0f);
        if (!std::isfinite(light.falloff_angle_deg)) light.falloff_angle_deg = 180.0f;
        if (!dir) {
          skip("its direction collapses");
          continue;
        }
        break;
      }
      case aiLightSource_DIRECTIONAL:
        light.type = LightType::kDirectional;
        if (!dir) {
          skip("its direction collapses");
          continue;
        }
        break;
      case aiLightSource_AMBIENT:
        light.type = LightType::kAmbient;
        break;
      case aiLightSource_AREA: {
        light.type = LightType::kArea;
        const Vec3 up_local = to_vec3(in.mUp);
        const Vec3 across_local = glm::cross(up_local, to_vec3(in.mDirection));
        light.edge_u = Vec3(m * Vec4(in.mSize.x * glm::normalize(across_local), 0.0f));
        light.edge_v = Vec3(m * Vec4(in.mSize.y * glm::normalize(up_local), 0.0f));
        const Vec3 normal = glm::cross(light.edge_u, light.edge_v);
        const float area = glm::length(normal);
        if (!dir || !(area > 0.0f) || !std::isfinite(area)) {
          skip("its size or direction collapses");
          continue;
        }
        // Emitting along the file's direction: swap the edges when their normal disagrees.
        if (glm::dot(normal, *dir) < 0.0f) std::swap(light.edge_u, light.edge_v);
        light.direction = *dir;
        break;
      }
      default:
        skip("its type is not one prism knows");
        continue;
    }
    lights.push_back(light);
  }
  return lights;
}

bool has_lighting(const Scene& scene) {
  for (const Light& light : scene.lights) {
    if (max_component(light.color) > 0.0f) return true;
  }
  for (const TriangleMesh& mesh : scene.geometry.meshes) {
    const Material& m = scene.materials[mesh.material_id];
    if (m.is_emissive() && max_component(m.radiance) > 0.0f) return true;
  }
  return false;
}

void add_default_lighting(Scene& scene, const ModelAxes& axes, const std::filesystem::path& file) {
  Light sky;
  sky.name = "prism default sky";
  sky.type = LightType::kAmbient;
  sky.color = Rgb(kDefaultSkyRadiance);
  sky.up = axes.up;
  Light key;
  key.name = "prism default key light";
  key.type = LightType::kDirectional;
  key.color = Rgb(kDefaultKeyIrradiance);
  const Vec3 from = glm::normalize(axes.up + 0.8f * axes.front + 0.5f * axes.right);
  key.direction = -from;
  key.up = axes.up;
  scene.lights.push_back(sky);
  scene.lights.push_back(key);
  scene.warnings.push_back(fmt::format(
      "{}: the file has no lights and no emissive surfaces: added prism's default lighting, an "
      "ambient sky of radiance {:g} about ({:g}, {:g}, {:g}) and a directional key light of "
      "irradiance {:.4g} from ({:.3g}, {:.3g}, {:.3g}) (docs/SCENE_FORMAT.md, \"Model files\")",
      file.string(), kDefaultSkyRadiance, axes.up.x, axes.up.y, axes.up.z, kDefaultKeyIrradiance,
      from.x, from.y, from.z));
}

}  // namespace prism::model
