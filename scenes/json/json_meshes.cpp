#include "scenes/json/json_meshes.h"

#include <cmath>
#include <utility>

#include "core/error.h"
#include "core/strings.h"
#include "scenes/mesh_file_loader.h"
#include "scenes/mesh_generator.h"

namespace prism::json {
namespace {

/// Entry `j` of tuple `i` of a vertex array, for error messages: "positions[4]" in the flat
/// form, "positions[1][1]" in the nested one.
[[noreturn]] void fail_entry(const JsonNode& array, bool flat, size_t width, size_t i, size_t j,
                             const std::string& message) {
  if (flat) array.fail_at(i * width + j, message);
  array.at(i).fail_at(j, message);
}

/// The form of a vertex array: flat ([x0, y0, z0, x1, ...]) when its first entry is a number,
/// nested ([[x0, y0, z0], ...]) otherwise. Returns the tuple count; fails on a ragged array.
size_t tuple_layout(const JsonNode& array, size_t width, bool& flat) {
  const Json& raw = array.raw();
  array.expect_array();
  flat = raw.empty() || raw[0].is_number();
  if (flat) {
    if (raw.size() % width != 0) {
      array.fail("flat array length " + std::to_string(raw.size()) + " is not a multiple of " +
                 std::to_string(width));
    }
    return raw.size() / width;
  }
  for (size_t i = 0; i < raw.size(); ++i) {
    if (!raw[i].is_array() || raw[i].size() != width) {
      array.fail_at(i, "expected an array of " + std::to_string(width) + " numbers");
    }
  }
  return raw.size();
}

/// A vertex array of `width`-tuples of finite floats, flattened.
std::vector<float> read_float_tuples(const JsonNode& array, size_t width, size_t& count) {
  bool flat = true;
  count = tuple_layout(array, width, flat);
  std::vector<float> out;
  out.reserve(count * width);
  const Json& raw = array.raw();
  for (size_t i = 0; i < count; ++i) {
    for (size_t j = 0; j < width; ++j) {
      const Json& v = flat ? raw[i * width + j] : raw[i][j];
      if (!v.is_number()) {
        fail_entry(array, flat, width, i, j,
                   std::string("expected a number, got ") + v.type_name());
      }
      const float f = v.get<float>();
      if (!std::isfinite(f)) fail_entry(array, flat, width, i, j, "number is not finite");
      out.push_back(f);
    }
  }
  return out;
}

/// Triangle corner indices, each an integer in [0, vertex_count).
std::vector<glm::uvec3> read_indices(const JsonNode& array, size_t vertex_count) {
  bool flat = true;
  const size_t count = tuple_layout(array, 3, flat);
  std::vector<glm::uvec3> out(count);
  const Json& raw = array.raw();
  for (size_t i = 0; i < count; ++i) {
    for (size_t j = 0; j < 3; ++j) {
      const Json& v = flat ? raw[i * 3 + j] : raw[i][j];
      if (!v.is_number_integer()) {
        fail_entry(array, flat, 3, i, j, "expected a vertex index (an integer)");
      }
      if (v.is_number_unsigned() ? v.get<uint64_t>() >= vertex_count : true) {
        fail_entry(array, flat, 3, i, j,
                   "vertex index " + v.dump() + " out of range (the mesh has " +
                       std::to_string(vertex_count) + " vertices)");
      }
      out[i][j] = static_cast<uint32_t>(v.get<uint64_t>());
    }
  }
  return out;
}

TriangleMesh read_inline_mesh(const JsonNode& node) {
  TriangleMesh mesh;
  size_t vertex_count = 0;
  const std::vector<float> p = read_float_tuples(node.child("positions"), 3, vertex_count);
  if (vertex_count >= std::numeric_limits<uint32_t>::max()) {
    node.child("positions").fail("too many vertices for 32-bit indices");
  }
  mesh.positions.reserve(vertex_count + 1);  // +1: Embree's padding (TriangleMesh::finalize)
  for (size_t i = 0; i < vertex_count; ++i)
    mesh.positions.emplace_back(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
  mesh.triangles = read_indices(node.child("indices"), vertex_count);
  if (mesh.triangles.empty()) node.child("indices").fail("a mesh needs at least one triangle");
  // Per-vertex attributes in the file, per-corner in TriangleMesh.
  if (const auto normals = node.find("normals")) {
    size_t n = 0;
    const std::vector<float> v = read_float_tuples(*normals, 3, n);
    if (n != vertex_count) {
      normals->fail("expected one normal per vertex (" + std::to_string(vertex_count) + "), got " +
                    std::to_string(n));
    }
    mesh.normals.reserve(3 * mesh.triangles.size());
    for (const auto& t : mesh.triangles) {
      for (int c = 0; c < 3; ++c)
        mesh.normals.emplace_back(v[3 * t[c]], v[3 * t[c] + 1], v[3 * t[c] + 2]);
    }
  }
  if (const auto uvs = node.find("uvs")) {
    size_t n = 0;
    const std::vector<float> v = read_float_tuples(*uvs, 2, n);
    if (n != vertex_count) {
      uvs->fail("expected one uv per vertex (" + std::to_string(vertex_count) + "), got " +
                std::to_string(n));
    }
    mesh.uvs.reserve(3 * mesh.triangles.size());
    for (const auto& t : mesh.triangles) {
      for (int c = 0; c < 3; ++c) mesh.uvs.emplace_back(v[2 * t[c]], v[2 * t[c] + 1]);
    }
  }
  return mesh;
}

TriangleMesh read_file_mesh(const JsonNode& node, const std::filesystem::path& base_dir) {
  const JsonNode file = node.child("file");
  const std::string name = file.string();
  if (name.empty()) file.fail("mesh file path is empty");
  const std::filesystem::path path = base_dir / std::filesystem::path(name);
  try {
    return load_mesh_file(path);
  } catch (const Error& e) {
    throw Error(e.kind(), "mesh file '" + path.string() + "': " + e.message(),
                file.document().locate(file.path()));
  }
}

TriangleMesh read_generated_mesh(const JsonNode& node) {
  const JsonNode gen = node.child("generate");
  gen.check_keys({"kind", "triangles", "seed"});
  const JsonNode kind_node = gen.child("kind");
  GeneratedMeshKind kind{};
  try {
    kind = parse_generated_mesh_kind(kind_node.string());
  } catch (const Error& e) {
    kind_node.fail(e.message());
  }
  const int64_t triangles = gen.child("triangles").integer(1, kMaxGeneratedTriangles);
  const auto seed_node = gen.find("seed");
  const uint64_t seed = seed_node ? seed_node->unsigned_integer() : 1;
  return generate_mesh(kind, static_cast<size_t>(triangles), seed);
}

}  // namespace

void MaterialNames::add(const std::string& name, uint32_t id, const JsonNode& where) {
  if (name.empty()) where.fail("material name is empty");
  if (!ids_.emplace(name, id).second) where.fail("duplicate material name '" + name + "'");
  names_.push_back(name);
}

uint32_t MaterialNames::resolve(const JsonNode& reference) const {
  const std::string name = reference.string();
  const auto it = ids_.find(name);
  if (it != ids_.end()) return it->second;
  reference.fail("unknown material '" + name +
                 "'; defined materials: " + join(names_, ", ", "(none)"));
}

TriangleMesh read_mesh(const JsonNode& node, const MaterialNames& materials,
                       const std::filesystem::path& base_dir, const std::string& default_name) {
  node.expect_object();
  const int sources =
      int(node.has("positions")) + int(node.has("file")) + int(node.has("generate"));
  if (sources != 1) {
    node.fail("a mesh needs exactly one of 'positions' (+ 'indices'), 'file' or 'generate'");
  }
  // Keys and the material first: a typo should not wait for a large file to load.
  if (node.has("positions")) {
    node.check_keys({"name", "material", "positions", "indices", "normals", "uvs", "transform"});
  } else if (node.has("file")) {
    node.check_keys({"name", "material", "file", "transform"});
  } else {
    node.check_keys({"name", "material", "generate", "transform"});
  }
  const uint32_t material_id = materials.resolve(node.child("material"));
  TriangleMesh mesh = node.has("positions") ? read_inline_mesh(node)
                      : node.has("file")    ? read_file_mesh(node, base_dir)
                                            : read_generated_mesh(node);
  mesh.material_id = material_id;
  const auto name = node.find("name");
  mesh.name = name ? name->string() : default_name;
  if (const auto transform = node.find("transform")) {
    transform_mesh(read_transform(*transform), mesh);
    for (const Vec3& p : mesh.positions) {
      if (!is_finite(p)) transform->fail("transformed vertex position is not finite");
    }
  }
  return mesh;
}

Mat4 read_transform(const JsonNode& node) {
  node.check_keys({"translate", "rotate", "scale", "matrix"});
  Mat4 m(1.0f);
  if (const auto matrix = node.find("matrix")) {
    if (node.raw().size() != 1) {
      node.fail("'matrix' cannot be combined with 'translate', 'rotate' or 'scale'");
    }
    if (!matrix->raw().is_array() || matrix->raw().size() != 16) {
      matrix->fail("expected 16 numbers (a 4x4 matrix, row by row)");
    }
    for (int row = 0; row < 4; ++row) {
      for (int col = 0; col < 4; ++col) m[col][row] = matrix->at(4 * row + col).number();
    }
    if (m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f) {
      matrix->fail("the last row must be 0 0 0 1 (an affine transform)");
    }
  } else {
    if (const auto t = node.find("translate")) m = glm::translate(m, t->vec3());
    if (const auto r = node.find("rotate")) {
      r->check_keys({"axis", "degrees"});
      const Vec3 axis = r->child("axis").direction();
      m = glm::rotate(m, radians(r->child("degrees").number()), axis);
    }
    if (const auto s = node.find("scale")) {
      const Vec3 scale = s->raw().is_number() ? Vec3(s->number()) : s->vec3();
      if (scale.x == 0.0f || scale.y == 0.0f || scale.z == 0.0f) s->fail("scale must not be 0");
      m = glm::scale(m, scale);
    }
  }
  const float det = glm::determinant(glm::mat3(m));
  if (!(std::abs(det) > 0.0f) || !std::isfinite(det)) node.fail("transform is not invertible");
  return m;
}

void transform_mesh(const Mat4& m, TriangleMesh& mesh) {
  for (Vec3& p : mesh.positions) p = Vec3(m * Vec4(p, 1.0f));
  const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(m)));
  for (Vec3& n : mesh.normals) {
    const Vec3 t = normal_matrix * n;
    const float length = glm::length(t);
    n = length > 0.0f ? t / length : t;
  }
  if (glm::determinant(glm::mat3(m)) < 0.0f) {
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
      std::swap(mesh.triangles[i].y, mesh.triangles[i].z);
      if (!mesh.normals.empty()) std::swap(mesh.normals[3 * i + 1], mesh.normals[3 * i + 2]);
      if (!mesh.uvs.empty()) std::swap(mesh.uvs[3 * i + 1], mesh.uvs[3 * i + 2]);
    }
  }
}

}  // namespace prism::json
