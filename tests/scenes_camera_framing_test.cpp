// The homework's camera framing for .dae scenes, recomputed here from the file with pugixml and
// plain double arithmetic (not the loader's code), plus the literal-camera option and
// Camera::fit_to_aspect on the loaded fields of view.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <pugixml.hpp>

#include "core/camera.h"
#include "scenes/scene_loader.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

using Vec = std::array<double, 3>;
using Matrix = std::array<double, 16>;  // row-major, as COLLADA writes it

std::vector<double> numbers(const char* text) {
  std::istringstream in(text);
  std::vector<double> out;
  for (double v; in >> v;) out.push_back(v);
  return out;
}

Vec apply(const Matrix& m, const Vec& p, double w) {
  Vec out{};
  for (size_t row = 0; row < 3; ++row) {
    out[row] =
        m[4 * row] * p[0] + m[4 * row + 1] * p[1] + m[4 * row + 2] * p[2] + m[4 * row + 3] * w;
  }
  return out;
}

double norm(const Vec& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

pugi::xml_node by_url(const pugi::xml_document& doc, const char* url) {
  const std::string id = std::string(url).substr(1);
  return doc.find_node([&](pugi::xml_node n) { return id == n.attribute("id").value(); });
}

Matrix node_matrix(pugi::xml_node node) {
  const std::vector<double> v = numbers(node.child_value("matrix"));
  EXPECT_EQ(v.size(), 16u) << "the shared files give each node one <matrix>";
  Matrix m{};
  std::copy_n(v.begin(), std::min<size_t>(16, v.size()), m.begin());
  return m;
}

struct Framing {
  Vec target, position, literal_position, literal_forward;
  double r = 0.0;
};

// The homework's rule, from the file: the bounding box of every vertex the polylists use
// (through each node's matrix), r = 1.5 |diagonal|, c = normalize(M (0,0,-1,1)).
Framing framing_from_file(const std::filesystem::path& path) {
  pugi::xml_document doc;
  EXPECT_TRUE(doc.load_file(path.c_str()));
  EXPECT_STREQ(doc.child("COLLADA").child("asset").child_value("up_axis"), "Z_UP");
  Vec lower{1e300, 1e300, 1e300}, upper{-1e300, -1e300, -1e300};
  Framing f;
  for (const pugi::xpath_node& x : doc.select_nodes("//visual_scene/node")) {
    const pugi::xml_node node = x.node();
    const Matrix m = node_matrix(node);
    if (node.child("instance_camera")) {
      const Vec front = apply(m, {0, 0, -1}, 1.0);
      const double length = norm(front);
      f.position = {front[0] / length, front[1] / length, front[2] / length};  // c, for now
      f.literal_position = apply(m, {0, 0, 0}, 1.0);
      f.literal_forward = apply(m, {0, 0, -1}, 0.0);
    }
    const pugi::xml_node instance = node.child("instance_geometry");
    if (!instance) continue;
    const pugi::xml_node mesh = by_url(doc, instance.attribute("url").value()).child("mesh");
    const pugi::xml_node position_source =
        by_url(doc, mesh.child("vertices")
                        .find_child_by_attribute("input", "semantic", "POSITION")
                        .attribute("source")
                        .value());
    const std::vector<double> xyz = numbers(position_source.child_value("float_array"));
    for (pugi::xml_node polylist : mesh.children("polylist")) {
      int stride = 0, vertex_offset = 0;
      for (pugi::xml_node input : polylist.children("input")) {
        stride = std::max(stride, input.attribute("offset").as_int() + 1);
        if (std::string(input.attribute("semantic").value()) == "VERTEX") {
          vertex_offset = input.attribute("offset").as_int();
        }
      }
      const std::vector<double> p = numbers(polylist.child_value("p"));
      for (size_t i = vertex_offset; i < p.size(); i += stride) {
        const size_t v = static_cast<size_t>(p[i]);
        const Vec world = apply(m, {xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]}, 1.0);
        for (int k = 0; k < 3; ++k) {
          lower[k] = std::min(lower[k], world[k]);
          upper[k] = std::max(upper[k], world[k]);
        }
      }
    }
  }
  const Vec c = f.position;
  const Vec diagonal{upper[0] - lower[0], upper[1] - lower[1], upper[2] - lower[2]};
  f.r = 1.5 * norm(diagonal);
  for (int k = 0; k < 3; ++k) {
    f.target[k] = 0.5 * (lower[k] + upper[k]);
    f.position[k] = f.target[k] + f.r * c[k];
  }
  return f;
}

void expect_close(const Vec3& actual, const Vec& expected, double scale, const char* what) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(actual[k], expected[k], 1e-4 * scale) << what << " component " << k;
  }
}

TEST(ScenesCameraFraming, CBbunnyMatchesTheHomeworkRule) {
  PRISM_REQUIRE_CS184(path, "CBbunny.dae");
  const Framing expected = framing_from_file(path);
  const Scene scene = load_scene(path);
  expect_close(scene.camera.target, expected.target, expected.r, "target");
  expect_close(scene.camera.position, expected.position, expected.r, "position");
  EXPECT_EQ(scene.camera.up, Vec3(0, 0, 1));
  EXPECT_EQ(scene.settings.width, 480);
  EXPECT_EQ(scene.settings.height, 360);

  // By hand: the walls span x, y in [-1, 1] and z in [0, 1.5] (the bunny sits inside), the
  // camera matrix's point one unit ahead is (0, -2, 0), so c = (0, -1, 0) and
  // r = 1.5 sqrt(2^2 + 2^2 + 1.5^2).
  const double r = 1.5 * std::sqrt(4.0 + 4.0 + 2.25);
  EXPECT_NEAR(expected.r, r, 1e-4 * r);
  expect_close(scene.camera.target, {0.0, 0.0, 0.75}, r, "target by hand");
  expect_close(scene.camera.position, {0.0, -r, 0.75}, r, "position by hand");
}

TEST(ScenesCameraFraming, LiteralCameraUsesTheNode) {
  PRISM_REQUIRE_CS184(path, "CBbunny.dae");
  const Framing expected = framing_from_file(path);
  SceneLoadOptions options;
  options.literal_camera = true;
  const Scene scene = load_scene(path, options);
  expect_close(scene.camera.position, expected.literal_position, 1.0, "literal position");
  expect_close(scene.camera.position, {0.0, -3.0, 0.0}, 1.0, "literal position by hand");
  const Vec3 forward = glm::normalize(scene.camera.target - scene.camera.position);
  const double length = norm(expected.literal_forward);
  expect_close(forward,
               {expected.literal_forward[0] / length, expected.literal_forward[1] / length,
                expected.literal_forward[2] / length},
               1.0, "literal forward");
  expect_close(scene.camera.up, {0.0, 0.0, 1.0}, 1.0, "literal up (the node's +Y)");
}

double tan_half(float degrees) { return std::tan(degrees * kPi / 360.0); }

TEST(ScenesCameraFraming, FieldsOfViewComeFromTheFile) {
  PRISM_REQUIRE_CS184(path, "CBbunny.dae");
  const Scene scene = load_scene(path);
  // xfov 49.13434 with aspect_ratio 1.777778 and no yfov.
  EXPECT_NEAR(scene.camera.hfov_deg, 49.13434f, 1e-4f);
  EXPECT_NEAR(tan_half(scene.camera.hfov_deg) / tan_half(scene.camera.vfov_deg), 1.777778, 1e-5);
}

TEST(ScenesCameraFraming, FitToAspectWidensNeverNarrows) {
  PRISM_REQUIRE_CS184(path, "CBbunny.dae");
  const Camera original = load_scene(path).camera;
  for (const float aspect : {0.5f, 1.0f, 480.0f / 360.0f, 1.777778f, 2.5f}) {
    SCOPED_TRACE(aspect);
    Camera fitted = original;
    fitted.fit_to_aspect(aspect);
    EXPECT_GE(fitted.hfov_deg, original.hfov_deg - 1e-5f);
    EXPECT_GE(fitted.vfov_deg, original.vfov_deg - 1e-5f);
    // Exactly one of the two changes (or neither, at the file's own aspect).
    EXPECT_TRUE(fitted.hfov_deg == original.hfov_deg || fitted.vfov_deg == original.vfov_deg);
    EXPECT_NEAR(tan_half(fitted.hfov_deg) / tan_half(fitted.vfov_deg), aspect, 1e-4 * aspect);
  }
  // The homework's 480 x 360 is narrower than the file's 16:9, so the vertical fov widens.
  Camera homework = original;
  homework.fit_to_aspect(480.0f / 360.0f);
  EXPECT_EQ(homework.hfov_deg, original.hfov_deg);
  EXPECT_GT(homework.vfov_deg, original.vfov_deg + 1.0f);
}

}  // namespace
}  // namespace prism
