// The custom wide BVH against brute force, bit for bit, for every split, layout and instruction
// set this CPU runs; plus builder invariants and parameter handling.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "accel/brute/brute_accelerator.h"
#include "accel/bvh/binned_sah_builder.h"
#include "accel/bvh/cpu_features.h"
#include "accel/bvh/reinsertion_optimizer.h"
#include "accel/bvh/spatial_split_builder.h"
#include "accel/bvh/wide_bvh.h"
#include "accel/bvh/wide_bvh_accelerator.h"
#include "accel/validation/hit_comparison.h"
#include "accel/validation/ray_sets.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/primitive_intersection.h"
#include "core/scene.h"
#include "scenes/mesh_generator.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

// --- scenes built in code -------------------------------------------------------------------

// The project's generated meshes (scenes/mesh_generator.h), moved to `center` and scaled.
TriangleMesh generated(GeneratedMeshKind kind, size_t triangles, uint64_t seed,
                       Vec3 center = Vec3(0.0f), float scale = 1.0f) {
  TriangleMesh m = generate_mesh(kind, triangles, seed);
  for (Vec3& p : m.positions) p = center + scale * p;
  return m;
}

// Long thin triangles crossing the box diagonally, through its centre: what spatial splits are
// for. (The generator's slivers run along the axes, where SBVH finds nothing to clip.)
TriangleMesh diagonal_slivers(size_t count, uint64_t seed) {
  std::mt19937 rng(static_cast<uint32_t>(seed));
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  TriangleMesh m;
  m.name = "slivers";
  for (size_t i = 0; i < count; ++i) {
    const Vec3 a(u(rng), u(rng), u(rng));
    const Vec3 b = -a + 0.2f * Vec3(u(rng), u(rng), u(rng));
    const Vec3 w = 0.002f * Vec3(u(rng), u(rng), u(rng));
    m.positions.insert(m.positions.end(), {a, b, a + w});
    const auto base = static_cast<uint32_t>(3 * i);
    m.triangles.push_back({base, base + 1, base + 2});
  }
  return m;
}

// A flat grid in z = 0 with shared edges and vertices, plus an exact duplicate of its first
// cell (coplanar copies are exact ties) and axis-aligned walls that make degenerate boxes.
TriangleMesh grid_with_ties(int n) {
  TriangleMesh m;
  m.name = "grid";
  for (int y = 0; y <= n; ++y) {
    for (int x = 0; x <= n; ++x) {
      m.positions.emplace_back(-1.0f + 2.0f * static_cast<float>(x) / static_cast<float>(n),
                               -1.0f + 2.0f * static_cast<float>(y) / static_cast<float>(n), 0.0f);
    }
  }
  const auto row = static_cast<uint32_t>(n + 1);
  for (uint32_t y = 0; y < static_cast<uint32_t>(n); ++y) {
    for (uint32_t x = 0; x < static_cast<uint32_t>(n); ++x) {
      const uint32_t i = y * row + x;
      m.triangles.push_back({i, i + 1, i + row + 1});
      m.triangles.push_back({i, i + row + 1, i + row});
    }
  }
  m.triangles.push_back(m.triangles[0]);
  m.triangles.push_back(m.triangles[1]);
  const auto base = static_cast<uint32_t>(m.positions.size());
  m.positions.insert(m.positions.end(),
                     {Vec3(0.5f, -1, -1), Vec3(0.5f, 1, -1), Vec3(0.5f, 1, 1), Vec3(0.5f, -1, 1)});
  m.triangles.push_back({base, base + 1, base + 2});
  m.triangles.push_back({base, base + 2, base + 3});
  return m;
}

struct NamedScene {
  std::string name;
  SceneGeometry geometry;
};

std::vector<NamedScene> make_scenes() {
  std::vector<NamedScene> scenes;
  {
    NamedScene s{"sphere", {}};
    s.geometry.meshes.push_back(generated(GeneratedMeshKind::kSphere, 4800, 1));
    scenes.push_back(std::move(s));
  }
  {
    NamedScene s{"soup", {}};
    s.geometry.meshes.push_back(generated(GeneratedMeshKind::kSoup, 3000, 7));
    scenes.push_back(std::move(s));
  }
  {
    NamedScene s{"slivers", {}};
    s.geometry.meshes.push_back(diagonal_slivers(1500, 11));
    scenes.push_back(std::move(s));
  }
  {
    NamedScene s{"grid_ties", {}};
    s.geometry.meshes.push_back(grid_with_ties(24));
    scenes.push_back(std::move(s));
  }
  {
    // Two meshes, far from the origin, with analytic spheres between them.
    NamedScene s{"mixed_offset", {}};
    const Vec3 offset(1000.0f, -500.0f, 250.0f);
    s.geometry.meshes.push_back(
        generated(GeneratedMeshKind::kSphere, 384, 2, offset + Vec3(-2, 0, 0)));
    s.geometry.meshes.push_back(generated(GeneratedMeshKind::kSoup, 400, 3, offset, 3.0f));
    for (int i = 0; i < 37; ++i) {
      s.geometry.spheres.push_back(
          {offset + Vec3(static_cast<float>(i % 6) - 2.5f, static_cast<float>(i / 6) - 3.0f, 0.5f),
           0.3f + 0.01f * static_cast<float>(i), 0});
    }
    scenes.push_back(std::move(s));
  }
  for (auto& s : scenes) s.geometry.finalize();
  return scenes;
}

std::vector<std::string> isas() {
  std::vector<std::string> out{"generic"};
  if (cpu_has_avx2()) out.emplace_back("avx2");
  if (cpu_has_avx512()) out.emplace_back("avx512");
  return out;
}

ParamSet bvh_params(const std::string& split, const std::string& layout, const std::string& isa) {
  ParamSet p;
  p.set("bvh.split", split);
  p.set("bvh.layout", layout);
  p.set("bvh.isa", isa);
  return p;
}

bool same_bits(float a, float b) {
  return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b);
}

// --- bit-exact agreement with brute force -----------------------------------------------------

TEST(AccelWideBvh, MatchesBruteForceBitForBitEverySplitLayoutAndIsa) {
  const std::vector<NamedScene> scenes = make_scenes();
  for (const NamedScene& scene : scenes) {
    BruteAccelerator brute{ParamSet()};
    brute.build(scene.geometry);
    std::vector<Ray> rays = random_rays(scene.geometry.bounds(), 1500, 42);
    const std::vector<Ray> features = feature_rays(scene.geometry, 1500, 43);
    rays.insert(rays.end(), features.begin(), features.end());
    std::vector<std::optional<Hit>> expected(rays.size());
    std::vector<bool> expected_occluded(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) {
      expected[i] = brute.intersect(rays[i]);
      expected_occluded[i] = brute.occluded(rays[i]);
    }
    for (const std::string split : {"median", "sah", "sbvh"}) {
      for (const std::string layout : {"bvh2", "bvh4", "bvh8"}) {
        for (const std::string& isa : isas()) {
          WideBvhAccelerator bvh(parse_wide_bvh_options(bvh_params(split, layout, isa)));
          bvh.build(scene.geometry);
          size_t failures = 0;
          for (size_t i = 0; i < rays.size() && failures < 3; ++i) {
            const std::optional<Hit> got = bvh.intersect(rays[i]);
            const std::optional<Hit>& want = expected[i];
            const bool same =
                got.has_value() == want.has_value() &&
                (!got || (same_bits(got->t, want->t) && same_bits(got->u, want->u) &&
                          same_bits(got->v, want->v) && got->geom_id == want->geom_id &&
                          got->prim_id == want->prim_id));
            const bool occluded_same = bvh.occluded(rays[i]) == expected_occluded[i];
            if (!same || !occluded_same) {
              ++failures;
              ADD_FAILURE() << scene.name << " " << split << " " << layout << " " << isa << " ray "
                            << i << " " << format_ray(rays[i]) << ": bvh " << format_hit(got)
                            << " brute " << format_hit(want)
                            << (occluded_same ? "" : " (occluded differs)");
            }
          }
        }
      }
    }
  }
}

// A triangle hit carries its triangle's corners from the tree's leaf (Hit::vertex_lanes), the
// mesh's own floats; Scene::surface_at() reading them gives what it gives reading the mesh.
TEST(AccelWideBvh, TriangleHitsCarryTheirCornersForSurfaceAt) {
  for (const NamedScene& named : make_scenes()) {
    Scene scene;
    scene.geometry = named.geometry;
    const std::vector<Ray> rays = random_rays(scene.geometry.bounds(), 600, 17);
    for (const std::string layout : {"bvh2", "bvh8"}) {
      for (const std::string& isa : isas()) {
        // Spatial splits: a triangle's references in several leaves all carry its corners.
        WideBvhAccelerator bvh(parse_wide_bvh_options(bvh_params("sbvh", layout, isa)));
        bvh.build(scene.geometry);
        size_t triangle_hits = 0;
        for (const Ray& ray : rays) {
          const std::optional<Hit> hit = bvh.intersect(ray);
          if (!hit) continue;
          const std::string where = named.name + " " + layout + " " + isa + " " + format_ray(ray);
          if (scene.geometry.is_sphere(hit->geom_id)) {
            EXPECT_EQ(hit->vertex_lanes, nullptr) << where;
            continue;
          }
          ++triangle_hits;
          ASSERT_NE(hit->vertex_lanes, nullptr) << where;
          const TriangleMesh& mesh = scene.geometry.meshes[hit->geom_id];
          const glm::uvec3 tri = mesh.triangles[hit->prim_id];
          for (int k = 0; k < 3; ++k) {
            for (int a = 0; a < 3; ++a) {
              ASSERT_TRUE(same_bits(hit->vertex_lanes[4 * (3 * k + a)], mesh.positions[tri[k]][a]))
                  << where << " corner " << k << " axis " << a;
            }
          }
          Hit from_mesh = *hit;
          from_mesh.vertex_lanes = nullptr;
          const SurfaceInteraction fast = scene.surface_at(ray, *hit);
          const SurfaceInteraction slow = scene.surface_at(ray, from_mesh);
          for (int a = 0; a < 3; ++a) {
            ASSERT_TRUE(same_bits(fast.position[a], slow.position[a])) << where;
            ASSERT_TRUE(same_bits(fast.position_error[a], slow.position_error[a])) << where;
            ASSERT_TRUE(same_bits(fast.geometric_normal[a], slow.geometric_normal[a])) << where;
            ASSERT_TRUE(same_bits(fast.shading_normal[a], slow.shading_normal[a])) << where;
          }
          ASSERT_TRUE(same_bits(fast.uv.x, slow.uv.x) && same_bits(fast.uv.y, slow.uv.y)) << where;
        }
        EXPECT_GT(triangle_hits, 20u) << named.name << " " << layout << " " << isa;
      }
    }
  }
}

TEST(AccelWideBvh, BatchedIntersectEqualsSingleRays) {
  const std::vector<NamedScene> scenes = make_scenes();
  const SceneGeometry& g = scenes[1].geometry;
  WideBvhAccelerator bvh(parse_wide_bvh_options(ParamSet()));
  bvh.build(g);
  const std::vector<Ray> rays = random_rays(g.bounds(), 500, 5);
  std::vector<std::optional<Hit>> hits(rays.size());
  bvh.intersect(rays, hits);
  for (size_t i = 0; i < rays.size(); ++i) {
    const std::optional<Hit> single = bvh.intersect(rays[i]);
    ASSERT_EQ(single.has_value(), hits[i].has_value()) << i;
    if (single) {
      EXPECT_TRUE(same_bits(single->t, hits[i]->t)) << i;
    }
  }
}

TEST(AccelWideBvh, InvalidRaysAndEmptySceneMiss) {
  SceneGeometry empty;
  WideBvhAccelerator bvh(parse_wide_bvh_options(ParamSet()));
  bvh.build(empty);
  EXPECT_FALSE(bvh.intersect(Ray{}).has_value());
  EXPECT_FALSE(bvh.occluded(Ray{}));

  const std::vector<NamedScene> scenes = make_scenes();
  WideBvhAccelerator full(parse_wide_bvh_options(ParamSet()));
  full.build(scenes[0].geometry);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = kInfinity;
  const Vec3 o(0.0f, 0.0f, -5.0f);
  const std::vector<Ray> bad = {
      {o, 0.0f, Vec3(nan, 0, 1), inf},       {o, 0.0f, Vec3(inf, 0, 1), inf},
      {Vec3(nan), 0.0f, Vec3(0, 0, 1), inf}, {o, nan, Vec3(0, 0, 1), inf},
      {o, 0.0f, Vec3(0, 0, 1), nan},         {o, 0.0f, Vec3(0.0f), inf},
      {o, 3.0f, Vec3(0, 0, 1), 2.0f}};
  for (const Ray& r : bad) {
    EXPECT_FALSE(full.intersect(r).has_value()) << format_ray(r);
    EXPECT_FALSE(full.occluded(r)) << format_ray(r);
  }
  // Sanity: the same origin and a valid direction hits the sphere at t = 4.
  const std::optional<Hit> h = full.intersect({o, 0.0f, Vec3(0.001f, 0.002f, 1.0f), inf});
  ASSERT_TRUE(h.has_value());
  EXPECT_NEAR(h->t, 4.0f, 0.01f);
}

// --- builder invariants -------------------------------------------------------------------

void check_binary_tree(const BinaryBvh& bvh, const SceneGeometry& g, bool allow_duplicates) {
  ASSERT_GT(bvh.node_count, 0u);
  std::multiset<std::pair<uint32_t, uint32_t>> seen;
  std::vector<std::pair<uint32_t, int>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [index, depth] = stack.back();
    stack.pop_back();
    ASSERT_LT(depth, kMaxBvhDepth);
    const BinaryNode& n = bvh.nodes[index];
    const Bounds3 b = n.bounds();
    if (n.is_leaf()) {
      ASSERT_LE(n.first + n.count, bvh.refs.size());
      const bool spheres = bvh.refs[n.first].geom_id == g.sphere_geom_id();
      for (uint32_t i = n.first; i < n.first + n.count; ++i) {
        const PrimRef& r = bvh.refs[i];
        EXPECT_EQ(r.geom_id == g.sphere_geom_id(), spheres) << "leaf mixes spheres and triangles";
        for (int a = 0; a < 3; ++a) {
          EXPECT_LE(b.lower[a], r.lower[a]);
          EXPECT_GE(b.upper[a], r.upper[a]);
        }
        seen.insert({r.geom_id, r.prim_id});
      }
      continue;
    }
    ASSERT_LT(n.first + 1, bvh.node_count);
    for (uint32_t c = n.first; c <= n.first + 1; ++c) {
      const Bounds3 cb = bvh.nodes[c].bounds();
      for (int a = 0; a < 3; ++a) {
        EXPECT_LE(b.lower[a], cb.lower[a]);
        EXPECT_GE(b.upper[a], cb.upper[a]);
      }
      stack.push_back({c, depth + 1});
    }
  }
  // Every primitive but the degenerate triangles is referenced; object splits reference each
  // exactly once.
  size_t hittable = g.primitive_count();
  for (const TriangleMesh& mesh : g.meshes) {
    for (const glm::uvec3& t : mesh.triangles) {
      if (is_degenerate_triangle(mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z])) {
        --hittable;
      }
    }
  }
  std::set<std::pair<uint32_t, uint32_t>> distinct(seen.begin(), seen.end());
  EXPECT_EQ(distinct.size(), hittable);
  if (!allow_duplicates) {
    EXPECT_EQ(seen.size(), hittable);
  }
}

TEST(AccelWideBvh, DegenerateTrianglesAreLeftOutOfTheTree) {
  SceneGeometry g;
  TriangleMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {3, 0, 0}, {4, 0, 0}};
  mesh.triangles = {{0, 1, 2}, {3, 4, 5}, {0, 0, 0}, {1, 2, 0}};  // 2nd: collinear, 3rd: a point
  g.meshes.push_back(mesh);
  const std::vector<PrimRef> refs = make_prim_refs(g);
  ASSERT_EQ(refs.size(), 2u);
  EXPECT_EQ(refs[0].prim_id, 0u);
  EXPECT_EQ(refs[1].prim_id, 3u);
}

TEST(AccelWideBvh, BuildersProduceValidTrees) {
  for (const NamedScene& scene : make_scenes()) {
    for (const SplitMethod split : {SplitMethod::kMedian, SplitMethod::kSah}) {
      BvhBuildSettings s;
      s.split = split;
      const BinaryBvh bvh = build_object_split_bvh(make_prim_refs(scene.geometry),
                                                   scene.geometry.sphere_geom_id(), s);
      SCOPED_TRACE(scene.name + " " + split_name(split));
      check_binary_tree(bvh, scene.geometry, false);
    }
    BvhBuildSettings s;
    s.split = SplitMethod::kSpatial;
    const BinaryBvh bvh =
        build_spatial_split_bvh(scene.geometry, make_prim_refs(scene.geometry), s);
    SCOPED_TRACE(scene.name + " sbvh");
    check_binary_tree(bvh, scene.geometry, true);
    EXPECT_LE(
        bvh.refs.size(),
        static_cast<size_t>((1.0f + s.spatial_budget) * scene.geometry.primitive_count()) + 1);
  }
}

// The primitives under one child of a wide tree: their box, their largest size (a triangle's
// box's largest side, a sphere's diameter) and their largest |coordinate|.
struct SubtreeExtent {
  Bounds3 box;
  double size = 0.0;
};

template <int W>
void add_subtree(const WideBvh<W>& bvh, const SceneGeometry& g, uint32_t ref, SubtreeExtent& out) {
  if ((ref & kLeafFlag) == 0) {
    const WideNode<W>& node = bvh.nodes[ref];
    for (int i = 0; i < W; ++i) {
      if (node.bounds[0][i] <= node.bounds[1][i]) add_subtree(bvh, g, node.child[i], out);
    }
    return;
  }
  const uint32_t first = ref & kLeafFirstMask;
  const uint32_t blocks = ((ref >> kLeafCountShift) & 15u) + 1;
  for (uint32_t b = first; b < first + blocks; ++b) {
    for (int lane = 0; lane < 4; ++lane) {
      if ((ref & kSphereLeafFlag) != 0) {
        const Sphere& sp = g.spheres[bvh.sphere_blocks[b].sphere[lane]];
        out.box.extend(sp.bounds());
        out.size = std::max(out.size, 2.0 * sp.radius);
        continue;
      }
      const TriangleBlock& block = bvh.triangle_blocks[b];
      Vec3 v[3];
      for (int k = 0; k < 3; ++k) {
        v[k] = Vec3(block.p[k][0][lane], block.p[k][1][lane], block.p[k][2][lane]);
        out.box.extend(v[k]);
      }
      out.size = std::max(out.size, double(triangle_size(v[0], v[1], v[2])));
    }
  }
}

// The traversal's padding (core/ray.h) has a share that depends on the box alone: every stored
// child box must hold its primitives widened by kBoxCoordinatePaddingUlps of their largest
// |coordinate| and kBoxSizePaddingUlps of their largest size, on every axis; the kernels add
// only the ray origin's share.
template <int W>
void check_box_padding(const WideBvh<W>& bvh, const SceneGeometry& g) {
  constexpr double kU = 1.0 / (1 << 24);
  size_t checked = 0;
  for (const WideNode<W>& node : bvh.nodes) {
    for (int i = 0; i < W; ++i) {
      if (!(node.bounds[0][i] <= node.bounds[1][i])) continue;
      SubtreeExtent e;
      add_subtree(bvh, g, node.child[i], e);
      const double coordinate =
          std::max(max_component(glm::abs(e.box.lower)), max_component(glm::abs(e.box.upper)));
      const double padding =
          kBoxCoordinatePaddingUlps * kU * coordinate + kBoxSizePaddingUlps * kU * e.size;
      for (int a = 0; a < 3; ++a) {
        ASSERT_LE(double(node.bounds[2 * a][i]), double(e.box.lower[a]) - padding) << "axis " << a;
        ASSERT_GE(double(node.bounds[2 * a + 1][i]), double(e.box.upper[a]) + padding)
            << "axis " << a;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 0u);
}

TEST(AccelWideBvh, StoredBoxesCarryTheirShareOfThePadding) {
  for (const NamedScene& scene : make_scenes()) {
    SCOPED_TRACE(scene.name);
    const BinaryBvh binary =
        build_object_split_bvh(make_prim_refs(scene.geometry), scene.geometry.sphere_geom_id(), {});
    check_box_padding(collapse_to_wide<8>(binary, scene.geometry), scene.geometry);
    check_box_padding(collapse_to_wide<4>(binary, scene.geometry), scene.geometry);
    check_box_padding(collapse_to_wide<2>(binary, scene.geometry), scene.geometry);
  }
}

double interior_area(const BinaryBvh& bvh) {
  double sum = 0.0;
  for (size_t i = 0; i < bvh.node_count; ++i) {
    if (!bvh.nodes[i].is_leaf()) sum += bvh.nodes[i].bounds().area();
  }
  return sum;
}

TEST(AccelWideBvh, ReinsertionKeepsEveryLeafAndLowersTheInteriorArea) {
  size_t total_moves = 0;
  for (const NamedScene& scene : make_scenes()) {
    SCOPED_TRACE(scene.name);
    BvhBuildSettings s;
    BinaryBvh bvh =
        build_object_split_bvh(make_prim_refs(scene.geometry), scene.geometry.sphere_geom_id(), s);
    const std::vector<PrimRef> refs = bvh.refs;
    const size_t nodes = bvh.node_count;
    const double before = interior_area(bvh);
    total_moves += optimize_by_reinsertion(bvh, 2);
    check_binary_tree(bvh, scene.geometry, false);
    EXPECT_EQ(bvh.node_count, nodes);
    EXPECT_LE(interior_area(bvh), before * (1.0 + 1e-6));
    ASSERT_EQ(bvh.refs.size(), refs.size());
    EXPECT_EQ(0, std::memcmp(bvh.refs.data(), refs.data(), refs.size() * sizeof(PrimRef)));
  }
  EXPECT_GT(total_moves, 0u);  // the test scenes leave the optimizer something to do
}

// A room of five walls (two large triangles each) around a detailed mesh, as the CS184 Cornell
// scenes are: the walls' node is as large as the root, so nearly every ray enters it, and the
// builders must find the splits that give each wall its own thin box, however few triangles
// that node holds (sah::bins_for() with the node's share of the root's area).
TEST(AccelWideBvh, RoomWallsAroundADetailedMeshGetLeavesOfTheirOwn) {
  SceneGeometry g;
  TriangleMesh walls;
  walls.name = "walls";
  const auto quad = [&](Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    const auto base = static_cast<uint32_t>(walls.positions.size());
    walls.positions.insert(walls.positions.end(), {a, b, c, d});
    walls.triangles.push_back({base, base + 1, base + 2});
    walls.triangles.push_back({base, base + 2, base + 3});
  };
  quad(Vec3(-1, -1, -1), Vec3(1, -1, -1), Vec3(1, 1, -1), Vec3(-1, 1, -1));  // floor
  quad(Vec3(-1, -1, 1), Vec3(-1, 1, 1), Vec3(1, 1, 1), Vec3(1, -1, 1));      // ceiling
  quad(Vec3(-1, 1, -1), Vec3(1, 1, -1), Vec3(1, 1, 1), Vec3(-1, 1, 1));      // back
  quad(Vec3(-1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, 1, 1), Vec3(-1, -1, 1));  // left
  quad(Vec3(1, -1, -1), Vec3(1, -1, 1), Vec3(1, 1, 1), Vec3(1, 1, -1));      // right
  g.meshes.push_back(std::move(walls));
  g.meshes.push_back(generated(GeneratedMeshKind::kSphere, 20000, 3, Vec3(0, 0, -0.6f), 0.35f));
  g.finalize();
  for (const SplitMethod split : {SplitMethod::kSah, SplitMethod::kSpatial}) {
    SCOPED_TRACE(split_name(split));
    BvhBuildSettings s;
    s.split = split;
    const BinaryBvh bvh = split == SplitMethod::kSpatial
                              ? build_spatial_split_bvh(g, make_prim_refs(g), s)
                              : build_object_split_bvh(make_prim_refs(g), g.sphere_geom_id(), s);
    const float root_area = bvh.nodes[0].bounds().area();
    size_t wall_leaves = 0;
    for (size_t i = 0; i < bvh.node_count; ++i) {
      const BinaryNode& node = bvh.nodes[i];
      if (!node.is_leaf() || node.bounds().area() < 0.25f * root_area) continue;
      ++wall_leaves;
      EXPECT_LE(node.count, 2u) << "a leaf as large as the room holds " << node.count
                                << " triangles: more than one wall";
    }
    EXPECT_GE(wall_leaves, 3u);
  }
}

// More references than the builders' parallel thresholds (64k for binning and for SBVH's
// clipping bins, 4096 for recursion): the parallel paths run, and the tree is the same on one
// thread as on four, node for node and block for block. ThreadSanitizer runs this test (label
// `threaded`, docs/RELIABILITY.md) to check those paths.
TEST(AccelWideBvh, LargeBuildsDoNotDependOnTheThreadCount) {
  SceneGeometry g;
  g.meshes.push_back(generated(GeneratedMeshKind::kSoup, 100'000, 11));
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 2000; ++i) g.spheres.push_back({Vec3(u(rng), u(rng), u(rng)), 0.01f, 0});
  g.finalize();
  ASSERT_GT(g.primitive_count(), 64u * 1024u);
  for (const SplitMethod split : {SplitMethod::kMedian, SplitMethod::kSah, SplitMethod::kSpatial}) {
    const auto build = [&](int threads) {
      const ThreadLimit limit(threads);
      BvhBuildSettings s;
      s.split = split;
      const BinaryBvh binary =
          split == SplitMethod::kSpatial
              ? build_spatial_split_bvh(g, make_prim_refs(g), s)
              : build_object_split_bvh(make_prim_refs(g), g.sphere_geom_id(), s);
      return collapse_to_wide<8>(binary, g);
    };
    const WideBvh<8> one = build(1);
    const WideBvh<8> four = build(4);
    SCOPED_TRACE(split_name(split));
    EXPECT_EQ(one.root, four.root);
    ASSERT_EQ(one.nodes.size(), four.nodes.size());
    for (size_t i = 0; i < one.nodes.size(); ++i) {
      ASSERT_EQ(0,
                std::memcmp(one.nodes[i].bounds, four.nodes[i].bounds, sizeof one.nodes[i].bounds))
          << "node " << i;
      ASSERT_EQ(0, std::memcmp(one.nodes[i].child, four.nodes[i].child, sizeof one.nodes[i].child))
          << "node " << i;
    }
    ASSERT_EQ(one.triangle_blocks.size(), four.triangle_blocks.size());
    EXPECT_EQ(0, std::memcmp(one.triangle_blocks.data(), four.triangle_blocks.data(),
                             one.triangle_blocks.size() * sizeof(TriangleBlock)));
    ASSERT_EQ(one.sphere_blocks.size(), four.sphere_blocks.size());
    EXPECT_EQ(0, std::memcmp(one.sphere_blocks.data(), four.sphere_blocks.data(),
                             one.sphere_blocks.size() * sizeof(SphereBlock)));
  }
}

TEST(AccelWideBvh, SpatialSplitsLowerTheSahCostOfSlivers) {
  SceneGeometry g;
  g.meshes.push_back(diagonal_slivers(4000, 3));
  g.finalize();
  ParamSet sah = bvh_params("sah", "bvh8", "generic");
  ParamSet sbvh = bvh_params("sbvh", "bvh8", "generic");
  WideBvhAccelerator a(parse_wide_bvh_options(sah)), b(parse_wide_bvh_options(sbvh));
  a.build(g);
  b.build(g);
  EXPECT_LT(b.stats().sah_cost, a.stats().sah_cost);
}

TEST(AccelWideBvh, WideNodesAreFullerThanBinaryOnes) {
  const std::vector<NamedScene> scenes = make_scenes();
  const SceneGeometry& g = scenes[0].geometry;
  BvhBuildSettings s;
  const BinaryBvh binary = build_object_split_bvh(make_prim_refs(g), g.sphere_geom_id(), s);
  const WideBvh<8> wide = collapse_to_wide<8>(binary, g);
  const WideBvh<4> wide4 = collapse_to_wide<4>(binary, g);
  EXPECT_LT(wide.stats.nodes, wide4.stats.nodes);
  EXPECT_LT(wide4.stats.nodes, binary.node_count / 2);
  EXPECT_EQ(wide.stats.leaves, wide4.stats.leaves);
  EXPECT_GT(wide.stats.bytes, 0u);
  EXPECT_GT(wide.stats.sah_cost, 0.0);
}

// --- parameters -----------------------------------------------------------------------------

TEST(AccelWideBvh, RejectsBadParameters) {
  auto kind_of = [](const ParamSet& p) {
    try {
      parse_wide_bvh_options(p);
    } catch (const Error& e) {
      return e.kind();
    }
    return ErrorKind::kInternal;
  };
  const std::pair<const char*, const char*> bad_values[] = {
      {"bvh.split", "octree"},     {"bvh.layout", "bvh16"},          {"bvh.bins", "1"},
      {"bvh.max_leaf_size", "65"}, {"bvh.reinsertion_passes", "17"}, {"bvh.isa", "neon"}};
  for (const auto& [key, value] : bad_values) {
    ParamSet params;
    params.set(key, value);
    EXPECT_EQ(kind_of(params), ErrorKind::kUsage) << key << "=" << value;
  }
  const WideBvhOptions o = parse_wide_bvh_options(bvh_params("sbvh", "bvh4", "generic"));
  EXPECT_EQ(o.build.split, SplitMethod::kSpatial);
  EXPECT_EQ(o.width, 4);
}

}  // namespace
}  // namespace prism
