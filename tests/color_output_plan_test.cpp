// The output plan: which files the render options resolve to, what validation rejects before any
// work, and that writing a validated plan writes exactly its files.

#include "color/output_plan.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>

#include "color/color_pipeline.h"
#include "color/image_output.h"
#include "core/app/render_options.h"
#include "core/error.h"
#include "tests/support/app_test_helpers.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {
namespace fs = std::filesystem;
using test::dir_entries;
using test::TestDirs;

/// (path, kind, format) of every planned file, for whole-plan comparisons.
struct FileSummary {
  std::string path;
  OutputKind kind;
  std::string format;
  bool operator==(const FileSummary&) const = default;
};

std::ostream& operator<<(std::ostream& out, const FileSummary& f) {
  return out << "{" << f.path << ", kind " << int(f.kind) << ", " << f.format << "}";
}

std::vector<FileSummary> summary(const OutputPlan& plan) {
  std::vector<FileSummary> files;
  for (const PlannedOutput& f : plan.files) files.push_back({f.path.string(), f.kind, f.format});
  return files;
}

constexpr OutputKind kExr = OutputKind::kSceneLinearExr;
constexpr OutputKind kDisplay = OutputKind::kDisplayImage;
constexpr OutputKind kRate = OutputKind::kSampleRate;

RenderOptions render_options(const std::string& output, bool png = false, bool exr = false) {
  RenderOptions options;
  options.scene = "scenes/data/cornell.json";
  options.output = output;
  options.png = png;
  options.exr = exr;
  return options;
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

/// Every test runs with the bundled config, whatever the caller's $OCIO.
class ColorOutputPlan : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const char* v = std::getenv("OCIO")) saved_ocio_ = v;
    unsetenv("OCIO");
  }
  void TearDown() override {
    if (saved_ocio_) setenv("OCIO", saved_ocio_->c_str(), 1);
  }

  // A film-like image: a grey beauty and a sample count growing to the right.
  static Image film_image() {
    Image image;
    image.width = 4;
    image.height = 2;
    image.channel_names = {"R", "G", "B", "sampleCount.Y"};
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) {
        image.pixels.insert(image.pixels.end(), {0.18f, 0.18f, 0.18f, float(8 * (x + 1))});
      }
    }
    return image;
  }

  std::optional<std::string> saved_ocio_;
};

TEST_F(ColorOutputPlan, DefaultIsTheSceneNameAsAnExrHere) {
  RenderOptions options = render_options("");
  options.color.view = "Raw";
  options.exr_options = ExrOptions{"float", "piz"};
  const OutputPlan plan = resolve_output_plan(options);
  EXPECT_EQ(summary(plan), (std::vector<FileSummary>{{"cornell.exr", kExr, "openexr"}}));
  EXPECT_EQ(plan.files.front().option, "--output (-f)");
  EXPECT_EQ(plan.color.view, "Raw");
  EXPECT_EQ(plan.exr.pixel_type, "float");
  EXPECT_EQ(plan.exr.compression, "piz");
}

TEST_F(ColorOutputPlan, PngAndExrAddTheOtherKindBesideTheOutput) {
  struct Case {
    RenderOptions options;
    std::vector<FileSummary> files;
  };
  const std::vector<Case> cases = {
      {render_options("out/a.exr"), {{"out/a.exr", kExr, "openexr"}}},
      {render_options("out/a.exr", true),
       {{"out/a.exr", kExr, "openexr"}, {"out/a.png", kDisplay, "png"}}},
      {render_options("out/a.exr", false, true), {{"out/a.exr", kExr, "openexr"}}},
      {render_options("out/a.png"), {{"out/a.png", kDisplay, "png"}}},
      {render_options("out/a.png", true), {{"out/a.png", kDisplay, "png"}}},
      {render_options("out/a.png", false, true),
       {{"out/a.png", kDisplay, "png"}, {"out/a.exr", kExr, "openexr"}}},
      {render_options("out/a.jpg", true, true),
       {{"out/a.jpg", kDisplay, "jpeg"},
        {"out/a.exr", kExr, "openexr"},
        {"out/a.png", kDisplay, "png"}}},
      {render_options("a.tiff", true), {{"a.tiff", kDisplay, "tiff"}, {"a.png", kDisplay, "png"}}},
      {render_options("", true, true),
       {{"cornell.exr", kExr, "openexr"}, {"cornell.png", kDisplay, "png"}}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.options.output + (c.options.png ? " --png" : "") +
                 (c.options.exr ? " --exr" : ""));
    EXPECT_EQ(summary(resolve_output_plan(c.options)), c.files);
  }
}

TEST_F(ColorOutputPlan, UpperCaseExtensionsAreTheSameKinds) {
  EXPECT_EQ(summary(resolve_output_plan(render_options("OUT.PNG", true, true))),
            (std::vector<FileSummary>{{"OUT.PNG", kDisplay, "png"}, {"OUT.exr", kExr, "openexr"}}));
  EXPECT_EQ(summary(resolve_output_plan(render_options("Out.EXR", true, true))),
            (std::vector<FileSummary>{{"Out.EXR", kExr, "openexr"}, {"Out.png", kDisplay, "png"}}));
  EXPECT_EQ(summary(resolve_output_plan(render_options("x.JPEG"))),
            (std::vector<FileSummary>{{"x.JPEG", kDisplay, "jpeg"}}));
  EXPECT_EQ(summary(resolve_output_plan(render_options("x.Tif"))),
            (std::vector<FileSummary>{{"x.Tif", kDisplay, "tiff"}}));
  EXPECT_TRUE(is_display_image_path("x.JPG"));
  EXPECT_FALSE(is_display_image_path("x.EXR"));
}

TEST_F(ColorOutputPlan, AdaptiveRendersAddTheRatePictureLast) {
  RenderOptions options = render_options("out/a.exr", true);
  options.adaptive = std::make_pair(8, 0.05);
  OutputPlan plan = resolve_output_plan(options);
  EXPECT_EQ(summary(plan), (std::vector<FileSummary>{{"out/a.exr", kExr, "openexr"},
                                                     {"out/a.png", kDisplay, "png"},
                                                     {"out/a_rate.png", kRate, "png"}}));
  EXPECT_EQ(plan.files.back().option, "--adaptive (-a)");

  options = render_options("Shot.JPG");
  options.adaptive = std::make_pair(8, 0.05);
  plan = resolve_output_plan(options);
  EXPECT_EQ(summary(plan), (std::vector<FileSummary>{{"Shot.JPG", kDisplay, "jpeg"},
                                                     {"Shot_rate.png", kRate, "png"}}));
  options.output.clear();
  EXPECT_EQ(resolve_output_plan(options).files.back().path, fs::path("cornell_rate.png"));
}

TEST_F(ColorOutputPlan, UnsupportedExtensionIsRejectedAtValidationNamingTheOption) {
  const TestDirs dirs("output_plan_bmp");
  const fs::path bmp = dirs.out / "image.bmp";
  const OutputPlan plan = resolve_output_plan(render_options(bmp.string(), true, true));
  ASSERT_EQ(plan.files.front().kind, OutputKind::kUnsupported);
  EXPECT_EQ(plan.files.front().format, "");
  const Error e = expect_error([&] { validate_outputs(plan); });
  EXPECT_EQ(e.kind(), ErrorKind::kUsage);
  EXPECT_EQ(e.location().element, "--output (-f)");
  EXPECT_EQ(e.message(), "unsupported extension '.bmp' in '" + bmp.string() +
                             "'; use .exr, .png, .jpg, .jpeg, .tif or .tiff");
  EXPECT_EQ(dir_entries(dirs.out), std::vector<std::string>{});

  const auto r = test::run_prism({"render", dirs.scene("tiny.dae", test::kTinyCollada), "-r", "32",
                                  "24", "-s", "1", "-f", bmp.string(), "--png"});
  test::expect_one_line_error(r, 2, {"--output (-f)", "'.bmp'"});
  EXPECT_EQ(dir_entries(dirs.out), std::vector<std::string>{});
}

TEST_F(ColorOutputPlan, BadExrEncodingIsRejectedEvenWithoutAnExr) {
  RenderOptions options = render_options("a.png");
  options.exr_options.pixel_type = "double";
  EXPECT_EQ(expect_error([&] { validate_outputs(resolve_output_plan(options)); }).message(),
            "unknown EXR pixel type 'double'; available: half, float");
  options.exr_options = ExrOptions{"half", "b44"};
  const Error e = expect_error([&] { validate_outputs(resolve_output_plan(options)); });
  EXPECT_EQ(e.kind(), ErrorKind::kUsage);
  EXPECT_EQ(e.message(), "unknown EXR compression 'b44'; available: zip, piz, dwaa, none");
}

TEST_F(ColorOutputPlan, UnwritableFolderIsRejectedBeforeRendering) {
  const TestDirs dirs("output_plan_unwritable");
  const fs::path missing = dirs.out / "missing" / "a.exr";
  RenderOptions options = render_options(missing.string(), true);
  options.adaptive = std::make_pair(8, 0.05);
  Error e = expect_error([&] { validate_outputs(resolve_output_plan(options)); });
  EXPECT_EQ(e.kind(), ErrorKind::kOutput);
  EXPECT_EQ(e.location().file, missing.string());
  EXPECT_NE(e.message().find("does not exist"), std::string::npos) << e.message();
  EXPECT_EQ(dir_entries(dirs.out), std::vector<std::string>{});

  // Through the program: exit 3 and nothing written, not even the files that could be.
  const std::string scene = dirs.scene("tiny.dae", test::kTinyCollada);
  auto r = test::run_prism({"render", scene, "-r", "32", "24", "-s", "1", "-a", "8", "0.05",
                            "--png", "-f", missing.string()});
  test::expect_one_line_error(r, 3, {missing.string(), "does not exist"});
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(dir_entries(dirs.out), std::vector<std::string>{});

  // A later file of the plan that cannot be written (its path is a folder) stops the render
  // before the first one is written.
  fs::create_directory(dirs.out / "b.exr");
  r = test::run_prism(
      {"render", scene, "-r", "32", "24", "-s", "1", "-f", (dirs.out / "b.png").string(), "--exr"});
  test::expect_one_line_error(r, 3, {(dirs.out / "b.exr").string(), "is a folder"});
  EXPECT_EQ(dir_entries(dirs.out), std::vector<std::string>{"b.exr"});
  EXPECT_TRUE(fs::is_empty(dirs.out / "b.exr"));
}

TEST_F(ColorOutputPlan, ValidateAndWriteWriteExactlyThePlannedFiles) {
  const TestDirs dirs("output_plan_write");
  RenderOptions options = render_options((dirs.out / "beauty.exr").string(), true);
  options.adaptive = std::make_pair(8, 0.05);
  options.exr_options = ExrOptions{"float", "piz"};
  const OutputPlan plan = resolve_output_plan(options);
  const ColorPipeline pipeline(plan.color);
  const ImageMetadata metadata = {{"prism:scene", "plan-test"}};
  validate_outputs(plan);
  EXPECT_EQ(dir_entries(dirs.out), std::vector<std::string>{});  // validation leaves nothing
  write_outputs(plan, film_image(), metadata, pipeline);
  EXPECT_EQ(dir_entries(dirs.out),
            (std::vector<std::string>{"beauty.exr", "beauty.png", "beauty_rate.png"}));

  const ImageFileContents exr = read_image_file(dirs.out / "beauty.exr");
  EXPECT_EQ(exr.format, "openexr");
  EXPECT_EQ(exr.compression, "piz");
  for (const std::string& f : exr.channel_formats) EXPECT_EQ(f, "float");
  EXPECT_GE(exr.channel("sampleCount.Y"), 0);
  const ImageFileContents png = read_image_file(dirs.out / "beauty.png");
  EXPECT_EQ(png.format, "png");
  EXPECT_EQ(png.attribute("prism:view"), "Standard");
  const ImageFileContents rate = read_image_file(dirs.out / "beauty_rate.png");
  EXPECT_EQ(rate.format, "png");
  EXPECT_EQ(rate.attribute("prism:view"), "Raw");
  EXPECT_GT(rate.image.at(3, 0, 0), rate.image.at(3, 0, 2));  // the most samples: red
  EXPECT_GT(rate.image.at(0, 0, 2), rate.image.at(0, 0, 0));  // a quarter of them: blue
  for (const auto* file : {&exr, &png, &rate}) {
    EXPECT_EQ(file->attribute("prism:scene"), "plan-test");
    EXPECT_EQ(file->attribute("prism:ocioConfigSource"), "bundled");
  }
}

TEST_F(ColorOutputPlan, WritersTakeTheFormatFromThePlan) {
  const TestDirs dirs("output_plan_formats");
  OutputPlan plan;
  plan.files = {plan_image_file(dirs.out / "a.JPG", "a"), plan_image_file(dirs.out / "b.tif", "b")};
  // A hand-made entry: the writer follows its kind and format, not the file name.
  plan.files.push_back({dirs.out / "c.data", OutputKind::kDisplayImage, "png", "c"});
  validate_outputs(plan);
  write_outputs(plan, film_image(), {}, ColorPipeline(plan.color));
  EXPECT_EQ(dir_entries(dirs.out), (std::vector<std::string>{"a.JPG", "b.tif", "c.data"}));
  EXPECT_EQ(read_image_file(dirs.out / "a.JPG").format, "jpeg");
  EXPECT_EQ(read_image_file(dirs.out / "b.tif").format, "tiff");
  EXPECT_EQ(read_image_file(dirs.out / "c.data").format, "png");
}

TEST_F(ColorOutputPlan, SummaryLineListsTheImagesButNotTheRatePicture) {
  const TestDirs dirs("output_plan_summary");
  const fs::path out = dirs.out / "a.exr";
  const auto r =
      test::run_prism({"render", dirs.scene("tiny.dae", test::kTinyCollada), "-r", "32", "24", "-s",
                       "4", "-a", "2", "0.5", "-q", "--png", "-f", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string tail = " -> " + out.string() + ", " + (dirs.out / "a.png").string() + "\n";
  ASSERT_GE(r.out.size(), tail.size()) << r.out;
  EXPECT_EQ(r.out.substr(r.out.size() - tail.size()), tail) << r.out;
  EXPECT_EQ(dir_entries(dirs.out), (std::vector<std::string>{"a.exr", "a.png", "a_rate.png"}));
}

}  // namespace
}  // namespace prism
