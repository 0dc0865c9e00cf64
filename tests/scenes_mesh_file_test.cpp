#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "scenes/json_scene_loader.h"
#include "scenes/mesh_file_loader.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

/// A unit square in z = 0 plus a triangle above it: 5 vertices, 3 triangles.
const std::vector<Vec3> kPositions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 0.5f, 2}};
const std::vector<glm::uvec3> kTriangles = {{0, 1, 2}, {0, 2, 3}, {0, 1, 4}};

class ScenesMeshFile : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::make_temp_dir("mesh_file"); }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  /// Loads `file_name` through a JSON scene that references it, with an optional transform.
  TriangleMesh load_through_scene(const std::string& file_name, const std::string& transform = "") {
    const std::string scene = R"({
      "camera": {"position": [0, 0, 5], "target": [0, 0, 0], "fov": 45},
      "materials": [{"name": "grey", "type": "diffuse"}],
      "meshes": [{"material": "grey", "file": ")" +
                              file_name + "\"" +
                              (transform.empty() ? "" : ", \"transform\": " + transform) + "}]}";
    test::write_text(dir_ / "scene.json", scene);
    const Scene s = load_json_scene(dir_ / "scene.json");
    EXPECT_EQ(s.geometry.meshes.size(), 1u);
    return s.geometry.meshes.at(0);
  }

  /// Every triangle has the corners of kTriangles, in order, at kPositions + offset.
  static void expect_same_triangles(const TriangleMesh& mesh, Vec3 offset = Vec3(0.0f)) {
    ASSERT_EQ(mesh.triangle_count(), kTriangles.size());
    EXPECT_LE(mesh.positions.size(), kPositions.size() * 3);
    for (size_t t = 0; t < kTriangles.size(); ++t) {
      for (int c = 0; c < 3; ++c) {
        const Vec3 expected = kPositions[kTriangles[t][c]] + offset;
        const Vec3 got = mesh.positions[mesh.triangles[t][c]];
        EXPECT_NEAR(glm::length(got - expected), 0.0f, 1e-6f)
            << "triangle " << t << " corner " << c;
      }
    }
  }

  fs::path dir_;
};

std::string obj_text(bool with_normals) {
  std::string s = "# written by prism's tests\no test\n";
  for (const Vec3& p : kPositions) {
    s += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
  }
  if (with_normals) s += "vn 0 0 1\n";
  for (const auto& t : kTriangles) {
    s += "f";
    for (int c = 0; c < 3; ++c) {
      s += " " + std::to_string(t[c] + 1) + (with_normals ? "//1" : "");
    }
    s += "\n";
  }
  return s;
}

std::string ply_header(const std::string& format) {
  return "ply\nformat " + format + " 1.0\nelement vertex " + std::to_string(kPositions.size()) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
         std::to_string(kTriangles.size()) +
         "\nproperty list uchar int vertex_indices\nend_header\n";
}

TEST_F(ScenesMeshFile, ObjRoundTrip) {
  test::write_text(dir_ / "mesh.obj", obj_text(false));
  const TriangleMesh mesh = load_through_scene("mesh.obj");
  expect_same_triangles(mesh);
  EXPECT_TRUE(mesh.normals.empty());
  EXPECT_EQ(mesh.material_id, 0u);
}

TEST_F(ScenesMeshFile, ObjNormalsArePerCorner) {
  test::write_text(dir_ / "lit.obj", obj_text(true));
  const TriangleMesh mesh = load_mesh_file(dir_ / "lit.obj");
  expect_same_triangles(mesh);
  ASSERT_EQ(mesh.normals.size(), 3 * kTriangles.size());
  for (const Vec3& n : mesh.normals) EXPECT_EQ(n, Vec3(0, 0, 1));
  EXPECT_EQ(mesh.name, "lit.obj");
}

TEST_F(ScenesMeshFile, AsciiPlyRoundTripWithTransform) {
  std::string s = ply_header("ascii");
  for (const Vec3& p : kPositions) {
    s += std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
  }
  for (const auto& t : kTriangles)
    s += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) +
         "\n";
  test::write_text(dir_ / "mesh.ply", s);
  expect_same_triangles(load_through_scene("mesh.ply"));
  expect_same_triangles(load_through_scene("mesh.ply", R"({"translate": [1, 2, 3]})"),
                        Vec3(1, 2, 3));
}

TEST_F(ScenesMeshFile, BinaryPlyRoundTrip) {
  std::string s = ply_header("binary_little_endian");
  const auto append = [&s](const void* data, size_t n) {
    s.append(static_cast<const char*>(data), n);
  };
  for (const Vec3& p : kPositions) append(&p, sizeof(Vec3));  // x86-64 is little-endian
  for (const auto& t : kTriangles) {
    const uint8_t three = 3;
    append(&three, 1);
    for (int c = 0; c < 3; ++c) {
      const int32_t index = static_cast<int32_t>(t[c]);
      append(&index, 4);
    }
  }
  test::write_text(dir_ / "binary.ply", s);
  expect_same_triangles(load_through_scene("binary.ply"));
}

TEST_F(ScenesMeshFile, QuadsAreTriangulated) {
  test::write_text(dir_ / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const TriangleMesh mesh = load_mesh_file(dir_ / "quad.obj");
  EXPECT_EQ(mesh.triangle_count(), 2u);
  EXPECT_EQ(mesh.positions.size(), 4u);  // identical vertices are shared
}

TEST_F(ScenesMeshFile, LinesAndPointsAreDropped) {
  test::write_text(dir_ / "mixed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\np 3\nf 1 2 3\n");
  EXPECT_EQ(load_mesh_file(dir_ / "mixed.obj").triangle_count(), 1u);
}

void expect_input_error(const fs::path& path, const std::string& words) {
  try {
    load_mesh_file(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInput) << e.what();
    EXPECT_EQ(e.location().file, path.string());
    EXPECT_NE(e.message().find(words), std::string::npos) << e.what();
  }
}

TEST_F(ScenesMeshFile, BadFilesAreInputErrors) {
  expect_input_error(dir_ / "absent.obj", "not found");
  test::write_text(dir_ / "mesh.stl", "solid x\nendsolid x\n");
  expect_input_error(dir_ / "mesh.stl", "supported: .obj, .ply");
  test::write_text(dir_ / "points.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\n");
  expect_input_error(dir_ / "points.obj", "cannot read mesh file");
  test::write_text(dir_ / "lines.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nl 1 2\n");
  expect_input_error(dir_ / "lines.obj", "cannot read mesh file");
  test::write_text(dir_ / "garbage.obj", std::string("\x01\x02 garbage\n", 12));
  expect_input_error(dir_ / "garbage.obj", "cannot read mesh file");
  test::write_text(dir_ / "bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  expect_input_error(dir_ / "bad_index.obj", "cannot read mesh file");
  test::write_text(dir_ / "empty.ply", "");
  expect_input_error(dir_ / "empty.ply", "invalid PLY file");
}

// Assimp 5.2 hangs on some of these and reads others as garbage vertices: prism checks the
// structure itself first.
TEST_F(ScenesMeshFile, CorruptPlyFilesAreRejectedQuickly) {
  test::write_text(dir_ / "no_end.ply", "ply\nformat ascii 1.0\nelement vertex 3\ngarbage\n");
  expect_input_error(dir_ / "no_end.ply", "unexpected header line 'garbage'");
  test::write_text(dir_ / "open.ply", "ply\nformat ascii 1.0\nelement vertex 3\n");
  expect_input_error(dir_ / "open.ply", "no end_header");
  test::write_text(dir_ / "truncated.ply", ply_header("ascii") + "0 0 0\n1 0\n");
  expect_input_error(dir_ / "truncated.ply", "wrong number of values");
  test::write_text(dir_ / "short.ply", ply_header("ascii") + "0 0 0\n1 0 0\n");
  expect_input_error(dir_ / "short.ply", "truncated");
  std::string lying = ply_header("ascii");
  for (const Vec3& p : kPositions) lying += std::to_string(p.x) + " 0 0\n";
  lying += "9 0 1 2\n";  // claims nine corners, gives three
  test::write_text(dir_ / "lying.ply", lying);
  expect_input_error(dir_ / "lying.ply", "wrong number of values");
  test::write_text(dir_ / "binary.ply", ply_header("binary_little_endian") + std::string(7, '\0'));
  expect_input_error(dir_ / "binary.ply", "truncated");
  test::write_text(dir_ / "format.ply", "ply\nformat utf8 1.0\nend_header\n");
  expect_input_error(dir_ / "format.ply", "unknown format");
  fs::create_directory(dir_ / "folder.obj");
  expect_input_error(dir_ / "folder.obj", "not a regular file");
}

}  // namespace
}  // namespace prism
