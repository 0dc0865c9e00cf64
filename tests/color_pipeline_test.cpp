// ColorPipeline against published colorimetry: config choice, names, conversions, display views.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>

#include "color/color_pipeline.h"
#include "core/error.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

// Runs a test with $OCIO as the test sets it (unset by default) and puts it back afterwards:
// every test starts with one. (A fixture would have to be named ColorPipeline, after the file,
// and would hide the class under test.)
class OcioEnv {
 public:
  OcioEnv() {
    if (const char* v = std::getenv("OCIO")) saved_ = v;
    unsetenv("OCIO");
  }
  ~OcioEnv() {
    if (saved_) {
      setenv("OCIO", saved_->c_str(), 1);
    } else {
      unsetenv("OCIO");
    }
  }
  void set(const std::string& value) { setenv("OCIO", value.c_str(), 1); }

 private:
  std::optional<std::string> saved_;
};

// Published linear Rec.709 (sRGB) -> ACEScg matrix: Rec.709 primaries and D65 white
// (0.3127, 0.3290) to AP1 primaries (0.713, 0.293), (0.165, 0.830), (0.128, 0.044) with the ACES
// white (0.32168, 0.33767), Bradford chromatic adaptation (as in colour-science and the ACES CG
// config). Rows are output channels.
constexpr double kRec709ToAcescg[3][3] = {
    {0.6130974024, 0.3395231462, 0.0473794514},
    {0.0701937225, 0.9163538791, 0.0134523985},
    {0.0206155929, 0.1095697729, 0.8698146342},
};
// Linear Rec.709 -> ACES2065-1 as the ACES studio config (OpenColorIO-Config-ACES) writes it.
constexpr double kRec709ToAces2065[3][3] = {
    {0.439632981919491, 0.382988698151554, 0.177378319928955},
    {0.0897764429588424, 0.813439428748981, 0.0967841282921771},
    {0.0175411703831727, 0.111546553302387, 0.87091227631444},
};

Rgb mul(const double m[3][3], const Rgb& c) {
  Rgb out;
  for (int i = 0; i < 3; ++i) out[i] = float(m[i][0] * c.x + m[i][1] * c.y + m[i][2] * c.z);
  return out;
}

// The matrix again from first principles (SMPTE RP 177 + Bradford), so the constants above are
// checked too.
glm::dmat3 derive_rec709_to_acescg() {
  auto xyz = [](double x, double y) { return glm::dvec3(x / y, 1.0, (1.0 - x - y) / y); };
  auto npm = [&](glm::dvec2 r, glm::dvec2 g, glm::dvec2 b, glm::dvec2 w) {
    const glm::dmat3 p(xyz(r.x, r.y), xyz(g.x, g.y), xyz(b.x, b.y));
    const glm::dvec3 s = glm::inverse(p) * xyz(w.x, w.y);
    return glm::dmat3(p[0] * s.x, p[1] * s.y, p[2] * s.z);
  };
  const glm::dvec2 d65(0.3127, 0.3290), aces(0.32168, 0.33767);
  const glm::dmat3 rec709 = npm({0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}, d65);
  const glm::dmat3 ap1 = npm({0.713, 0.293}, {0.165, 0.830}, {0.128, 0.044}, aces);
  const glm::dmat3 bfd = glm::transpose(
      glm::dmat3(0.8951, 0.2664, -0.1614, -0.7502, 1.7135, 0.0367, 0.0389, -0.0685, 1.0296));
  const glm::dvec3 from = bfd * xyz(d65.x, d65.y), to = bfd * xyz(aces.x, aces.y);
  glm::dmat3 scale(1.0);
  for (int i = 0; i < 3; ++i) scale[i][i] = to[i] / from[i];
  return glm::inverse(ap1) * glm::inverse(bfd) * scale * bfd * rec709;
}

double srgb_encode(double v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

template <typename F>
Error expect_error(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "expected prism::Error";
  return Error(ErrorKind::kInternal, "no error");
}

TEST(ColorPipeline, BundledConfigIsTheDefault) {
  OcioEnv ocio_env;
  ColorPipeline pipeline({});
  EXPECT_EQ(pipeline.config_source(), "bundled");
  EXPECT_EQ(pipeline.config_name(), "prism-default-v1");
  EXPECT_EQ(pipeline.working_space(), "Linear Rec.709 (sRGB)");
  EXPECT_EQ(pipeline.output_space(), "Linear Rec.709 (sRGB)");
  EXPECT_EQ(pipeline.scene_file_space(), "Linear Rec.709 (sRGB)");
  EXPECT_EQ(pipeline.display(), "sRGB - Display");
  EXPECT_EQ(pipeline.view(), "Standard");
  EXPECT_EQ(pipeline.display_color_space(), "sRGB - Display");
  const std::string hash = pipeline.config_hash();
  ASSERT_EQ(hash.size(), 5u + 40u) << hash;
  EXPECT_EQ(hash.substr(0, 5), "sha1:");
  EXPECT_EQ(hash.find_first_not_of("0123456789abcdef", 5), std::string::npos) << hash;
}

TEST(ColorPipeline, EmbeddedConfigMatchesTheSourceFile) {
  OcioEnv ocio_env;
  const std::string path = std::string(PRISM_SOURCE_DIR) + "/color/ocio/config.ocio";
  std::ifstream in(path, std::ios::binary);
  ASSERT_TRUE(in) << path;
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(bundled_color_config_text(), text.str());
  ColorOptions from_file;
  from_file.ocio_config = path;
  EXPECT_EQ(ColorPipeline(from_file).config_hash(), ColorPipeline({}).config_hash());
  EXPECT_EQ(ColorPipeline(from_file).config_source(), path);
}

TEST(ColorPipeline, Rec709ToAcescgMatchesThePublishedMatrix) {
  OcioEnv ocio_env;
  const glm::dmat3 derived = derive_rec709_to_acescg();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(derived[j][i], kRec709ToAcescg[i][j], 1e-9);
  }
  ColorPipeline pipeline({});
  const Rgb colors[] = {
      {1, 0, 0},           {0, 1, 0},           {0, 0, 1},          {0.18f, 0.18f, 0.18f},
      {0.9f, 0.2f, 0.05f}, {0.01f, 0.5f, 3.0f}, {12.0f, 4.0f, 0.5f}};
  for (const Rgb& c : colors) {
    const Rgb acescg = pipeline.convert(c, "Linear Rec.709 (sRGB)", "ACEScg");
    const Rgb aces = pipeline.convert(c, "Linear Rec.709 (sRGB)", "ACES2065-1");
    const Rgb want_cg = mul(kRec709ToAcescg, c), want_aces = mul(kRec709ToAces2065, c);
    for (int k = 0; k < 3; ++k) {
      const double tolerance = 1e-5 * std::max(1.0f, std::abs(want_cg[k]));
      EXPECT_NEAR(acescg[k], want_cg[k], tolerance) << "channel " << k << " of " << c.x;
      EXPECT_NEAR(aces[k], want_aces[k], 1e-5 * std::max(1.0f, std::abs(want_aces[k])));
    }
  }
  // Aliases and roles name the same spaces.
  const Rgb via_alias = pipeline.convert({0.9f, 0.2f, 0.05f}, "lin_rec709", "lin_ap1");
  const Rgb via_role = pipeline.convert({0.9f, 0.2f, 0.05f}, "scene_linear", "ACEScg");
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(via_alias[k], mul(kRec709ToAcescg, {0.9f, 0.2f, 0.05f})[k], 1e-5);
    EXPECT_FLOAT_EQ(via_role[k], via_alias[k]);
  }
}

TEST(ColorPipeline, StandardViewEncodesMiddleGreyAsSrgb) {
  OcioEnv ocio_env;
  ColorPipeline pipeline({});
  EXPECT_NEAR(pipeline.working_to_display(Rgb(0.18f)).x, 0.4613561, 1e-5);
  for (float v : {0.0f, 0.001f, 0.05f, 0.5f, 1.0f}) {
    const Rgb d = pipeline.working_to_display(Rgb(v));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(d[k], srgb_encode(v), 2e-5) << v;
  }
  // The image path: exposure scales before the view and values clamp to the display range.
  ColorOptions brighter;
  brighter.exposure = 1.0f;
  Image image;
  image.width = 2;
  image.height = 1;
  image.channel_names = {"R", "G", "B", "N.X"};
  image.pixels = {0.18f, 0.18f, 0.18f, -1.0f, 4.0f, 0.0f, 0.18f, 5.0f};
  const Image display = ColorPipeline(brighter).working_to_display(image);
  ASSERT_EQ(display.channel_names, (std::vector<std::string>{"R", "G", "B"}));
  EXPECT_NEAR(display.at(0, 0, 0), srgb_encode(0.36), 2e-5);
  EXPECT_FLOAT_EQ(display.at(1, 0, 0), 1.0f);
  EXPECT_FLOAT_EQ(display.at(1, 0, 1), 0.0f);
  EXPECT_NEAR(display.at(1, 0, 2), srgb_encode(0.36), 2e-5);
}

TEST(ColorPipeline, AcesViewToneMapsAndRawViewPassesThrough) {
  OcioEnv ocio_env;
  ColorOptions aces;
  aces.view = "ACES 1.0 - SDR Video";
  ColorPipeline pipeline(aces);
  // The ACES 1.0 SDR video transform puts scene middle grey near 0.36 on an sRGB display (lower
  // than the plain encoding's 0.46) and rolls highlights off below 1.
  const float grey = pipeline.working_to_display(Rgb(0.18f)).x;
  EXPECT_GT(grey, 0.30f);
  EXPECT_LT(grey, 0.42f);
  EXPECT_LT(pipeline.working_to_display(Rgb(1.0f)).x, 0.9f);
  EXPECT_LT(grey, pipeline.working_to_display(Rgb(0.5f)).x);
  ColorOptions raw;
  raw.view = "Raw";
  EXPECT_FLOAT_EQ(ColorPipeline(raw).working_to_display(Rgb(0.18f, 0.3f, 2.0f)).z, 2.0f);
}

TEST(ColorPipeline, LookChangesSaturatedColoursOnly) {
  OcioEnv ocio_env;
  ColorOptions with_look;
  with_look.view = "ACES 1.0 - SDR Video";
  with_look.look = "ACES 1.3 Reference Gamut Compression";
  ColorOptions without = with_look;
  without.look.clear();
  ColorPipeline a(with_look), b(without);
  EXPECT_EQ(a.look(), "ACES 1.3 Reference Gamut Compression");
  const Rgb grey_a = a.working_to_display(Rgb(0.18f)), grey_b = b.working_to_display(Rgb(0.18f));
  EXPECT_NEAR(grey_a.x, grey_b.x, 1e-5);
  // A colour outside AP1 (negative in ACEScg) is pulled in by the gamut compression.
  const Rgb out_of_gamut = a.convert({0.02f, 0.9f, -0.3f}, "ACEScg", "scene_linear");
  const Rgb da = a.working_to_display(out_of_gamut), db = b.working_to_display(out_of_gamut);
  EXPECT_GT(std::abs(da.x - db.x) + std::abs(da.y - db.y) + std::abs(da.z - db.z), 1e-3);
}

TEST(ColorPipeline, SceneColoursConvertToTheWorkingSpace) {
  OcioEnv ocio_env;
  Scene scene;
  Material m;
  m.reflectance = {0.8f, 0.1f, 0.1f};
  m.transmittance = {0.2f, 0.9f, 0.3f};
  m.radiance = {10.0f, 8.0f, 2.0f};
  m.eta = {0.2f, 0.9f, 1.1f};
  m.k = {3.9f, 2.4f, 2.2f};
  scene.materials.push_back(m);
  Light light;
  light.color = {5.0f, 1.0f, 0.25f};
  scene.lights.push_back(light);

  Scene same = scene;
  ColorPipeline rec709({});
  rec709.convert_scene_to_working(same, rec709.scene_file_space());
  EXPECT_EQ(same.materials[0].reflectance, m.reflectance);
  EXPECT_EQ(same.lights[0].color, light.color);

  ColorOptions options;
  options.working_space = "ACEScg";
  ColorPipeline acescg(options);
  EXPECT_EQ(acescg.working_space(), "ACEScg");
  acescg.convert_scene_to_working(scene, acescg.scene_file_space());
  const auto expect_near = [](const Rgb& got, const Rgb& want) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], 1e-5 * std::max(1.0f, want[k]));
  };
  expect_near(scene.materials[0].reflectance, mul(kRec709ToAcescg, m.reflectance));
  expect_near(scene.materials[0].transmittance, mul(kRec709ToAcescg, m.transmittance));
  expect_near(scene.materials[0].radiance, mul(kRec709ToAcescg, m.radiance));
  expect_near(scene.lights[0].color, mul(kRec709ToAcescg, light.color));
  EXPECT_EQ(scene.materials[0].eta, m.eta);  // optical constants, not colours
  EXPECT_EQ(scene.materials[0].k, m.k);
  const Error e = expect_error([&] { acescg.convert_scene_to_working(scene, "Rec709 linear"); });
  EXPECT_EQ(e.kind(), ErrorKind::kUsage);
}

TEST(ColorPipeline, ConvertImageConvertsColourChannelsToTheWorkingSpaceOnly) {
  OcioEnv ocio_env;
  const ColorPipeline pipeline(ColorOptions{});
  Image image;
  image.width = 2;
  image.height = 1;
  image.channel_names = {"R", "G", "B", "albedo.R", "albedo.G", "albedo.B", "Z"};
  image.pixels = {0.9f, 0.2f, 0.05f, 0.1f, 0.5f, 0.3f, 4.0f,
                  0.0f, 1.0f, 0.25f, 2.0f, 0.0f, 0.7f, 9.0f};
  Image converted = image;
  pipeline.convert_image_to_working(converted, "ACEScg");
  for (int x = 0; x < 2; ++x) {
    for (int first : {0, 3}) {
      const Rgb in(image.at(x, 0, first), image.at(x, 0, first + 1), image.at(x, 0, first + 2));
      const Rgb expected = pipeline.convert(in, "ACEScg", pipeline.working_space());
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(converted.at(x, 0, first + c), expected[c], 1e-5f) << x << " " << first + c;
      }
    }
    EXPECT_EQ(converted.at(x, 0, 6), image.at(x, 0, 6)) << "depth is data, not colour";
  }
  ASSERT_NE(converted.pixels, image.pixels);

  // From the working space itself (by role): nothing changes.
  Image same = image;
  pipeline.convert_image_to_working(same, "scene_linear");
  EXPECT_EQ(same.pixels, image.pixels);

  try {
    pipeline.convert_image_to_working(same, "Not A Space");
    ADD_FAILURE() << "an unknown space was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kUsage);
    EXPECT_NE(std::string(e.what()).find("Not A Space"), std::string::npos) << e.what();
  }
}

TEST(ColorPipeline, OutputConversionTouchesColourLayersOnly) {
  OcioEnv ocio_env;
  ColorOptions options;
  options.output_space = "ACEScg";
  ColorPipeline pipeline(options);
  Image image;
  image.width = 1;
  image.height = 1;
  image.channel_names = {
      "R",   "G",   "B", "albedo.R",      "albedo.G",   "albedo.B",   "N.X",
      "N.Y", "N.Z", "Z", "sampleCount.Y", "variance.R", "variance.G", "variance.B"};
  image.pixels = {0.5f, 0.2f, 0.1f, 0.9f,  0.1f,  0.0f,  0.0f,
                  1.0f, 0.0f, 7.5f, 64.0f, 0.01f, 0.02f, 0.03f};
  const ImagePixels before = image.pixels;
  pipeline.working_to_output(image);
  const Rgb beauty = mul(kRec709ToAcescg, {0.5f, 0.2f, 0.1f});
  const Rgb albedo = mul(kRec709ToAcescg, {0.9f, 0.1f, 0.0f});
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(image.pixels[k], beauty[k], 1e-5);
    EXPECT_NEAR(image.pixels[3 + k], albedo[k], 1e-5);
  }
  for (size_t c = 6; c < before.size(); ++c) EXPECT_EQ(image.pixels[c], before[c]) << c;

  EXPECT_TRUE(is_color_layer("albedo"));
  EXPECT_TRUE(is_color_layer(""));
  EXPECT_FALSE(is_color_layer("N"));
  EXPECT_FALSE(is_color_layer("variance"));
  const auto triples = color_channel_triples(image);
  ASSERT_EQ(triples.size(), 2u);
  EXPECT_EQ(triples[1], (std::array<int, 3>{3, 4, 5}));
}

TEST(ColorPipeline, ChromaticitiesFollowTheOutputSpace) {
  OcioEnv ocio_env;
  const auto chroma = [](const std::string& output) {
    ColorOptions options;
    options.output_space = output;
    return ColorPipeline(options).output_chromaticities();
  };
  const std::array<float, 8> rec709{0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
  const std::array<float, 8> ap1{0.713f, 0.293f, 0.165f,   0.830f,
                                 0.128f, 0.044f, 0.32168f, 0.33767f};
  const std::array<float, 8> ap0{0.7347f, 0.2653f, 0.0f,     1.0f,
                                 0.0001f, -0.077f, 0.32168f, 0.33767f};
  const std::array<float, 8> rec2020{0.708f, 0.292f, 0.170f,  0.797f,
                                     0.131f, 0.046f, 0.3127f, 0.3290f};
  EXPECT_EQ(chroma("Linear Rec.709 (sRGB)"), rec709);
  EXPECT_EQ(chroma("ACEScg"), ap1);
  EXPECT_EQ(chroma("ACES2065-1"), ap0);
  EXPECT_EQ(chroma("Linear Rec.2020"), rec2020);
  EXPECT_EQ(chroma("ACEScct"), std::nullopt);  // a log encoding: no linear primaries to derive
}

TEST(ColorPipeline, FindColorSpaceResolvesNamesAliasesAndRolesOfTheConfig) {
  OcioEnv ocio_env;
  const ColorPipeline pipeline(ColorOptions{});
  EXPECT_EQ(pipeline.find_color_space("ACEScg"), "ACEScg");
  EXPECT_EQ(pipeline.find_color_space("lin_ap1"), "ACEScg");
  EXPECT_EQ(pipeline.find_color_space("scene_linear"), "Linear Rec.709 (sRGB)");
  EXPECT_EQ(pipeline.find_color_space("Studio AP1"), std::nullopt);
  EXPECT_EQ(pipeline.find_color_space(""), std::nullopt);
}

TEST(ColorPipeline, UnknownNamesListWhatTheConfigOffers) {
  OcioEnv ocio_env;
  const auto error_for = [](ColorOptions options) {
    return expect_error([&] { ColorPipeline pipeline(options); });
  };
  ColorOptions o;
  o.working_space = "Linear Rec709";
  Error e = error_for(o);
  EXPECT_EQ(e.kind(), ErrorKind::kUsage);
  EXPECT_NE(e.message().find("unknown colour space 'Linear Rec709'"), std::string::npos);
  EXPECT_NE(e.message().find("ACEScg"), std::string::npos) << e.message();

  o = {};
  o.display = "sRGB";
  e = error_for(o);
  EXPECT_EQ(e.kind(), ErrorKind::kUsage);
  EXPECT_EQ(e.message(), "unknown display 'sRGB'; available: sRGB - Display");

  o = {};
  o.view = "Filmic";
  e = error_for(o);
  EXPECT_EQ(e.kind(), ErrorKind::kUsage);
  EXPECT_EQ(e.message(),
            "unknown view 'Filmic' for display 'sRGB - Display'; available: Standard, ACES 1.0 - "
            "SDR Video, Raw");

  o = {};
  o.look = "Punchy";
  e = error_for(o);
  EXPECT_EQ(e.kind(), ErrorKind::kUsage);
  EXPECT_NE(e.message().find("unknown look 'Punchy'; available: ACES 1.3 Reference Gamut"),
            std::string::npos)
      << e.message();

  for (const char* bad : {"Raw", "sRGB - Texture", "ACEScct", "sRGB - Display"}) {
    o = {};
    o.working_space = bad;
    EXPECT_EQ(error_for(o).kind(), ErrorKind::kUsage) << bad;
  }
  o = {};
  o.output_space = "sRGB - Display";
  EXPECT_EQ(error_for(o).kind(), ErrorKind::kUsage);
  o = {};
  o.exposure = std::nanf("");
  EXPECT_EQ(error_for(o).kind(), ErrorKind::kUsage);
}

TEST(ColorPipeline, BadConfigFilesAreReported) {
  OcioEnv ocio_env;
  const auto dir = test::make_temp_dir("color_badcfg");
  ColorOptions o;
  o.ocio_config = (dir / "missing.ocio").string();
  Error e = expect_error([&] { ColorPipeline pipeline(o); });
  EXPECT_EQ(e.kind(), ErrorKind::kUsage);
  EXPECT_NE(e.message().find("missing.ocio"), std::string::npos);
  test::write_text(dir / "broken.ocio", "ocio_profile_version: 2\nroles: [this is not yaml\n");
  o.ocio_config = (dir / "broken.ocio").string();
  e = expect_error([&] { ColorPipeline pipeline(o); });
  EXPECT_EQ(e.kind(), ErrorKind::kInput);
  EXPECT_NE(std::string(e.what()).find("broken.ocio"), std::string::npos);
  std::filesystem::remove_all(dir);
}

// A config unlike the bundled one: other names, a gamma-2.2 display, no interchange roles.
constexpr const char* kTestConfig = R"(ocio_profile_version: 2
name: prism-test-config
roles:
  default: Linear Rec.709
  scene_linear: Linear Rec.709
  data: Non-Color
file_rules:
  - !<Rule> {name: Default, colorspace: default}
displays:
  Test Monitor:
    - !<View> {name: Gamma 2.2, colorspace: Gamma 2.2 Rec.709}
    - !<View> {name: Raw, colorspace: Non-Color}
colorspaces:
  - !<ColorSpace>
    name: Linear Rec.709
    isdata: false
  - !<ColorSpace>
    name: Gamma 2.2 Rec.709
    isdata: false
    from_scene_reference: !<ExponentTransform> {value: 2.2, direction: inverse}
  - !<ColorSpace>
    name: Non-Color
    isdata: true
)";

TEST(ColorPipeline, ConfigFromTheOcioVariableIsHonoured) {
  OcioEnv ocio_env;
  const auto dir = test::make_temp_dir("color_envcfg");
  const std::string path = (dir / "test.ocio").string();
  test::write_text(path, kTestConfig);
  ocio_env.set(path);
  ColorPipeline pipeline({});
  EXPECT_EQ(pipeline.config_source(), path);
  EXPECT_EQ(pipeline.config_name(), "prism-test-config");
  EXPECT_EQ(pipeline.display(), "Test Monitor");
  EXPECT_EQ(pipeline.view(), "Gamma 2.2");
  EXPECT_EQ(pipeline.working_space(), "Linear Rec.709");
  EXPECT_EQ(pipeline.scene_file_space(), "Linear Rec.709");
  EXPECT_NEAR(pipeline.working_to_display(Rgb(0.18f)).x, std::pow(0.18, 1.0 / 2.2), 1e-5);
  EXPECT_EQ(pipeline.output_chromaticities(), std::nullopt);  // no interchange role to go by
  const ColorConfigListing listing = list_color_config("");
  EXPECT_EQ(listing.config_source, path);
  EXPECT_EQ(listing.displays, (std::vector<std::string>{"Test Monitor"}));
  // An explicit config wins over $OCIO.
  ColorOptions explicit_config;
  explicit_config.ocio_config = std::string(PRISM_SOURCE_DIR) + "/color/ocio/config.ocio";
  EXPECT_EQ(ColorPipeline(explicit_config).config_name(), "prism-default-v1");
  // Names of the bundled config are unknown here and the error lists this config's.
  ColorOptions o;
  o.view = "Standard";
  const Error e = expect_error([&] { ColorPipeline p(o); });
  EXPECT_EQ(e.message(),
            "unknown view 'Standard' for display 'Test Monitor'; available: Gamma 2.2, Raw");
  std::filesystem::remove_all(dir);
}

TEST(ColorPipeline, MissingSceneLinearRoleNeedsAWorkingSpace) {
  OcioEnv ocio_env;
  const auto dir = test::make_temp_dir("color_norole");
  std::string text = kTestConfig;
  text.replace(text.find("  scene_linear: Linear Rec.709\n"),
               std::string("  scene_linear: Linear Rec.709\n").size(), "");
  const std::string path = (dir / "norole.ocio").string();
  test::write_text(path, text);
  ColorOptions o;
  o.ocio_config = path;
  const Error e = expect_error([&] { ColorPipeline p(o); });
  EXPECT_EQ(e.kind(), ErrorKind::kUsage);
  EXPECT_NE(e.message().find("no scene_linear role"), std::string::npos) << e.message();
  EXPECT_NE(e.message().find("Linear Rec.709"), std::string::npos);
  o.working_space = "Linear Rec.709";
  ColorPipeline p(o);
  EXPECT_EQ(p.output_space(), "Linear Rec.709");  // falls back to the working space
  std::filesystem::remove_all(dir);
}

// Linear Rec.709 under a name prism does not know is found through aces_interchange.
TEST(ColorPipeline, Rec709SpaceIsFoundByItsTransform) {
  OcioEnv ocio_env;
  const auto dir = test::make_temp_dir("color_matrixcfg");
  const std::string path = (dir / "matrix.ocio").string();
  test::write_text(path, R"(ocio_profile_version: 2
roles:
  default: Studio AP0
  scene_linear: Studio AP0
  aces_interchange: Studio AP0
file_rules:
  - !<Rule> {name: Default, colorspace: default}
displays:
  Monitor:
    - !<View> {name: Raw, colorspace: Studio AP0}
colorspaces:
  - !<ColorSpace>
    name: Studio AP0
  - !<ColorSpace>
    name: Plate Primaries
    to_scene_reference: !<MatrixTransform> {matrix: [0.5, 0.3, 0.2, 0, 0.1, 0.8, 0.1, 0, 0, 0.1, 0.9, 0, 0, 0, 0, 1]}
  - !<ColorSpace>
    name: Shot Linear
    to_scene_reference: !<MatrixTransform> {matrix: [0.439632981919491, 0.382988698151554, 0.177378319928955, 0, 0.0897764429588424, 0.813439428748981, 0.0967841282921771, 0, 0.0175411703831727, 0.111546553302387, 0.87091227631444, 0, 0, 0, 0, 1]}
)");
  ColorOptions o;
  o.ocio_config = path;
  o.output_space = "Shot Linear";
  ColorPipeline pipeline(o);
  EXPECT_EQ(pipeline.scene_file_space(), "Shot Linear");
  const std::array<float, 8> rec709{0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
  EXPECT_EQ(pipeline.output_chromaticities(), rec709);
  std::filesystem::remove_all(dir);
}

// An ACES CG/studio-style config (scene_linear = ACEScg) works through $OCIO unchanged: prism
// renders in ACEScg, writes ACEScg, and still finds linear Rec.709 for the scene colours.
TEST(ColorPipeline, AcesStyleConfigRendersInAcescg) {
  OcioEnv ocio_env;
  const auto dir = test::make_temp_dir("color_acescfg");
  std::string text = bundled_color_config_text();
  const std::string role = "  scene_linear: Linear Rec.709 (sRGB)\n";
  ASSERT_NE(text.find(role), std::string::npos);
  text.replace(text.find(role), role.size(), "  scene_linear: ACEScg\n");
  const std::string path = (dir / "aces_style.ocio").string();
  test::write_text(path, text);
  ocio_env.set(path);
  ColorPipeline pipeline({});
  EXPECT_EQ(pipeline.working_space(), "ACEScg");
  EXPECT_EQ(pipeline.output_space(), "ACEScg");
  EXPECT_EQ(pipeline.scene_file_space(), "Linear Rec.709 (sRGB)");
  const std::array<float, 8> ap1{0.713f, 0.293f, 0.165f,   0.830f,
                                 0.128f, 0.044f, 0.32168f, 0.33767f};
  EXPECT_EQ(pipeline.output_chromaticities(), ap1);
  Scene scene;
  Light light;
  light.color = {0.0f, 0.0f, 1.0f};
  scene.lights.push_back(light);
  pipeline.convert_scene_to_working(scene, pipeline.scene_file_space());
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(scene.lights[0].color[k], kRec709ToAcescg[k][2], 1e-5);
  }
  // The Standard view of ACEScg middle grey is still sRGB-encoded 0.18.
  EXPECT_NEAR(pipeline.working_to_display(Rgb(0.18f)).x, 0.4613561, 1e-5);
  std::filesystem::remove_all(dir);
}

TEST(ColorPipeline, ListingDescribesTheConfig) {
  OcioEnv ocio_env;
  const ColorConfigListing listing = list_color_config("");
  EXPECT_EQ(listing.config_source, "bundled");
  EXPECT_EQ(listing.config_name, "prism-default-v1");
  for (const char* space : {"Linear Rec.709 (sRGB)", "ACEScg", "ACES2065-1", "sRGB - Texture",
                            "Raw", "sRGB - Display"}) {
    EXPECT_NE(std::find(listing.color_spaces.begin(), listing.color_spaces.end(), space),
              listing.color_spaces.end())
        << space;
  }
  ASSERT_EQ(listing.views.size(), 1u);
  EXPECT_EQ(listing.views[0].second,
            (std::vector<std::string>{"Standard", "ACES 1.0 - SDR Video", "Raw"}));
  for (const char* role : {"scene_linear", "rendering", "data", "color_picking", "default",
                           "reference", "texture_paint", "compositing_log", "aces_interchange"}) {
    EXPECT_NE(std::find(listing.roles.begin(), listing.roles.end(), role), listing.roles.end())
        << role;
  }
  const std::string text = format_color_config(listing);
  EXPECT_NE(text.find("sRGB - Display (default): Standard, ACES 1.0 - SDR Video, Raw"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("scene_linear: Linear Rec.709 (sRGB)"), std::string::npos);
}

}  // namespace
}  // namespace prism
