#pragma once

// Helpers shared by the tests of the prism program (tests/app_*_test.cpp, and the colour tests
// that run it): scenes to render, per-test folders, the one-line error contract, image files.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "color/color_pipeline.h"
#include "color/image_output.h"
#include "tests/support/test_support.h"

namespace prism::test {

/// A small CS184-dialect COLLADA scene written for these tests: a floor and a back wall (4
/// triangles), a point light, a camera. Renders in milliseconds at 32 x 24.
inline const std::string kTinyCollada = R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><up_axis>Z_UP</up_axis></asset>
  <library_cameras>
    <camera id="cam"><optics><technique_common><perspective>
      <xfov>50</xfov><aspect_ratio>1.333333</aspect_ratio><znear>0.1</znear><zfar>100</zfar>
    </perspective></technique_common></optics></camera>
  </library_cameras>
  <library_lights>
    <light id="lamp"><technique_common><point>
      <color>1 1 1</color><constant_attenuation>1</constant_attenuation>
      <linear_attenuation>0</linear_attenuation><quadratic_attenuation>0</quadratic_attenuation>
    </point></technique_common></light>
  </library_lights>
  <library_effects>
    <effect id="grey-effect"><profile_COMMON><technique sid="common"><phong>
      <diffuse><color sid="diffuse">0.6 0.6 0.6 1</color></diffuse>
    </phong></technique></profile_COMMON></effect>
  </library_effects>
  <library_materials>
    <material id="grey-material" name="grey"><instance_effect url="#grey-effect"/></material>
  </library_materials>
  <library_geometries>
    <geometry id="box-mesh" name="box"><mesh>
      <source id="box-positions">
        <float_array id="box-positions-array" count="24">-1 -1 0 1 -1 0 1 1 0 -1 1 0 -1 1 0 1 1 0 1 1 2 -1 1 2</float_array>
        <technique_common><accessor source="#box-positions-array" count="8" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common>
      </source>
      <vertices id="box-vertices"><input semantic="POSITION" source="#box-positions"/></vertices>
      <polylist material="grey-symbol" count="4">
        <input semantic="VERTEX" source="#box-vertices" offset="0"/>
        <vcount>3 3 3 3</vcount>
        <p>0 1 2 0 2 3 4 5 6 4 6 7</p>
      </polylist>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="Scene" name="Scene">
      <node id="Camera" name="Camera" type="NODE">
        <matrix sid="transform">1 0 0 0 0 0 -1 -3 0 1 0 1 0 0 0 1</matrix>
        <instance_camera url="#cam"/>
      </node>
      <node id="Lamp" name="Lamp" type="NODE">
        <matrix sid="transform">1 0 0 0 0 1 0 0 0 0 1 1.5 0 0 0 1</matrix>
        <instance_light url="#lamp"/>
      </node>
      <node id="Box" name="Box" type="NODE">
        <matrix sid="transform">1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1</matrix>
        <instance_geometry url="#box-mesh"><bind_material><technique_common>
          <instance_material symbol="grey-symbol" target="#grey-material"/>
        </technique_common></bind_material></instance_geometry>
      </node>
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#Scene"/></scene>
</COLLADA>
)";

/// `text` with the one occurrence of `from` replaced by `to` (fails the test when absent).
inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "'" << from << "' not in the scene text";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

/// A fresh folder pair for one test: `in` for scene files, `out` for what prism writes.
struct TestDirs {
  std::filesystem::path root, in, out;
  explicit TestDirs(const std::string& tag) : root(make_temp_dir(tag)) {
    in = root / "in";
    out = root / "out";
    std::filesystem::create_directories(in);
    std::filesystem::create_directories(out);
  }
  ~TestDirs() {
    std::error_code ec;
    std::filesystem::permissions(out, std::filesystem::perms::owner_all, ec);
    std::filesystem::remove_all(root, ec);
  }
  /// Writes `text` to in/`name` and returns the path as a string.
  std::string scene(const std::string& name, const std::string& text) const {
    write_text(in / name, text);
    return (in / name).string();
  }
};

/// Names of the entries of `dir` (files and folders), sorted.
inline std::vector<std::string> dir_entries(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    names.push_back(e.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

/// Number of lines (newline characters) of `text`, e.g. of a command's output.
inline size_t line_count(const std::string& text) {
  return size_t(std::count(text.begin(), text.end(), '\n'));
}

/// The contract for every rejected input: the exit code, exactly one line on stderr starting
/// "prism: error: " and containing every string of `mentions`.
inline void expect_one_line_error(const ProgramResult& r, int exit_code,
                                  const std::vector<std::string>& mentions) {
  EXPECT_EQ(r.exit_code, exit_code) << "stderr: " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "stderr: " << r.err;
  EXPECT_TRUE(!r.err.empty() && r.err.back() == '\n') << "stderr: " << r.err;
  EXPECT_EQ(r.err.rfind("prism: error: ", 0), 0u) << "stderr: " << r.err;
  for (const auto& m : mentions) {
    EXPECT_NE(r.err.find(m), std::string::npos) << "stderr lacks '" << m << "': " << r.err;
  }
}

/// Options of the bundled colour config, whatever the caller's environment: unsets $OCIO (for
/// the rest of the process).
inline ColorOptions bundled_config() {
  unsetenv("OCIO");  // the bundled config, whatever the caller's environment
  return {};
}

/// A Portable Float Map (colour, little-endian) holding `values` (width * height * 3, top row
/// first); PFM stores rows bottom to top. The one float format that needs no library to write
/// and may hold NaN and infinity.
inline void write_pfm(const std::filesystem::path& path, int width, int height,
                      const std::vector<float>& values) {
  std::ofstream out(path, std::ios::binary);
  out << "PF\n" << width << " " << height << "\n-1.0\n";
  for (int y = height - 1; y >= 0; --y) {
    out.write(reinterpret_cast<const char*>(values.data() + size_t(y) * width * 3),
              std::streamsize(sizeof(float) * width * 3));
  }
}

/// Renders `scene` at 64 x 48 into `out` (float EXR: every bit of the film's means), with
/// `args` added, expects exit 0 and returns the file read back.
inline ImageFileContents render_small_float_exr(const std::filesystem::path& scene,
                                                const std::filesystem::path& out,
                                                const std::vector<std::string>& args) {
  std::vector<std::string> all = {"render",     "-q",    "-r",           "64", "48",
                                  "--exr-type", "float", scene.string(), "-f", out.string()};
  all.insert(all.end(), args.begin(), args.end());
  const ProgramResult r = run_prism(all);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return read_image_file(out);
}

}  // namespace prism::test
