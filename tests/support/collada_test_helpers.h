#pragma once

// Helpers of the COLLADA loader tests (scenes_collada_test.cpp, scenes_collada_errors_test.cpp):
// a small base document to edit, loading text through a temporary file, and the contract of a
// rejected document.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "scenes/scene_loader.h"
#include "tests/support/test_support.h"

namespace prism::test::collada {

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Replaces the first `from` in `text` (which must be there, so a test cannot silently test the
// unmodified document).
inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test document lacks: " << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// 1-based line of the first occurrence of `needle` in `text`.
inline int line_of(const std::string& text, const std::string& needle) {
  const size_t at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
}

inline Scene load_text(const std::string& text, const SceneLoadOptions& options = {}) {
  // The folder goes away on every way out, a thrown Error included.
  struct RemoveDir {
    std::filesystem::path dir;
    ~RemoveDir() {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  };
  const RemoveDir guard{make_temp_dir("collada")};
  const auto path = guard.dir / "scene.dae";
  write_text(path, text);
  return load_scene(path, options);
}

// Loads `text`, expects Error(kInput) whose one-line message contains every `needle`, and
// returns its location line.
inline int expect_input_error(const std::string& text, const std::vector<std::string>& needles) {
  try {
    load_text(text);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInput) << e.what();
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << "not one line: " << what;
    for (const auto& needle : needles) {
      EXPECT_NE(what.find(needle), std::string::npos) << "'" << needle << "' not in: " << what;
    }
    return e.location().line;
  }
  ADD_FAILURE() << "no error for the document";
  return -1;
}

// One triangle bound to a lambert material; every piece on its own line so tests can edit it.
inline constexpr const char* kBase = R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<asset>
<up_axis>Z_UP</up_axis>
</asset>
<library_effects>
<effect id="red-effect"><profile_COMMON><technique sid="common"><lambert><diffuse><color>0.8 0.1 0.1 1</color></diffuse></lambert></technique></profile_COMMON></effect>
</library_effects>
<library_materials>
<material id="red" name="red"><instance_effect url="#red-effect"/></material>
</library_materials>
<library_geometries>
<geometry id="tri">
<mesh>
<source id="tri-pos">
<float_array id="tri-pos-array" count="9">0 0 0 1 0 0 0 1 0</float_array>
<technique_common><accessor source="#tri-pos-array" count="3" stride="3"/></technique_common>
</source>
<vertices id="tri-vtx"><input semantic="POSITION" source="#tri-pos"/></vertices>
<polylist material="mat" count="1">
<input semantic="VERTEX" source="#tri-vtx" offset="0"/>
<vcount>3</vcount>
<p>0 1 2</p>
</polylist>
</mesh>
</geometry>
<geometry id="ball"><extra><technique profile="CGL"><sphere><radius>0.5</radius></sphere></technique></extra></geometry>
</library_geometries>
<library_visual_scenes>
<visual_scene id="Scene">
<node id="n">
<instance_geometry url="#tri"><bind_material><technique_common><instance_material symbol="mat" target="#red"/></technique_common></bind_material></instance_geometry>
</node>
<node id="s"><translate>0 0 2</translate><instance_geometry url="#ball"/></node>
</visual_scene>
</library_visual_scenes>
<scene><instance_visual_scene url="#Scene"/></scene>
</COLLADA>
)";

}  // namespace prism::test::collada
