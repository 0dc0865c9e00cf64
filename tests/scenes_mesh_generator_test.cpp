#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <utility>

#include "core/error.h"
#include "core/scene_geometry.h"
#include "scenes/mesh_generator.h"

namespace prism {
namespace {

const GeneratedMeshKind kAllKinds[] = {
    GeneratedMeshKind::kSphere,  GeneratedMeshKind::kNoisySphere, GeneratedMeshKind::kSoup,
    GeneratedMeshKind::kSlivers, GeneratedMeshKind::kGrid,        GeneratedMeshKind::kFoldedSlivers,
    GeneratedMeshKind::kInterior};

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof(Vec3)) == 0; }

/// Edge -> number of triangles using it, with the edge's endpoints ordered.
std::map<std::pair<uint32_t, uint32_t>, int> edge_use(const TriangleMesh& mesh) {
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (const auto& t : mesh.triangles) {
    for (int e = 0; e < 3; ++e) {
      const uint32_t a = t[e], b = t[(e + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  return uses;
}

TEST(ScenesMeshGenerator, ParsesAndPrintsEveryKind) {
  for (const GeneratedMeshKind kind : kAllKinds) {
    EXPECT_EQ(parse_generated_mesh_kind(to_string(kind)), kind);
  }
  try {
    parse_generated_mesh_kind("spehre");
    FAIL() << "no error for an unknown kind";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kUsage);
    EXPECT_NE(std::string(e.what()).find("noisy_sphere"), std::string::npos) << e.what();
  }
}

TEST(ScenesMeshGenerator, ExactCountsForSoupAndSlivers) {
  for (const size_t n : {1u, 7u, 1000u}) {
    const TriangleMesh soup = generate_mesh(GeneratedMeshKind::kSoup, n, 3);
    EXPECT_EQ(soup.triangle_count(), n);
    EXPECT_EQ(soup.positions.size(), 3 * n);  // no shared vertices
    const TriangleMesh slivers = generate_mesh(GeneratedMeshKind::kSlivers, n, 3);
    EXPECT_EQ(slivers.triangle_count(), n);
    EXPECT_EQ(generate_mesh(GeneratedMeshKind::kFoldedSlivers, n, 3).triangle_count(), n);
  }
}

TEST(ScenesMeshGenerator, FoldedSliversArePairsSharingALongEdge) {
  const TriangleMesh mesh = generate_mesh(GeneratedMeshKind::kFoldedSlivers, 2000, 5);
  ASSERT_EQ(mesh.triangle_count(), 2000u);
  for (size_t i = 0; i + 1 < mesh.triangles.size(); i += 2) {
    const glm::uvec3 a = mesh.triangles[i], b = mesh.triangles[i + 1];
    // The second triangle runs the shared edge the other way (a consistent fold).
    ASSERT_EQ(a.x, b.y);
    ASSERT_EQ(a.y, b.x);
    const Vec3 edge = mesh.positions[a.y] - mesh.positions[a.x];
    EXPECT_NEAR(glm::length(edge), 1.36f, 1e-4f);
    for (const glm::uvec3 t : {a, b}) {
      const Vec3 p0 = mesh.positions[t.x], p1 = mesh.positions[t.y], p2 = mesh.positions[t.z];
      const float width = glm::length(glm::cross(p1 - p0, p2 - p0)) / glm::length(p1 - p0);
      EXPECT_GE(width, 0.0003f * 0.999f);
      EXPECT_LE(width, 0.003f * 1.001f);
    }
  }
}

TEST(ScenesMeshGenerator, SphereAndGridCountsAreNearTheRequest) {
  for (const size_t n : {100u, 2000u, 50000u}) {
    for (const auto kind :
         {GeneratedMeshKind::kSphere, GeneratedMeshKind::kNoisySphere, GeneratedMeshKind::kGrid}) {
      const TriangleMesh mesh = generate_mesh(kind, n, 1);
      const double ratio = double(mesh.triangle_count()) / double(n);
      EXPECT_GT(ratio, 0.8) << to_string(kind) << " " << n;
      EXPECT_LT(ratio, 1.25) << to_string(kind) << " " << n;
    }
  }
  // Tiny requests still give a closed sphere and one grid cell.
  EXPECT_GE(generate_mesh(GeneratedMeshKind::kSphere, 1).triangle_count(), 6u);
  EXPECT_EQ(generate_mesh(GeneratedMeshKind::kGrid, 1).triangle_count(), 2u);
}

TEST(ScenesMeshGenerator, ZeroTrianglesIsAnError) {
  EXPECT_THROW(generate_mesh(GeneratedMeshKind::kSoup, 0), Error);
}

TEST(ScenesMeshGenerator, DeterministicForKindCountAndSeed) {
  for (const GeneratedMeshKind kind : kAllKinds) {
    const TriangleMesh a = generate_mesh(kind, 500, 42, 3);
    const TriangleMesh b = generate_mesh(kind, 500, 42, 3);
    ASSERT_EQ(a.positions.size(), b.positions.size()) << to_string(kind);
    ASSERT_EQ(a.triangles, b.triangles) << to_string(kind);
    for (size_t i = 0; i < a.positions.size(); ++i) {
      ASSERT_TRUE(same_bits(a.positions[i], b.positions[i])) << to_string(kind) << " vertex " << i;
    }
    EXPECT_EQ(a.material_id, 3u);
  }
  // The seed matters for the random kinds.
  for (const auto kind :
       {GeneratedMeshKind::kNoisySphere, GeneratedMeshKind::kSoup, GeneratedMeshKind::kSlivers}) {
    const TriangleMesh a = generate_mesh(kind, 500, 1);
    const TriangleMesh b = generate_mesh(kind, 500, 2);
    ASSERT_EQ(a.positions.size(), b.positions.size());
    size_t differing = 0;
    for (size_t i = 0; i < a.positions.size(); ++i)
      differing += !same_bits(a.positions[i], b.positions[i]);
    EXPECT_GT(differing, a.positions.size() / 2) << to_string(kind);
  }
}

TEST(ScenesMeshGenerator, StaysInsideTheDocumentedBounds) {
  const float eps = 1e-5f;
  for (const GeneratedMeshKind kind : kAllKinds) {
    const TriangleMesh mesh = generate_mesh(kind, 3000, 9);
    const Bounds3 b = mesh.bounds();
    ASSERT_FALSE(b.empty());
    const float limit = kind == GeneratedMeshKind::kNoisySphere ? 1.4f : 1.0f + eps;
    EXPECT_LE(max_component(glm::abs(b.lower)), limit) << to_string(kind);
    EXPECT_LE(max_component(glm::abs(b.upper)), limit) << to_string(kind);
  }
  // The sphere's vertices lie on the unit sphere, the grid's in z = 0 covering [-1,1]^2.
  for (const Vec3& p : generate_mesh(GeneratedMeshKind::kSphere, 2000).positions) {
    EXPECT_NEAR(glm::length(p), 1.0f, 1e-5f);
  }
  const TriangleMesh grid = generate_mesh(GeneratedMeshKind::kGrid, 200);
  for (const Vec3& p : grid.positions) EXPECT_EQ(p.z, 0.0f);
  EXPECT_EQ(grid.bounds().lower, Vec3(-1.0f, -1.0f, 0.0f));
  EXPECT_EQ(grid.bounds().upper, Vec3(1.0f, 1.0f, 0.0f));
  // The noisy sphere really is displaced.
  float lo = 2.0f, hi = 0.0f;
  for (const Vec3& p : generate_mesh(GeneratedMeshKind::kNoisySphere, 2000, 5).positions) {
    lo = std::min(lo, glm::length(p));
    hi = std::max(hi, glm::length(p));
  }
  EXPECT_LT(lo, 0.97f);
  EXPECT_GT(hi, 1.03f);
  EXPECT_GT(lo, 0.6f);
}

TEST(ScenesMeshGenerator, InteriorMixesRoomsAndFurniture) {
  for (const size_t n : {20000u, 200000u}) {
    const TriangleMesh mesh = generate_mesh(GeneratedMeshKind::kInterior, n, 4);
    // Furniture fills the count up to less than one sphere (80 triangles) short of it.
    EXPECT_LE(mesh.triangle_count(), n);
    EXPECT_GT(mesh.triangle_count(), n - 80);
    // The floors span [-1,1]^2 at z = 0 and the walls reach 0.2.
    EXPECT_EQ(mesh.bounds().lower, Vec3(-1.0f, -1.0f, 0.0f));
    EXPECT_EQ(mesh.bounds().upper, Vec3(1.0f, 1.0f, 0.2f));
    float smallest = std::numeric_limits<float>::infinity(), largest = 0.0f;
    size_t floor_triangles = 0;
    for (const auto& t : mesh.triangles) {
      const Vec3 &a = mesh.positions[t.x], &b = mesh.positions[t.y], &c = mesh.positions[t.z];
      const Vec3 normal = glm::cross(b - a, c - a);
      const float area = 0.5f * glm::length(normal);
      ASSERT_GT(area, 0.0f);
      smallest = std::min(smallest, area);
      largest = std::max(largest, area);
      floor_triangles += a.z == 0.0f && b.z == 0.0f && c.z == 0.0f && normal.z > 0.0f;
    }
    // Room floors against the sides of the smallest boxes: large and small triangles mixed.
    EXPECT_GT(largest / smallest, 1e3f) << n;
    EXPECT_GE(floor_triangles, 8u) << n;  // at least 2 x 2 rooms, two triangles each
  }
  // Rooms smaller than the furniture's full size (37 a side here) keep it inside them.
  const Bounds3 many_rooms = generate_mesh(GeneratedMeshKind::kInterior, 2000000, 4).bounds();
  EXPECT_EQ(many_rooms.lower, Vec3(-1.0f, -1.0f, 0.0f));
  EXPECT_EQ(many_rooms.upper, Vec3(1.0f, 1.0f, 0.2f));
}

TEST(ScenesMeshGenerator, GridSharesEdgesAndVertices) {
  const TriangleMesh grid = generate_mesh(GeneratedMeshKind::kGrid, 2 * 10 * 10);
  ASSERT_EQ(grid.triangle_count(), 200u);
  EXPECT_EQ(grid.positions.size(), 11u * 11u);
  const auto uses = edge_use(grid);
  size_t shared = 0, boundary = 0;
  for (const auto& [edge, count] : uses) {
    EXPECT_LE(count, 2);
    (count == 2 ? shared : boundary) += 1;
  }
  EXPECT_EQ(boundary, 4u * 10u);
  EXPECT_EQ(shared, uses.size() - boundary);
  EXPECT_GT(shared, 0u);
  // Every triangle faces +z.
  for (const auto& t : grid.triangles) {
    const Vec3 n = glm::cross(grid.positions[t.y] - grid.positions[t.x],
                              grid.positions[t.z] - grid.positions[t.x]);
    EXPECT_GT(n.z, 0.0f);
  }
}

TEST(ScenesMeshGenerator, SpheresAreClosedAndOutwardFacing) {
  for (const auto kind : {GeneratedMeshKind::kSphere, GeneratedMeshKind::kNoisySphere}) {
    const TriangleMesh mesh = generate_mesh(kind, 1000, 2);
    for (const auto& [edge, count] : edge_use(mesh)) {
      ASSERT_EQ(count, 2) << to_string(kind) << " edge " << edge.first << "-" << edge.second;
    }
    // Euler characteristic of a sphere: V - E + F = 2.
    const long v = long(mesh.positions.size()), f = long(mesh.triangle_count());
    EXPECT_EQ(v - long(edge_use(mesh).size()) + f, 2);
    for (const auto& t : mesh.triangles) {
      const Vec3 p0 = mesh.positions[t.x], p1 = mesh.positions[t.y], p2 = mesh.positions[t.z];
      const Vec3 n = glm::cross(p1 - p0, p2 - p0);
      ASSERT_GT(glm::dot(n, p0 + p1 + p2), 0.0f) << to_string(kind);
    }
  }
}

TEST(ScenesMeshGenerator, SliversAreLongAndThin) {
  const TriangleMesh mesh = generate_mesh(GeneratedMeshKind::kSlivers, 2000, 11);
  for (const auto& t : mesh.triangles) {
    const Vec3 p0 = mesh.positions[t.x], p1 = mesh.positions[t.y], p2 = mesh.positions[t.z];
    const float longest =
        std::max({glm::length(p1 - p0), glm::length(p2 - p1), glm::length(p0 - p2)});
    const float area2 = glm::length(glm::cross(p1 - p0, p2 - p0));
    ASSERT_GT(area2, 0.0f);
    // Longest edge over the height on it.
    const float aspect = longest * longest / area2;
    ASSERT_GT(aspect, 900.0f);
    ASSERT_LT(aspect, 1100.0f);
    // It crosses the box: at least 2 long along some axis.
    ASSERT_GE(max_component(glm::abs(p1 - p0)), 2.0f - 1e-6f);
  }
}

TEST(ScenesMeshGenerator, EveryKindPassesValidation) {
  for (const GeneratedMeshKind kind : kAllKinds) {
    SceneGeometry geometry;
    geometry.meshes.push_back(generate_mesh(kind, 777, 5));
    EXPECT_NO_THROW(geometry.validate()) << to_string(kind);
    // Room for Embree's padding is there already, so finalize() does not reallocate.
    const Vec3* before = geometry.meshes[0].positions.data();
    geometry.finalize();
    EXPECT_EQ(geometry.meshes[0].positions.data(), before) << to_string(kind);
  }
}

}  // namespace
}  // namespace prism
