#include "scenes/collada/geometry.h"

#include <algorithm>
#include <cmath>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "scenes/collada/transforms.h"

namespace prism::collada {
namespace {

constexpr uint32_t kUnused = UINT32_MAX;

uint64_t required_uint(const Document& doc, pugi::xml_node element, const char* name) {
  if (!element.attribute(name)) doc.fail(element, std::string("missing attribute '") + name + "'");
  return doc.uint_attribute(element, name, 0);
}

// The elements of a <source> read through its <accessor>: `components` floats per element.
// Everything is checked against the numbers actually present before anything is allocated.
std::vector<float> read_source(const Document& doc, pugi::xml_node source, unsigned components,
                               size_t* element_count) {
  const pugi::xml_node common = doc.require_child(source, "technique_common");
  const pugi::xml_node accessor = doc.require_child(common, "accessor");
  const pugi::xml_node array = doc.resolve(accessor, "source", "float_array");
  std::vector<float> values = doc.floats(array);
  if (array.attribute("count")) {
    // The homework reads exactly `count` numbers from the text: fewer than it holds leaves the
    // rest unread; more repeats the last one, which no index may then use (the accessor and
    // index checks below are against the numbers present). The count is never trusted for
    // an allocation.
    const uint64_t declared = doc.uint_attribute(array, "count", 0);
    const std::string mismatch = "count=\"" + std::to_string(declared) +
                                 "\" but the element holds " + std::to_string(values.size()) +
                                 " numbers; ";
    if (declared < values.size()) {
      doc.warn(array, mismatch + "only the first " + std::to_string(declared) +
                          " are read, as the CS184 homework does");
      values.resize(declared);
    } else if (declared > values.size()) {
      doc.warn(array, mismatch + "the " + std::to_string(values.size()) +
                          " present are read, as the CS184 homework reads them, and nothing may "
                          "use more");
    }
  }
  const uint64_t count = required_uint(doc, accessor, "count");
  const uint64_t stride = doc.uint_attribute(accessor, "stride", 1);
  const uint64_t offset = doc.uint_attribute(accessor, "offset", 0);
  if (stride < components) {
    doc.fail(accessor, "stride " + std::to_string(stride) + " is too small for " +
                           std::to_string(components) + " components per element");
  }
  const uint64_t size = values.size();
  // offset + (count - 1) * stride + components <= size, written so nothing can overflow.
  const bool fits = count == 0 || (offset <= size && components <= size - offset &&
                                   count - 1 <= (size - offset - components) / stride);
  if (!fits) {
    doc.fail(accessor, "count=" + std::to_string(count) + " stride=" + std::to_string(stride) +
                           " offset=" + std::to_string(offset) + " reads past the end of " +
                           describe(array) + " (" + std::to_string(size) + " numbers)");
  }
  std::vector<float> out;
  out.reserve(count * components);
  for (uint64_t i = 0; i < count; ++i) {
    for (unsigned k = 0; k < components; ++k) out.push_back(values[offset + i * stride + k]);
  }
  *element_count = count;
  return out;
}

std::vector<Vec3> read_vec3_source(const Document& doc, pugi::xml_node source) {
  size_t n = 0;
  const std::vector<float> v = read_source(doc, source, 3, &n);
  std::vector<Vec3> out(n);
  for (size_t i = 0; i < n; ++i) out[i] = Vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
  return out;
}

std::vector<Vec2> read_vec2_source(const Document& doc, pugi::xml_node source) {
  size_t n = 0;
  const std::vector<float> v = read_source(doc, source, 2, &n);
  std::vector<Vec2> out(n);
  for (size_t i = 0; i < n; ++i) out[i] = Vec2(v[2 * i], v[2 * i + 1]);
  return out;
}

// Parses each <source> once per geometry, however many primitive groups use it.
class SourceCache {
 public:
  SourceCache(const Document& doc, Geometry& geometry) : doc_(doc), geometry_(geometry) {}

  int normals(pugi::xml_node source) {
    return lookup(normal_keys_, source, geometry_.normal_sources,
                  [&] { return read_vec3_source(doc_, source); });
  }
  int uvs(pugi::xml_node source) {
    return lookup(uv_keys_, source, geometry_.uv_sources,
                  [&] { return read_vec2_source(doc_, source); });
  }

 private:
  template <typename T, typename Read>
  int lookup(std::unordered_map<size_t, int>& keys, pugi::xml_node source, std::vector<T>& store,
             Read read) {
    const auto it = keys.find(source.hash_value());
    if (it != keys.end()) return it->second;
    store.push_back(read());
    const int index = static_cast<int>(store.size() - 1);
    keys.emplace(source.hash_value(), index);
    return index;
  }

  const Document& doc_;
  Geometry& geometry_;
  std::unordered_map<size_t, int> normal_keys_, uv_keys_;  // xml_node::hash_value()
};

struct Input {
  pugi::xml_node element;
  uint32_t offset = 0;
};

// Shared-vertex attributes a <vertices> element may carry besides POSITION.
struct VertexAttributes {
  int normal_source = -1;
  int uv_source = -1;
};

void parse_group(const Document& doc, pugi::xml_node element, bool polylist,
                 pugi::xml_node vertices, const VertexAttributes& vertex_attributes,
                 SourceCache& cache, Geometry& geometry) {
  PrimitiveGroup group;
  group.element = element;
  group.material_symbol = element.attribute("material").value();
  Input vertex, normal, uv;
  uint64_t stride = 0;
  for (pugi::xml_node input : element.children("input")) {
    const uint64_t offset = required_uint(doc, input, "offset");
    if (offset >= UINT32_MAX) doc.fail(input, "offset is too large");
    stride = std::max(stride, offset + 1);
    const std::string_view semantic = input.attribute("semantic").value();
    Input* slot = semantic == "VERTEX"     ? &vertex
                  : semantic == "NORMAL"   ? &normal
                  : semantic == "TEXCOORD" ? &uv
                                           : nullptr;
    if (slot && !slot->element) *slot = Input{input, static_cast<uint32_t>(offset)};
  }
  if (!vertex.element) doc.fail(element, "missing <input semantic=\"VERTEX\">");
  if (doc.resolve(vertex.element, "source", "vertices") != vertices) {
    doc.fail(vertex.element, "the VERTEX input must name the <vertices> of its own <mesh>");
  }
  if (normal.element) {
    group.normal_source = cache.normals(doc.resolve(normal.element, "source", "source"));
  }
  if (uv.element) group.uv_source = cache.uvs(doc.resolve(uv.element, "source", "source"));

  const pugi::xml_node p_element = element.child("p");
  const std::vector<uint32_t> p = doc.indices(p_element);
  const pugi::xml_node p_where = p_element ? p_element : element;
  std::vector<uint32_t> polygon_sizes;
  const pugi::xml_node vcount_element = element.child("vcount");
  if (polylist) {
    polygon_sizes = doc.indices(vcount_element);
  } else {
    if (p.size() % (3 * stride) != 0) {
      doc.fail(p_where, "<p> holds " + std::to_string(p.size()) +
                            " indices, not a multiple of 3 corners x " + std::to_string(stride) +
                            " inputs");
    }
    polygon_sizes.assign(p.size() / (3 * stride), 3);
  }
  const uint64_t declared = doc.uint_attribute(element, "count", polygon_sizes.size());
  if (declared != polygon_sizes.size()) {
    doc.fail(element, "count=\"" + std::to_string(declared) + "\" but the element holds " +
                          std::to_string(polygon_sizes.size()) +
                          (polylist ? " <vcount> entries" : " triangles"));
  }
  uint64_t corners = 0;
  for (size_t i = 0; i < polygon_sizes.size(); ++i) {
    if (polygon_sizes[i] < 3) {
      doc.fail_at_line(vcount_element, doc.token_line(vcount_element, i),
                       "polygon " + std::to_string(i) + " has " + std::to_string(polygon_sizes[i]) +
                           " corners; at least 3 are needed");
    }
    corners += polygon_sizes[i];
  }
  if (corners > p.size() / stride || corners * stride != p.size()) {
    doc.fail(p_where, "<p> holds " + std::to_string(p.size()) + " indices but <vcount> needs " +
                          std::to_string(corners) + " corners x " + std::to_string(stride) +
                          " inputs");
  }

  // Every index must address an element of its source.
  const auto check = [&](const Input& input, size_t limit, const char* semantic) {
    for (uint64_t c = 0; c < corners; ++c) {
      const size_t at = c * stride + input.offset;
      if (p[at] >= limit) {
        doc.fail_at_line(p_where, doc.token_line(p_element, at),
                         "index " + std::to_string(p[at]) + " of input " + semantic +
                             " is out of range: " + std::to_string(limit) + " elements");
      }
    }
  };
  check(vertex, geometry.positions.size(), "VERTEX");
  if (normal.element) check(normal, geometry.normal_sources[group.normal_source].size(), "NORMAL");
  if (uv.element) check(uv, geometry.uv_sources[group.uv_source].size(), "TEXCOORD");

  const uint64_t triangles = corners - 2 * polygon_sizes.size();
  const bool vertex_normals = !normal.element && vertex_attributes.normal_source >= 0;
  const bool vertex_uvs = !uv.element && vertex_attributes.uv_source >= 0;
  if (vertex_normals) group.normal_source = vertex_attributes.normal_source;
  if (vertex_uvs) group.uv_source = vertex_attributes.uv_source;
  group.positions.reserve(3 * triangles);
  if (group.normal_source >= 0) group.normals.reserve(3 * triangles);
  if (group.uv_source >= 0) group.uvs.reserve(3 * triangles);
  const auto emit = [&](uint64_t c) {
    const uint32_t v = p[c * stride + vertex.offset];
    group.positions.push_back(v);
    if (group.normal_source >= 0) {
      group.normals.push_back(vertex_normals ? v : p[c * stride + normal.offset]);
    }
    if (group.uv_source >= 0) group.uvs.push_back(vertex_uvs ? v : p[c * stride + uv.offset]);
  };
  uint64_t first = 0;
  for (const uint32_t n : polygon_sizes) {
    for (uint32_t k = 1; k + 1 < n; ++k) {
      emit(first);
      emit(first + k);
      emit(first + k + 1);
    }
    first += n;
  }
  geometry.groups.push_back(std::move(group));
}

void parse_mesh(const Document& doc, pugi::xml_node mesh, Geometry& geometry) {
  const pugi::xml_node vertices = doc.require_child(mesh, "vertices");
  SourceCache cache(doc, geometry);
  VertexAttributes attributes;
  pugi::xml_node position_input;
  for (pugi::xml_node input : vertices.children("input")) {
    const std::string_view semantic = input.attribute("semantic").value();
    if (semantic == "POSITION" && !position_input) {
      position_input = input;
    } else if (semantic == "NORMAL" && attributes.normal_source < 0) {
      attributes.normal_source = cache.normals(doc.resolve(input, "source", "source"));
    } else if (semantic == "TEXCOORD" && attributes.uv_source < 0) {
      attributes.uv_source = cache.uvs(doc.resolve(input, "source", "source"));
    }
  }
  if (!position_input) doc.fail(vertices, "missing <input semantic=\"POSITION\">");
  geometry.positions = read_vec3_source(doc, doc.resolve(position_input, "source", "source"));
  // Shared-vertex attributes are indexed by the vertex index, so they must cover every vertex.
  const auto covers = [&](size_t size) { return size >= geometry.positions.size(); };
  if ((attributes.normal_source >= 0 &&
       !covers(geometry.normal_sources[attributes.normal_source].size())) ||
      (attributes.uv_source >= 0 && !covers(geometry.uv_sources[attributes.uv_source].size()))) {
    doc.fail(vertices, "a per-vertex NORMAL or TEXCOORD source has fewer elements than POSITION");
  }
  for (pugi::xml_node child = mesh.first_child(); child; child = child.next_sibling()) {
    const std::string_view name = child.name();
    if (name == "polylist" || name == "triangles") {
      parse_group(doc, child, name == "polylist", vertices, attributes, cache, geometry);
    } else if (name == "polygons" || name == "tristrips" || name == "trifans") {
      std::string message(1, '<');
      message.append(name).append("> is not supported; export as <polylist> or <triangles>");
      doc.fail(child, message);
    }
    // <lines> and <linestrips> have no surface to render.
  }
}

}  // namespace

size_t Geometry::triangle_count() const {
  size_t n = 0;
  for (const auto& g : groups) n += g.triangle_count();
  return n;
}

Geometry parse_geometry(const Document& doc, pugi::xml_node element) {
  Geometry geometry;
  geometry.element = element;
  geometry.id = element.attribute("id").value();
  if (const pugi::xml_node mesh = element.child("mesh")) {
    parse_mesh(doc, mesh, geometry);
    return geometry;
  }
  const pugi::xml_node sphere = find_extra_technique(element, "CGL").child("sphere");
  if (!sphere) {
    doc.fail(element, "geometry has neither a <mesh> nor a CGL <sphere>");
  }
  const pugi::xml_node radius = doc.require_child(sphere, "radius");
  const double r = doc.scalar(radius);
  if (!(r > 0.0))
    doc.fail(radius, "sphere radius must be positive, found " + quote(trimmed_text(radius)));
  geometry.is_sphere = true;
  geometry.radius = static_cast<float>(r);
  return geometry;
}

void append_mesh_instance(const Geometry& geometry, const DMat4& world,
                          std::span<const uint32_t> material_ids, const std::string& name_prefix,
                          SceneGeometry& out) {
  const glm::dmat3 to_normal = normal_matrix(world);
  const bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
  std::vector<uint32_t> remap(geometry.positions.size(), kUnused);
  std::vector<uint32_t> touched;
  for (size_t g = 0; g < geometry.groups.size(); ++g) {
    const PrimitiveGroup& group = geometry.groups[g];
    TriangleMesh mesh;
    mesh.name =
        name_prefix + "/" +
        (group.material_symbol.empty() ? "primitives" + std::to_string(g) : group.material_symbol);
    mesh.material_id = material_ids[g];
    const size_t triangles = group.triangle_count();
    mesh.triangles.reserve(triangles);
    if (group.normal_source >= 0) mesh.normals.reserve(3 * triangles);
    if (group.uv_source >= 0) mesh.uvs.reserve(3 * triangles);
    touched.clear();
    for (size_t t = 0; t < triangles; ++t) {
      size_t corner[3] = {3 * t, 3 * t + 1, 3 * t + 2};
      if (mirrored) std::swap(corner[1], corner[2]);
      glm::uvec3 tri;
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = group.positions[corner[k]];
        if (remap[v] == kUnused) {
          remap[v] = static_cast<uint32_t>(mesh.positions.size());
          touched.push_back(v);
          mesh.positions.push_back(Vec3(transform_point(world, DVec3(geometry.positions[v]))));
        }
        tri[k] = remap[v];
      }
      mesh.triangles.push_back(tri);
      if (group.normal_source >= 0) {
        const std::vector<Vec3>& source = geometry.normal_sources[group.normal_source];
        const Vec3& p0 = mesh.positions[tri[0]];
        Vec3 geometric = glm::cross(mesh.positions[tri[1]] - p0, mesh.positions[tri[2]] - p0);
        const float length = glm::length(geometric);
        geometric = length > 0.0f && std::isfinite(length) ? geometric / length : kWorldUp;
        for (int k = 0; k < 3; ++k) {
          const DVec3 n = to_normal * DVec3(source[group.normals[corner[k]]]);
          const double n_length = glm::length(n);
          const bool usable = n_length > 0.0 && std::isfinite(n_length);
          mesh.normals.push_back(usable ? Vec3(n / n_length) : geometric);
        }
      }
      if (group.uv_source >= 0) {
        const std::vector<Vec2>& source = geometry.uv_sources[group.uv_source];
        for (int k = 0; k < 3; ++k) mesh.uvs.push_back(source[group.uvs[corner[k]]]);
      }
    }
    for (const uint32_t v : touched) remap[v] = kUnused;
    out.meshes.push_back(std::move(mesh));
  }
}

}  // namespace prism::collada
