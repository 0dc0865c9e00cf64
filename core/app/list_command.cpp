// `prism list`: every table of names the command line accepts.

#include <fmt/format.h>

#include "accel/accelerator.h"
#include "core/app/commands.h"
#include "core/samplers.h"
#include "integrators/integrator.h"
#include "scenes/mesh_generator.h"

namespace prism {
namespace {

template <typename Interface>
void print_registry(const std::string& title, const Registry<Interface>& registry) {
  fmt::print("{}:\n", title);
  for (const auto& entry : registry.entries()) {
    fmt::print("  {:<14} {}\n", entry.name, entry.description);
  }
}

struct Row {
  const char* name;
  const char* description;
};

void print_rows(const std::string& title, std::initializer_list<Row> rows) {
  fmt::print("{}:\n", title);
  for (const auto& row : rows) fmt::print("  {:<14} {}\n", row.name, row.description);
}

}  // namespace

int run_list_command() {
  print_registry("accelerators (--accel)", accelerator_registry());
  print_registry("integrators (--integrator)", integrator_registry());
  print_registry("samplers (--sampler)", sampler_registry());
  print_rows("scene formats (by extension)",
             {{".dae", "CS184 COLLADA 1.4.1 with the CGL profile"},
              {".json", "prism's native JSON scene format"},
              {".obj .ply .stl", "a model file through Assimp, framed and lit as a scene"},
              {".gltf .glb .fbx",
               "a model file through Assimp, with its materials, textures, "
               "lights and camera"}});
  // Names come from the generator's own to_string(), so they match what its parser accepts.
  const std::initializer_list<std::pair<GeneratedMeshKind, const char*>> kinds = {
      {GeneratedMeshKind::kSphere, "tessellated UV sphere of radius 1"},
      {GeneratedMeshKind::kNoisySphere, "the sphere with vertices moved radially by noise"},
      {GeneratedMeshKind::kSoup, "independent random triangles in [-1,1]^3"},
      {GeneratedMeshKind::kSlivers, "long thin triangles (aspect ~1000:1)"},
      {GeneratedMeshKind::kGrid, "flat grid in the z=0 plane sharing edges and vertices"},
      {GeneratedMeshKind::kFoldedSlivers, "pairs of thin triangles folded along a long edge"},
      {GeneratedMeshKind::kInterior, "rooms with walls, floors and furniture (sizes mixed)"},
  };
  fmt::print("generated meshes:\n");
  for (const auto& [kind, description] : kinds) {
    fmt::print("  {:<14} {}\n", to_string(kind), description);
  }
  print_rows("output formats (by extension of --output)",
             {{".exr",
               "scene-linear OpenEXR in the output colour space (--exr-type, "
               "--exr-compression)"},
              {".png", "display-referred 8-bit through the OCIO display/view (--display, --view)"},
              {".jpg .jpeg", "display-referred 8-bit, as .png"},
              {".tif .tiff", "display-referred 8-bit, as .png"}});
  return kExitSuccess;
}

}  // namespace prism
