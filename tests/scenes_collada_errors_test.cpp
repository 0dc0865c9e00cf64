// The CS184 COLLADA loader's bad-input contract: one test per class of malformed or hostile
// document, each a single-line Error(kInput) naming the file, line and element.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/error.h"
#include "tests/support/collada_test_helpers.h"

namespace prism {
namespace {

using test::collada::expect_input_error;
using test::collada::kBase;
using test::collada::line_of;
using test::collada::replaced;

TEST(ScenesColladaErrors, MalformedXml) {
  const std::string text = replaced(kBase, "<p>0 1 2</p>", "<p>0 1 2</q>");
  const int line = expect_input_error(text, {"malformed XML", "mismatch"});
  EXPECT_EQ(line, line_of(text, "</q>"));
  EXPECT_GT(expect_input_error("", {"malformed XML"}), 0);
  expect_input_error("\x01\x02garbage<<>>", {"malformed XML"});
  EXPECT_EQ(expect_input_error("<?xml version=\"1.0\"?>\n<scene/>\n", {"<scene>", "COLLADA"}), 2);
}

TEST(ScenesColladaErrors, MissingOrUnknownUpAxis) {
  const std::string missing = replaced(kBase, "<up_axis>Z_UP</up_axis>\n", "");
  EXPECT_EQ(expect_input_error(missing, {"<asset>", "up_axis"}), line_of(missing, "<asset>"));
  const std::string unknown = replaced(kBase, "Z_UP", "W_UP");
  EXPECT_EQ(expect_input_error(unknown, {"<up_axis>", "'W_UP'"}), line_of(unknown, "W_UP"));
  // Windows line endings count lines the same way.
  std::string crlf;
  for (char c : unknown) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  EXPECT_EQ(expect_input_error(crlf, {"'W_UP'"}), line_of(unknown, "W_UP"));
}

TEST(ScenesColladaErrors, DanglingReferencesNameTheId) {
  struct Case {
    std::string from, to;
    std::vector<std::string> needles;
    std::string at;  // text on the line the error must point at
  };
  const std::vector<Case> cases = {
      {"url=\"#tri\"", "url=\"#nope\"", {"'nope'", "<instance_geometry"}, "#nope"},
      {"target=\"#red\"", "target=\"#ghost\"", {"'ghost'", "<instance_material"}, "#ghost"},
      {"source=\"#tri-pos\"/>", "source=\"#lost\"/>", {"'lost'", "<input"}, "#lost"},
      {"source=\"#tri-pos-array\"",
       "source=\"#no-array\"",
       {"'no-array'", "<accessor"},
       "#no-array"},
      {"url=\"#red-effect\"",
       "url=\"#no-effect\"",
       {"'no-effect'", "<instance_effect"},
       "#no-effect"},
      {"url=\"#Scene\"", "url=\"#NoScene\"", {"'NoScene'", "<instance_visual_scene"}, "#NoScene"},
      {"<translate>0 0 2</translate>", "<instance_light url=\"#lamp\"/>", {"'lamp'"}, "#lamp"},
      {"url=\"#tri\"",
       "url=\"#red\"",
       {"'#red' names a <material>, expected <geometry>"},
       "url=\"#red\""},
      {"url=\"#tri\"", "url=\"other.dae#tri\"", {"other.dae#tri", "local reference"}, "other.dae"},
      {"symbol=\"mat\"",
       "symbol=\"other\"",
       {"symbol 'mat'", "<polylist material=\"mat\">"},
       "other"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.to);
    const std::string text = replaced(kBase, c.from, c.to);
    EXPECT_EQ(expect_input_error(text, c.needles), line_of(text, c.at));
  }
}

TEST(ScenesColladaErrors, WrongCounts) {
  // A <float_array count> that disagrees with its numbers is a warning, as the homework reads
  // such files (ScenesCollada.FloatArrayCountDisagreeingWithItsNumbers); what the accessor and
  // the indices read must be there.
  const std::string past = replaced(kBase, "count=\"3\" stride=\"3\"", "count=\"4\" stride=\"3\"");
  EXPECT_EQ(expect_input_error(past, {"<accessor", "reads past the end", "tri-pos-array"}),
            line_of(past, "count=\"4\""));
  expect_input_error(
      replaced(kBase, "count=\"3\" stride=\"3\"", "count=\"18446744073709551615\" stride=\"3\""),
      {"reads past the end"});
  expect_input_error(replaced(kBase, "count=\"3\" stride=\"3\"", "count=\"3\" stride=\"0\""),
                     {"stride 0 is too small"});
  expect_input_error(replaced(kBase, "count=\"9\"", "count=\"nine\""),
                     {"count=\"nine\"", "integer"});
}

TEST(ScenesColladaErrors, NonNumericAndNonFiniteNumbers) {
  const std::string array = "0 0 0 1 0 0 0 1 0";
  for (const std::string bad :
       {"zero", "nan", "NaN", "inf", "-Infinity", "1e999", "0x1p3", "1,5"}) {
    SCOPED_TRACE(bad);
    // The bad token sits on the float_array's second line; the error points there.
    const std::string text = replaced(kBase, array, "0 0 0 1 0 0\n0 " + bad + " 0");
    EXPECT_EQ(expect_input_error(text, {"'" + bad + "'", "tri-pos-array"}),
              line_of(text, "tri-pos-array\"") + 1);
  }
  const std::string transform =
      replaced(kBase, "<translate>0 0 2</translate>", "<translate>0 NaN 2</translate>");
  EXPECT_EQ(expect_input_error(transform, {"'NaN'", "<translate>"}), line_of(transform, "NaN"));
  // A colour short of numbers is a warning (ScenesCollada.ColourWithMissingOrExtraNumbers); one
  // with none at all crashes the homework.
  const std::string empty = replaced(kBase, "0.8 0.1 0.1 1", "");
  EXPECT_EQ(expect_input_error(empty, {"<color>", "3 or 4 numbers", "found 0"}),
            line_of(empty, "<color>"));
  expect_input_error(replaced(kBase, "0.8 0.1 0.1 1", "0.8 -0.1 0.1 1"), {"<color>", ">= 0"});
}

TEST(ScenesColladaErrors, ShortMatrixAboveGeometry) {
  // The homework reads the missing numbers as 0 and divides vertices by the w that leaves 0:
  // the geometry is lost, so prism refuses (cameras and lights read the top rows only, and
  // warn: ScenesCollada.ShortCameraMatrixFramesAsTheHomework).
  const std::string matrix = "<matrix>1 0 0 0 0 1 0 0 0 0 1 0 0 0 0</matrix>";
  const std::string text = replaced(kBase, "<node id=\"n\">", "<node id=\"n\">\n" + matrix);
  EXPECT_EQ(expect_input_error(text, {"<matrix>", "15 numbers, not 16",
                                      "<instance_geometry url=\"#tri\"> at line " +
                                          std::to_string(line_of(text, "url=\"#tri\""))}),
            line_of(text, matrix));
  // Geometry in a nested node counts too, and so does an <instance_node>, which may hold some.
  const std::string nested = replaced(kBase, "<node id=\"n\">",
                                      "<node id=\"outer\">\n" + matrix + "<node><node id=\"n\">");
  EXPECT_EQ(expect_input_error(replaced(nested, "</node>", "</node></node></node>"),
                               {"15 numbers, not 16", "#tri"}),
            line_of(nested, matrix));
  expect_input_error(
      replaced(kBase, "<node id=\"s\">",
               "<node>" + matrix + "<instance_node url=\"#s\"/></node><node id=\"s\">"),
      {"15 numbers, not 16", "<instance_node url=\"#s\">"});
  // An empty <matrix> crashes the homework.
  const std::string empty = replaced(kBase, "<node id=\"n\">", "<node id=\"n\">\n<matrix/>");
  EXPECT_EQ(expect_input_error(empty, {"<matrix>", "expected 16 numbers, found 0"}),
            line_of(empty, "<matrix/>"));
}

TEST(ScenesColladaErrors, IndexOutOfRange) {
  const std::string text = replaced(kBase, "<p>0 1 2</p>", "<p>0 1 7</p>");
  EXPECT_EQ(expect_input_error(text, {"index 7", "VERTEX", "out of range", "<p>"}),
            line_of(text, "<p>"));
  expect_input_error(replaced(kBase, "<p>0 1 2</p>", "<p>0 -1 2</p>"), {"'-1'", "<p>"});
  expect_input_error(replaced(kBase, "<p>0 1 2</p>", "<p>0 1 4294967296</p>"), {"'4294967296'"});
}

TEST(ScenesColladaErrors, VcountAndPLengthMismatch) {
  const std::string text = replaced(kBase, "<vcount>3</vcount>", "<vcount>4</vcount>");
  EXPECT_EQ(expect_input_error(text, {"<p>", "holds 3 indices", "<vcount> needs 4"}),
            line_of(text, "<p>"));
  expect_input_error(replaced(kBase, "<vcount>3</vcount>", "<vcount>4294967295</vcount>"),
                     {"<vcount> needs 4294967295"});
  const std::string small = replaced(kBase, "<vcount>3</vcount>", "<vcount>2</vcount>");
  EXPECT_EQ(expect_input_error(small, {"<vcount>", "at least 3"}), line_of(small, "<vcount>2"));
  expect_input_error(replaced(kBase, "<polylist material=\"mat\" count=\"1\">",
                              "<polylist material=\"mat\" count=\"2\">"),
                     {"count=\"2\"", "1 <vcount> entries"});
}

TEST(ScenesColladaErrors, MissingVisualScene) {
  const std::string no_scene =
      replaced(kBase, "<scene><instance_visual_scene url=\"#Scene\"/></scene>\n", "");
  EXPECT_EQ(expect_input_error(no_scene, {"<COLLADA>", "visual scene"}),
            line_of(no_scene, "<COLLADA"));
  const std::string empty = replaced(kBase, "<instance_visual_scene url=\"#Scene\"/>", "");
  EXPECT_EQ(expect_input_error(empty, {"<scene>", "instance_visual_scene"}),
            line_of(empty, "<scene>"));
}

TEST(ScenesColladaErrors, SphereRadiusMustBePositive) {
  for (const std::string radius : {"-1", "0", "-0"}) {
    SCOPED_TRACE(radius);
    const std::string text =
        replaced(kBase, "<radius>0.5</radius>", "<radius>" + radius + "</radius>");
    EXPECT_EQ(expect_input_error(text, {"<radius>", "positive"}), line_of(text, "<radius>"));
  }
  // Finite as a double, infinite as the float it is stored in.
  expect_input_error(replaced(kBase, "<radius>0.5</radius>", "<radius>1e300</radius>"),
                     {"<radius>", "'1e300'", "too large"});
}

TEST(ScenesColladaErrors, HostileStructureFailsCleanly) {
  // Nesting far deeper than any real file.
  std::string deep;
  for (int i = 0; i < 300; ++i) deep += "<node>";
  for (int i = 0; i < 300; ++i) deep += "</node>";
  expect_input_error(replaced(kBase, "<node id=\"n\">", deep + "<node id=\"n\">"),
                     {"deeper than 256"});
  // A node that instantiates itself.
  expect_input_error(
      replaced(kBase, "<node id=\"n\">", "<node id=\"n\"><instance_node url=\"#n\"/>"),
      {"deeper than 256"});
  // Doubling fan-out: 2^40 instances from 40 small nodes.
  std::string chain = "<library_nodes>\n";
  for (int i = 0; i < 40; ++i) {
    chain += "<node id=\"c" + std::to_string(i) + "\"><instance_node url=\"#c" +
             std::to_string(i + 1) + "\"/><instance_node url=\"#c" + std::to_string(i + 1) +
             "\"/></node>\n";
  }
  chain += "<node id=\"c40\"/>\n</library_nodes>\n<library_visual_scenes>";
  std::string fan = replaced(kBase, "<library_visual_scenes>", chain);
  expect_input_error(
      replaced(fan, "<node id=\"s\">", "<node><instance_node url=\"#c0\"/></node><node id=\"s\">"),
      {"more than 1000000 nodes"});
  // Unsupported primitives and transforms say so instead of silently dropping geometry.
  const std::string polygons = replaced(kBase, "<polylist material=\"mat\" count=\"1\">",
                                        "<polygons material=\"mat\" count=\"1\">");
  expect_input_error(replaced(polygons, "</polylist>", "</polygons>"),
                     {"<polygons", "not supported"});
  expect_input_error(replaced(kBase, "<translate>0 0 2</translate>", "<skew>45 0 1 0 1 0 0</skew>"),
                     {"<skew>", "not supported"});
}

TEST(ScenesColladaErrors, BadMaterialAndLightValues) {
  const std::string cgl = "<extra><technique profile=\"CGL\">";
  const std::string effect = "<effect id=\"red-effect\">";
  expect_input_error(replaced(kBase, effect, effect + cgl + "<velvet/></technique></extra>"),
                     {"<velvet>", "unknown CGL material"});
  expect_input_error(
      replaced(kBase, effect, effect + cgl + "<glass><ior>-1</ior></glass></technique></extra>"),
      {"<ior>", "> 0"});
  const std::string lights =
      "<library_lights><light id=\"l\"><technique_common><point><color>1 1 1</color>"
      "<constant_attenuation>0</constant_attenuation></point></technique_common></light></"
      "library_lights>\n"
      "<library_geometries>";
  std::string text = replaced(kBase, "<library_geometries>", lights);
  text = replaced(text, "<translate>0 0 2</translate>", "<instance_light url=\"#l\"/>");
  expect_input_error(text, {"<point>", "attenuation are all zero"});
}

}  // namespace
}  // namespace prism
