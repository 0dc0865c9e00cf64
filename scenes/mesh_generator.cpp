#include "scenes/mesh_generator.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/sampler.h"

namespace prism {
namespace {

/// Counter-based random numbers: value (index, dimension) depends only on the seed and the
/// counter, so the mesh is the same whatever the order of generation or the standard library.
class CounterRng {
 public:
  CounterRng(uint64_t seed, GeneratedMeshKind kind)
      : key_(mix_bits(seed ^ mix_bits(0x9e3779b97f4a7c15ULL + static_cast<uint64_t>(kind)))) {}

  /// Uniform in [0, 1) for (index, dimension); up to 16 dimensions per index.
  float unit(uint64_t index, uint32_t dimension) const {
    return bits_to_unit_float(static_cast<uint32_t>(mix_bits(key_ + index * 16 + dimension) >> 32));
  }
  /// Uniform in [lo, hi).
  float uniform(uint64_t index, uint32_t dimension, float lo, float hi) const {
    return lo + (hi - lo) * unit(index, dimension);
  }

 private:
  uint64_t key_;
};

/// Positions get one spare slot so that TriangleMesh::finalize() (Embree's padding) never has to
/// reallocate a 10M-triangle array.
void reserve_mesh(TriangleMesh& mesh, size_t vertices, size_t triangles) {
  mesh.positions.reserve(vertices + 1);
  mesh.triangles.reserve(triangles);
}

glm::uvec3 tri(size_t a, size_t b, size_t c) {
  return {static_cast<uint32_t>(a), static_cast<uint32_t>(b), static_cast<uint32_t>(c)};
}

/// Radial displacement of the noisy sphere: a few random low-frequency waves (smooth bumps a
/// renderer shows as a lumpy surface) plus a small per-vertex jitter (breaks the symmetry that
/// makes ties between neighbouring triangles exact).
class SphereNoise {
 public:
  SphereNoise(const CounterRng& rng) : rng_(rng) {
    for (int k = 0; k < kWaves; ++k) {
      // Random direction times a frequency between 2 and 7 waves across the sphere.
      const float z = rng.uniform(k, 0, -1.0f, 1.0f);
      const float phi = rng.uniform(k, 1, 0.0f, 2.0f * kPi);
      const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
      const float frequency = rng.uniform(k, 2, 2.0f, 7.0f);
      waves_[k].direction = frequency * Vec3(r * std::cos(phi), r * std::sin(phi), z);
      waves_[k].phase = rng.uniform(k, 3, 0.0f, 2.0f * kPi);
    }
  }

  /// Radius factor in [1 - kAmplitude - kJitter, 1 + kAmplitude + kJitter].
  float radius(const Vec3& unit_direction, uint64_t vertex) const {
    float sum = 0.0f;
    for (const Wave& w : waves_) sum += std::sin(glm::dot(w.direction, unit_direction) + w.phase);
    const float jitter = rng_.uniform(kWaves + vertex, 0, -kJitter, kJitter);
    return 1.0f + kAmplitude * sum / kWaves + jitter;
  }

 private:
  static constexpr int kWaves = 8;
  static constexpr float kAmplitude = 0.35f;
  static constexpr float kJitter = 0.004f;
  struct Wave {
    Vec3 direction;
    float phase;
  };
  const CounterRng& rng_;
  Wave waves_[kWaves];
};

/// UV sphere with `stacks` latitude bands and `slices` longitude segments: two poles and
/// (stacks - 1) rings of `slices` shared vertices, 2 * slices * (stacks - 1) triangles, wound
/// counter-clockwise seen from outside. The seam shares vertices too, so it is watertight.
TriangleMesh make_sphere(size_t stacks, size_t slices, const SphereNoise* noise) {
  TriangleMesh mesh;
  const size_t rings = stacks - 1;
  reserve_mesh(mesh, 2 + rings * slices, 2 * slices * rings);
  const auto place = [&](const Vec3& d) {
    const uint64_t vertex = mesh.positions.size();
    mesh.positions.push_back(noise ? d * noise->radius(d, vertex) : d);
  };
  place({0.0f, 0.0f, 1.0f});
  for (size_t i = 1; i <= rings; ++i) {
    const float theta = kPi * static_cast<float>(i) / static_cast<float>(stacks);
    const float st = std::sin(theta), ct = std::cos(theta);
    for (size_t j = 0; j < slices; ++j) {
      const float phi = 2.0f * kPi * static_cast<float>(j) / static_cast<float>(slices);
      place({st * std::cos(phi), st * std::sin(phi), ct});
    }
  }
  place({0.0f, 0.0f, -1.0f});
  const size_t south = mesh.positions.size() - 1;
  const auto ring_vertex = [&](size_t ring, size_t j) { return 1 + ring * slices + j % slices; };
  for (size_t j = 0; j < slices; ++j)
    mesh.triangles.push_back(tri(0, ring_vertex(0, j), ring_vertex(0, j + 1)));
  for (size_t r = 0; r + 1 < rings; ++r) {
    for (size_t j = 0; j < slices; ++j) {
      const size_t a = ring_vertex(r, j), b = ring_vertex(r, j + 1);
      const size_t c = ring_vertex(r + 1, j), d = ring_vertex(r + 1, j + 1);
      mesh.triangles.push_back(tri(a, c, d));
      mesh.triangles.push_back(tri(a, d, b));
    }
  }
  for (size_t j = 0; j < slices; ++j) {
    mesh.triangles.push_back(tri(ring_vertex(rings - 1, j), south, ring_vertex(rings - 1, j + 1)));
  }
  return mesh;
}

/// Stacks for a sphere of about n triangles with slices = 2 * stacks: n = 4 s (s - 1).
size_t sphere_stacks(size_t n) {
  const double s = 0.5 + std::sqrt(0.25 + static_cast<double>(n) / 4.0);
  return std::max<size_t>(2, static_cast<size_t>(std::llround(s)));
}

/// Independent triangles whose size shrinks with their number, so the soup stays about equally
/// dense (and overlapping) at every count instead of becoming a mesh of huge crossing triangles.
TriangleMesh make_soup(size_t n, const CounterRng& rng) {
  TriangleMesh mesh;
  reserve_mesh(mesh, 3 * n, n);
  const float size = std::min(0.5f, 1.5f / static_cast<float>(std::cbrt(static_cast<double>(n))));
  for (size_t i = 0; i < n; ++i) {
    const Vec3 center{rng.uniform(i, 0, -1.0f + size, 1.0f - size),
                      rng.uniform(i, 1, -1.0f + size, 1.0f - size),
                      rng.uniform(i, 2, -1.0f + size, 1.0f - size)};
    for (uint32_t corner = 0; corner < 3; ++corner) {
      const uint32_t d = 3 + 3 * corner;
      mesh.positions.push_back(center + Vec3(rng.uniform(i, d, -size, size),
                                             rng.uniform(i, d + 1, -size, size),
                                             rng.uniform(i, d + 2, -size, size)));
    }
    mesh.triangles.push_back(tri(3 * i, 3 * i + 1, 3 * i + 2));
  }
  return mesh;
}

/// Triangles running from one face of [-1,1]^3 to the opposite face (a random axis each), with
/// their third corner at the midpoint pushed off by length / kSliverAspect: longest edge over
/// height is then kSliverAspect. The worst case for boxes that bound triangles poorly.
TriangleMesh make_slivers(size_t n, const CounterRng& rng) {
  constexpr float kSliverAspect = 1000.0f;
  constexpr float kInset = 0.99f;  // keeps the pushed-off corner inside the box
  TriangleMesh mesh;
  reserve_mesh(mesh, 3 * n, n);
  for (size_t i = 0; i < n; ++i) {
    const int axis = std::min(2, static_cast<int>(rng.unit(i, 0) * 3.0f));
    Vec3 a, b;
    for (int k = 0; k < 3; ++k) {
      a[k] = rng.uniform(i, 1 + k, -kInset, kInset);
      b[k] = rng.uniform(i, 4 + k, -kInset, kInset);
    }
    a[axis] = -1.0f;
    b[axis] = 1.0f;
    const Vec3 along = b - a;
    const float length = glm::length(along);
    // A direction perpendicular to the edge: the edge crossed with a random unit vector (retried
    // along a fixed axis in the measure-zero case that they are parallel).
    const float z = rng.uniform(i, 7, -1.0f, 1.0f), phi = rng.uniform(i, 8, 0.0f, 2.0f * kPi);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    Vec3 perp = glm::cross(along, Vec3(r * std::cos(phi), r * std::sin(phi), z));
    if (glm::length(perp) < 1e-3f * length) perp = glm::cross(along, Vec3(0.0f, 0.0f, 1.0f));
    if (glm::length(perp) < 1e-3f * length) perp = glm::cross(along, Vec3(1.0f, 0.0f, 0.0f));
    perp = glm::normalize(perp);
    const Vec3 c = 0.5f * (a + b) + (length / kSliverAspect) * perp;
    mesh.positions.push_back(a);
    mesh.positions.push_back(b);
    mesh.positions.push_back(c);
    mesh.triangles.push_back(tri(3 * i, 3 * i + 1, 3 * i + 2));
  }
  return mesh;
}

/// Pairs of long thin triangles folded along their shared long edge, as thin panels of an
/// architectural mesh are: the edge is about 1.4 long and runs anywhere in the box; each
/// triangle's third corner sits near one end, 0.0003 to 0.003 off the edge, the two at an angle
/// of 0.05 to 30 degrees about it. Seen along its length such a pair is two surfaces a few
/// 1e-5 apart, where only an accurate t orders them right.
TriangleMesh make_folded_slivers(size_t n, const CounterRng& rng) {
  TriangleMesh mesh;
  reserve_mesh(mesh, 3 * n, n);
  for (size_t i = 0; i < n; i += 2) {
    const size_t pair = i / 2;
    const Vec3 center(rng.uniform(pair, 0, -0.3f, 0.3f), rng.uniform(pair, 1, -0.3f, 0.3f),
                      rng.uniform(pair, 2, -0.3f, 0.3f));
    const float z = rng.uniform(pair, 3, -1.0f, 1.0f), phi = rng.uniform(pair, 4, 0.0f, 2 * kPi);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const Vec3 along(r * std::cos(phi), r * std::sin(phi), z);
    const Vec3 a = center - 0.68f * along, b = center + 0.68f * along;
    // Two unit directions across the edge, `fold` radians apart about it.
    Vec3 p = glm::cross(along, Vec3(0.0f, 0.0f, 1.0f));
    if (glm::length(p) < 0.1f) p = glm::cross(along, Vec3(1.0f, 0.0f, 0.0f));
    p = glm::normalize(p);
    const Vec3 q = glm::normalize(glm::cross(along, p));
    const float spin = rng.uniform(pair, 5, 0.0f, 2 * kPi);
    const Vec3 p1 = std::cos(spin) * p + std::sin(spin) * q;
    const Vec3 q1 = glm::normalize(glm::cross(along, p1));
    const float fold =
        glm::radians(std::exp(rng.uniform(pair, 6, std::log(0.05f), std::log(30.0f))));
    const Vec3 p2 = std::cos(fold) * p1 + std::sin(fold) * q1;
    const float w1 = rng.uniform(pair, 7, 0.0003f, 0.003f);
    const float w2 = rng.uniform(pair, 8, 0.0003f, 0.003f);
    const size_t base = mesh.positions.size();
    mesh.positions.push_back(a);
    mesh.positions.push_back(b);
    mesh.positions.push_back(b + w1 * p1);
    mesh.triangles.push_back(tri(base, base + 1, base + 2));
    if (i + 1 < n) {
      mesh.positions.push_back(a + w2 * p2);
      mesh.triangles.push_back(tri(base + 1, base, base + 3));
    }
  }
  return mesh;
}

/// Appends the axis-aligned box [lo, hi]: 8 vertices, 12 triangles wound outward.
void add_box(TriangleMesh& mesh, const Vec3& lo, const Vec3& hi) {
  const size_t base = mesh.positions.size();
  for (int i = 0; i < 8; ++i) {
    mesh.positions.emplace_back(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
  }
  constexpr uint32_t kQuads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : kQuads) {
    mesh.triangles.push_back(tri(base + q[0], base + q[1], base + q[2]));
    mesh.triangles.push_back(tri(base + q[0], base + q[2], base + q[3]));
  }
}

constexpr float kInteriorWallHeight = 0.2f;
/// Rooms a side up to which the furniture has its full size (about a million triangles).
constexpr size_t kFullSizeFurnitureRooms = 26;

/// A cutaway floor plan, as the architectural meshes of issue 12 mix large and small
/// triangles: rooms x rooms square rooms over [-1,1]^2 with their floors at z = 0 (two
/// triangles each), no ceilings, walls kInteriorWallHeight high and 0.01 thick as boxes (a
/// doorway in each inner one), and the rest of the n triangles in furniture on the floors:
/// boxes (12 triangles, 0.005 to 0.06 wide) and small spheres (80 triangles, radius 0.005 to
/// 0.03), one in four a sphere. With more than kFullSizeFurnitureRooms rooms a side the
/// furniture shrinks with the rooms, so that it stays inside them. About n triangles (at least
/// the rooms' own); inside [-1,1]^2 x [0, kInteriorWallHeight].
TriangleMesh make_interior(size_t n, const CounterRng& rng) {
  constexpr float kHalfThickness = 0.005f;
  constexpr size_t kPropSphereStacks = 5;  // 2 x 10 x 4 = 80 triangles
  const size_t rooms = std::clamp<size_t>(
      static_cast<size_t>(std::llround(std::sqrt(static_cast<double>(n) / 1500.0))), 2, 256);
  const float room = 2.0f / static_cast<float>(rooms);
  // 1 exactly up to kFullSizeFurnitureRooms (the same bits as unscaled), below 1 beyond.
  const float scale = std::min(1.0f, float(kFullSizeFurnitureRooms) / float(rooms));
  const TriangleMesh unit_sphere = make_sphere(kPropSphereStacks, 2 * kPropSphereStacks, nullptr);
  const size_t structure = 2 * rooms * rooms + 2 * (rooms + 1) * rooms * 24;
  const size_t capacity = std::max(n, structure) + 2 * unit_sphere.triangles.size();
  TriangleMesh mesh;
  // Boxes and spheres have fewer vertices than triangles; the floors' quads four for two.
  reserve_mesh(mesh, capacity + 2 * rooms * rooms, capacity);
  const auto grid = [&](size_t i) { return i == rooms ? 1.0f : -1.0f + room * float(i); };
  for (size_t y = 0; y < rooms; ++y) {
    for (size_t x = 0; x < rooms; ++x) {
      const size_t base = mesh.positions.size();
      mesh.positions.emplace_back(grid(x), grid(y), 0.0f);
      mesh.positions.emplace_back(grid(x + 1), grid(y), 0.0f);
      mesh.positions.emplace_back(grid(x + 1), grid(y + 1), 0.0f);
      mesh.positions.emplace_back(grid(x), grid(y + 1), 0.0f);
      mesh.triangles.push_back(tri(base, base + 1, base + 2));
      mesh.triangles.push_back(tri(base, base + 2, base + 3));
    }
  }
  // Walls along x = grid(i) and y = grid(i), one segment per room side; inner ones have a
  // doorway of a third of the side in the middle.
  for (int axis = 0; axis < 2; ++axis) {
    for (size_t i = 0; i <= rooms; ++i) {
      const bool outer = i == 0 || i == rooms;
      const float at = std::clamp(grid(i), -1.0f + kHalfThickness, 1.0f - kHalfThickness);
      for (size_t j = 0; j < rooms; ++j) {
        const float from = grid(j), to = grid(j + 1);
        const auto wall = [&](float a, float b) {
          Vec3 lo(at - kHalfThickness, a, 0.0f), hi(at + kHalfThickness, b, kInteriorWallHeight);
          if (axis == 1) {
            std::swap(lo.x, lo.y);
            std::swap(hi.x, hi.y);
          }
          add_box(mesh, lo, hi);
        };
        if (outer) {
          wall(from, to);
        } else {
          wall(from, from + room / 3.0f);
          wall(to - room / 3.0f, to);
        }
      }
    }
  }
  for (uint64_t k = 0;; ++k) {
    const bool sphere = rng.unit(k, 0) < 0.25f;
    const size_t count = sphere ? unit_sphere.triangles.size() : 12;
    if (mesh.triangles.size() + count > n) break;
    const size_t r =
        std::min(rooms * rooms - 1, static_cast<size_t>(rng.unit(k, 1) * rooms * rooms));
    const float x0 = grid(r % rooms) + 0.035f * scale, y0 = grid(r / rooms) + 0.035f * scale;
    const float span = room - 0.07f * scale;
    const float cx = x0 + span * rng.unit(k, 2), cy = y0 + span * rng.unit(k, 3);
    if (sphere) {
      const float radius = scale * rng.uniform(k, 4, 0.005f, 0.03f);
      const Vec3 center(cx, cy, radius);
      const size_t base = mesh.positions.size();
      for (const Vec3& p : unit_sphere.positions) mesh.positions.push_back(center + radius * p);
      for (const glm::uvec3& t : unit_sphere.triangles) {
        mesh.triangles.push_back(tri(base + t.x, base + t.y, base + t.z));
      }
    } else {
      const Vec3 half =
          scale * Vec3(rng.uniform(k, 4, 0.0025f, 0.03f), rng.uniform(k, 5, 0.0025f, 0.03f), 0.0f);
      const float height = scale * rng.uniform(k, 6, 0.005f, 0.12f);
      add_box(mesh, Vec3(cx, cy, 0.0f) - half, Vec3(cx + half.x, cy + half.y, height));
    }
  }
  return mesh;
}

/// cells x cells squares over [-1,1]^2 at z = 0, two triangles each, facing +z; every interior
/// vertex is shared by six triangles.
TriangleMesh make_grid(size_t cells) {
  TriangleMesh mesh;
  const size_t side = cells + 1;
  reserve_mesh(mesh, side * side, 2 * cells * cells);
  for (size_t y = 0; y < side; ++y) {
    for (size_t x = 0; x < side; ++x) {
      // Exact end points (-1 and 1) so grids of any size cover the same square.
      const float fx = x == cells ? 1.0f : -1.0f + 2.0f * static_cast<float>(x) / cells;
      const float fy = y == cells ? 1.0f : -1.0f + 2.0f * static_cast<float>(y) / cells;
      mesh.positions.emplace_back(fx, fy, 0.0f);
    }
  }
  for (size_t y = 0; y < cells; ++y) {
    for (size_t x = 0; x < cells; ++x) {
      const size_t v00 = y * side + x, v10 = v00 + 1, v01 = v00 + side, v11 = v01 + 1;
      mesh.triangles.push_back(tri(v00, v10, v11));
      mesh.triangles.push_back(tri(v00, v11, v01));
    }
  }
  return mesh;
}

}  // namespace

GeneratedMeshKind parse_generated_mesh_kind(const std::string& name) {
  if (name == "sphere") return GeneratedMeshKind::kSphere;
  if (name == "noisy_sphere") return GeneratedMeshKind::kNoisySphere;
  if (name == "soup") return GeneratedMeshKind::kSoup;
  if (name == "slivers") return GeneratedMeshKind::kSlivers;
  if (name == "grid") return GeneratedMeshKind::kGrid;
  if (name == "folded_slivers") return GeneratedMeshKind::kFoldedSlivers;
  if (name == "interior") return GeneratedMeshKind::kInterior;
  throw Error(ErrorKind::kUsage, "unknown generated mesh kind '" + name +
                                     "'; available: sphere, noisy_sphere, soup, slivers, grid, "
                                     "folded_slivers, interior");
}

std::string to_string(GeneratedMeshKind kind) {
  switch (kind) {
    case GeneratedMeshKind::kSphere:
      return "sphere";
    case GeneratedMeshKind::kNoisySphere:
      return "noisy_sphere";
    case GeneratedMeshKind::kSoup:
      return "soup";
    case GeneratedMeshKind::kSlivers:
      return "slivers";
    case GeneratedMeshKind::kGrid:
      return "grid";
    case GeneratedMeshKind::kFoldedSlivers:
      return "folded_slivers";
    case GeneratedMeshKind::kInterior:
      return "interior";
  }
  return "unknown";
}

TriangleMesh generate_mesh(GeneratedMeshKind kind, size_t triangle_count, uint64_t seed,
                           uint32_t material_id) {
  // 32-bit vertex indices bound every kind; soup and slivers use three vertices per triangle.
  constexpr size_t kMaxTriangles = (size_t(1) << 32) / 3 - 1;
  if (triangle_count == 0 || triangle_count > kMaxTriangles) {
    throw Error(ErrorKind::kUsage, "generated mesh needs between 1 and " +
                                       std::to_string(kMaxTriangles) + " triangles, not " +
                                       std::to_string(triangle_count));
  }
  const CounterRng rng(seed, kind);
  TriangleMesh mesh;
  switch (kind) {
    case GeneratedMeshKind::kSphere:
    case GeneratedMeshKind::kNoisySphere: {
      const size_t stacks = sphere_stacks(triangle_count);
      const SphereNoise noise(rng);
      mesh = make_sphere(stacks, std::max<size_t>(3, 2 * stacks),
                         kind == GeneratedMeshKind::kNoisySphere ? &noise : nullptr);
      break;
    }
    case GeneratedMeshKind::kSoup:
      mesh = make_soup(triangle_count, rng);
      break;
    case GeneratedMeshKind::kSlivers:
      mesh = make_slivers(triangle_count, rng);
      break;
    case GeneratedMeshKind::kFoldedSlivers:
      mesh = make_folded_slivers(triangle_count, rng);
      break;
    case GeneratedMeshKind::kInterior:
      mesh = make_interior(triangle_count, rng);
      break;
    case GeneratedMeshKind::kGrid: {
      const double cells = std::sqrt(static_cast<double>(triangle_count) / 2.0);
      mesh = make_grid(std::max<size_t>(1, static_cast<size_t>(std::llround(cells))));
      break;
    }
  }
  mesh.name = to_string(kind);
  mesh.material_id = material_id;
  return mesh;
}

}  // namespace prism
