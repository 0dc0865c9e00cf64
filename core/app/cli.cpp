// The command-line grammar (CLI11): which words and flags exist and where their values go.

#include "core/app/cli.h"

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "accel/accelerator.h"
#include "color/image_io.h"
#include "core/app/bench_command.h"
#include "core/app/commands.h"
#include "core/app/merge_command.h"
#include "core/app/mpi_world.h"
#include "core/app/provenance.h"
#include "core/app/rank_agreement.h"
#include "core/app/validate_command.h"
#include "core/error.h"
#include "core/samplers.h"
#include "integrators/integrator.h"

namespace prism {
namespace {

constexpr std::array<const char*, 8> kCommands = {"render",  "info",  "list",     "colorspaces",
                                                  "convert", "bench", "validate", "merge"};

/// `prism render --help`'s footer; the defaults come from the constants the code uses.
std::string render_footer() {
  return fmt::format(
      R"(Defaults: SCENE is the bundled Cornell box with two spheres. Flags override the
scene file's settings, which override prism's defaults: resolution {} x {}, {} spp,
integrator '{}', accelerator '{}', sampler '{}', seed {}, all hardware threads.

Integrator flags: -l, -m, -H and --two-sided-emitters (and the scene file's max_depth) stand
for the parameters <integrator>.light_samples, .max_depth, .hemisphere and .two_sided_emitters
of the integrators that have them (see `prism list`), and are ignored by the others. --set with
the same key must agree with them.

Ambient lights light the scene but, as in the CS184 homework, rays that leave the scene see
black; --set path.ambient_visible=true (or direct.ambient_visible) shows them as a sky.

Output: -f FILE picks the format by extension. FILE.exr writes a scene-linear EXR (add --png
for FILE.png beside it); FILE.png/.jpg/.tif writes only that display-referred image (add --exr
for FILE.exr beside it). Without -f, prism writes <scene name>.exr in the current folder.
Files are written atomically: a failed render leaves no partial file.

Exit codes: 0 success, 2 bad command line or scene, 3 output or resource failure, 1 internal.
Typing `render` is optional: `prism -s 64 -r 480 360 -f out.png scene.dae` renders too.)",
      kDefaultWidth, kDefaultHeight, kDefaultSpp, kDefaultIntegrator, kDefaultAccelerator,
      kDefaultSampler, kDefaultSeed);
}

/// argv without the program name, with "render" put first when the first argument is neither a
/// command nor a top-level flag: CLI11 2.1 has no default subcommand.
std::vector<std::string> arguments_with_default_command(int argc, const char* const* argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) return args;
  const std::string& first = args.front();
  const bool is_command = std::find(kCommands.begin(), kCommands.end(), first) != kCommands.end();
  const bool is_top_level_flag = first == "-h" || first == "--help" || first == "--version";
  if (!is_command && !is_top_level_flag) args.insert(args.begin(), "render");
  return args;
}

void add_color_options(CLI::App& command, ColorOptions& color) {
  command.add_option("--ocio-config", color.ocio_config,
                     "OpenColorIO config file (default: $OCIO, else the bundled config)");
  command.add_option("--working-space", color.working_space,
                     "colour space rendering happens in (default: the config's scene_linear)");
  command.add_option("--output-space", color.output_space,
                     "colour space of the EXR (default: the config's scene_linear)");
  command.add_option("--display", color.display, "display for PNG/JPEG/TIFF output");
  command.add_option("--view", color.view, "view of that display");
  command.add_option("--look", color.look, "look applied with the view");
  command.add_option("--exposure", color.exposure,
                     "exposure in stops, for display-referred output only");
}

void add_render_options(CLI::App& render, RenderOptions& o) {
  render.add_option("scene", o.scene,
                    "scene file (.dae, .json) or model file (.obj .ply .stl .gltf .glb .fbx)");
  render
      .add_option("--accel", o.accelerator, "accelerator: " + accelerator_registry().names_joined())
      ->capture_default_str();
  render.add_option("--integrator", o.integrator,
                    "integrator: " + integrator_registry().names_joined() +
                        " (default: the scene's, else " + kDefaultIntegrator + ")");
  render.add_option("--sampler", o.sampler, "sampler: " + sampler_registry().names_joined())
      ->capture_default_str();
  render.add_option("-s,--spp", o.spp, "camera rays per pixel");
  render.add_option("-l,--light-samples", o.light_samples,
                    "samples per area light (alias of <integrator>.light_samples: direct, path)");
  render.add_option("-m,--max-depth", o.max_depth,
                    "maximum ray depth (alias of <integrator>.max_depth: path)");
  render.add_option("-t,--threads", o.threads, "worker threads; 0 = all (default)");
  render.add_option("--seed", o.seed, "sampler seed (non-negative integer)");
  render.add_option("-r,--resolution", o.resolution, "image width and height in pixels")
      ->type_name("W H");
  render.add_option("-f,--output", o.output, "output file: .exr, .png, .jpg or .tif");
  render.add_flag("--png", o.png, "also write a PNG beside the EXR");
  render.add_flag("--exr", o.exr, "also write an EXR beside a PNG/JPEG/TIFF output");
  render.add_option("-a,--adaptive", o.adaptive, "adaptive sampling batch size and tolerance")
      ->type_name("B TOL");
  render.add_flag("-H,--hemisphere", o.hemisphere_sampling,
                  "direct light by uniform hemisphere sampling (alias of "
                  "<integrator>.hemisphere=true: direct, path)");
  render.add_flag("--two-sided-emitters", o.two_sided_emitters,
                  "emissive surfaces and area lights emit from both sides, as in Blender (alias "
                  "of <integrator>.two_sided_emitters=true: direct, path)");
  render.add_option("-b,--lens-radius", o.lens_radius, "thin-lens aperture radius (0: pinhole)");
  render.add_option("-d,--focal-distance", o.focal_distance, "distance of the plane in focus");
  render.add_option("-e,--environment", o.environment_map,
                    "latitude-longitude environment map (EXR, .hdr, ...) lighting the scene");
  render.add_option("-c,--camera-file", o.camera_file, "camera settings (not supported yet)");
  // allow_extra_args(false): one value per --set, so `--set k=v scene.dae` keeps its scene.
  render.add_option("--set", o.set, "component parameter key=value, e.g. bvh.max_leaf_size=4")
      ->allow_extra_args(false);
  render.add_flag("-q,--quiet", o.quiet, "no progress output");
  render.add_option("--time-limit", o.time_limit,
                    "render at most this many seconds (whole passes), then write the image");
  render.add_option("--checkpoint", o.checkpoint,
                    "save the render state to FILE (an EXR) every --checkpoint-interval seconds "
                    "and when stopped");
  render.add_option("--checkpoint-interval", o.checkpoint_interval, "seconds between checkpoints")
      ->capture_default_str();
  render.add_option("--resume", o.resume,
                    "continue the render saved in FILE with its options (SCENE not needed)");
  render.add_option("--crop", o.crop, "render only the pixels X0 <= x < X1, Y0 <= y < Y1")
      ->type_name("X0 Y0 X1 Y1");
  render
      .add_option("--samples", o.sample_range,
                  "render only the samples FIRST <= s < LAST of every pixel (of -s in all)")
      ->type_name("FIRST LAST");
  render.add_option("--pass-samples", o.pass_samples,
                    "samples per pixel in each pass (default: spp / 64, at least 4)");
  render.add_flag("--literal-camera", o.literal_camera,
                  "COLLADA and model files: use the file's camera, not the homework framing");
  add_color_options(render, o.color);
  render.add_option("--exr-type", o.exr_options.pixel_type, "EXR pixel type: half or float");
  render.add_option("--exr-compression", o.exr_options.compression,
                    "EXR compression: zip, piz, dwaa or none");
  render.footer(render_footer());
}

void add_info_options(CLI::App& info, InfoOptions& o) {
  info.add_option("scene", o.scene,
                  "scene file (.dae, .json) or model file (.obj .ply .stl .gltf .glb .fbx)")
      ->required();
  info.add_option("--accel", o.accelerators, "accelerators to build (default: all)")
      ->delimiter(',')
      ->allow_extra_args(false);
  info.add_option("--set", o.set, "component parameter key=value")->allow_extra_args(false);
  info.add_option("-t,--threads", o.threads, "worker threads; 0 = all (default)");
  info.add_flag("--literal-camera", o.literal_camera,
                "COLLADA and model files: use the file's camera, not the homework framing");
}

void add_convert_options(CLI::App& convert, ConvertOptions& o) {
  convert.add_option("input", o.input, "scene-linear EXR to read (its R, G, B)")->required();
  convert.add_option("output", o.output, "display-referred file: .png, .jpg or .tif")->required();
  convert.add_option("--input-space", o.input_space,
                     "colour space of the EXR (default: its prism:colorSpace, else scene_linear)");
  convert.add_option("--ocio-config", o.color.ocio_config,
                     "OpenColorIO config file (default: $OCIO, else the bundled config)");
  convert.add_option("--display", o.color.display, "display (default: the config's)");
  convert.add_option("--view", o.color.view, "view of that display (default: the display's)");
  convert.add_option("--look", o.color.look, "look applied with the view");
  convert.add_option("--exposure", o.color.exposure, "exposure in stops, before the view");
}

void add_bench_options(CLI::App& bench, BenchOptions& o) {
  bench.add_option("scenes", o.scenes,
                   "scene files, or generated meshes gen:KIND:COUNT (e.g. gen:soup:100k); "
                   "default: the standard suite");
  bench.add_option("--json", o.json, "write the results here (JSON array of rows)")->required();
  bench.add_flag("--quick", o.quick, "reduced suite: 10k and 100k meshes, 256x256 primary rays");
  bench.add_option("--threads", o.threads, "thread counts to time")
      ->delimiter(',')
      ->capture_default_str();
  bench.add_option("--passes", o.passes, "timed passes after one warm-up (>= 5)")
      ->capture_default_str();
  bench.add_option("--resolution", o.resolution, "primary rays per image side (0: 512, quick 256)");
  bench
      .add_option("--backend", o.backends,
                  "embree, bvh or bvh:SPLIT:LAYOUT (repeatable; default: all)")
      ->allow_extra_args(false);
  bench.add_option("--set", o.set, "component parameter key=value")->allow_extra_args(false);
  bench
      .add_option("--min-pass-rays", o.min_pass_rays,
                  "each timed pass repeats a smaller ray set up to at least this many rays (0: as "
                  "many as the scene's largest set; 1: every set once)")
      ->capture_default_str();
  bench
      .add_option("--max-pass-seconds", o.max_pass_seconds,
                  "bench slow scenes on every k-th ray so one Embree pass takes at most this")
      ->capture_default_str();
}

void add_validate_options(CLI::App& validate, ValidateOptions& o) {
  validate.add_option("scene", o.scene,
                      "scene file or gen:KIND:COUNT (default with --replay: the file's)");
  validate.add_option("--rays", o.rays, "rays per set (P, S, D1, D2, R, F)")->capture_default_str();
  validate.add_option("--accel", o.accel, "backend under test")->capture_default_str();
  validate.add_option("--against", o.against, "backend to compare with")->capture_default_str();
  validate.add_option("--set", o.set, "component parameter key=value")->allow_extra_args(false);
  validate.add_option("--replay", o.replay, "re-run the rays of a failures file");
  validate.add_option("--failures", o.failures, "replay file of the rays that do not match")
      ->capture_default_str();
  validate.add_option("--heatmap", o.heatmap, "PNG of where they fall on the image")
      ->capture_default_str();
  validate.add_option("-t,--threads", o.threads, "worker threads; 0 = all (default)");
}

void add_merge_options(CLI::App& merge, MergeOptions& o) {
  merge
      .add_option("parts", o.parts,
                  "part files: EXRs of `prism render --crop/--samples`, or of an earlier merge")
      ->required();
  merge
      .add_option("-f,--output", o.output,
                  "the merged image (.exr, .png, .jpg, .tif), or a larger part (.exr) when the "
                  "parts are not the whole frame")
      ->required();
  merge.add_flag("--png", o.png, "also write a PNG beside the EXR");
  merge.add_flag("-q,--quiet", o.quiet, "no progress output");
  merge.footer(
      "The parts must be of one render (scene, options, resolution, spp, seed) and cover every "
      "pixel and sample of a box exactly once; the result is bit for bit the single render's. "
      "See docs/PRODUCTION.md.");
}

/// One line, whatever CLI11 put in its message.
std::string usage_error_line(const std::string& message, const std::string& help_hint) {
  std::string line = message;
  std::replace(line.begin(), line.end(), '\n', ' ');
  return line + "; see '" + help_hint + "'";
}

/// Under mpirun every rank parses its own command line: they must run the same command, else
/// every rank exits with the first failing rank's error (RankError, printed by rank 0), so that
/// no rank waits for others that are not coming.
void agree_on_command(int exit_code, const std::string& message, const nlohmann::json& command) {
  agree_across_ranks(RankStatus{exit_code, message, command}, "the command");
}

}  // namespace

RenderOptions parse_render_arguments(const std::vector<std::string>& arguments) {
  CLI::App render{"render", "render"};
  RenderOptions options;
  add_render_options(render, options);
  std::vector<std::string> args(arguments.rbegin(), arguments.rend());  // consumed from the back
  try {
    render.parse(args);
  } catch (const CLI::ParseError& e) {
    throw Error(ErrorKind::kUsage, usage_error_line(e.what(), "prism render --help"));
  }
  return options;
}

int run_cli(int argc, const char* const* argv) {
  CLI::App app{"prism: a CPU path tracer with a BVH and an Embree backend", "prism"};
  app.set_version_flag("--version", std::string("prism ") + PRISM_VERSION);
  app.require_subcommand(0, 1);
  app.footer("Run `prism COMMAND --help` for a command's options.");

  RenderOptions render_options;
  CLI::App* render = app.add_subcommand("render", "render a scene to EXR and/or PNG (default)");
  add_render_options(*render, render_options);

  InfoOptions info_options;
  CLI::App* info = app.add_subcommand(
      "info", "scene contents, camera, settings and each accelerator's build statistics");
  add_info_options(*info, info_options);

  CLI::App* list = app.add_subcommand(
      "list", "accelerators, integrators, scene formats, generated meshes, output formats");

  std::string ocio_config;
  CLI::App* colorspaces =
      app.add_subcommand("colorspaces", "colour spaces, displays, views and looks of a config");
  colorspaces->add_option("--ocio-config", ocio_config,
                          "OpenColorIO config file (default: $OCIO, else the bundled config)");

  ConvertOptions convert_options;
  CLI::App* convert = app.add_subcommand(
      "convert", "a PNG/JPEG/TIFF of an existing EXR through an OCIO display and view");
  add_convert_options(*convert, convert_options);

  BenchOptions bench_options;
  CLI::App* bench = app.add_subcommand(
      "bench", "time every backend on the same rays (build, memory, Mrays/s per ray set)");
  add_bench_options(*bench, bench_options);

  ValidateOptions validate_options;
  CLI::App* validate = app.add_subcommand(
      "validate", "compare two backends ray by ray, judged by a double-precision oracle");
  add_validate_options(*validate, validate_options);

  MergeOptions merge_options;
  CLI::App* merge = app.add_subcommand(
      "merge", "add up parts of a frame (render --crop, --samples) into the image, bit for bit");
  add_merge_options(*merge, merge_options);

  std::vector<std::string> args = arguments_with_default_command(argc, argv);
  if (args.empty()) {
    agree_on_command(kExitSuccess, "", "help");
    if (mpi::rank() == 0) std::fputs(app.help().c_str(), stdout);
    return kExitSuccess;
  }
  try {
    std::reverse(args.begin(), args.end());  // CLI11 consumes the vector from its back
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) {  // --help, --version: printed on stdout
      agree_on_command(kExitSuccess, "", "help");
      return mpi::rank() == 0 ? app.exit(e) : kExitSuccess;
    }
    std::string hint = "prism --help";
    for (const CLI::App* command : app.get_subcommands()) {
      hint = "prism " + command->get_name() + " --help";
    }
    const std::string message = usage_error_line(e.what(), hint);
    agree_on_command(kExitBadInput, message, nullptr);
    std::fprintf(stderr, "prism: error: %s\n", message.c_str());
    return kExitBadInput;
  }
  const std::vector<CLI::App*> commands = app.get_subcommands();
  agree_on_command(kExitSuccess, "", commands.empty() ? "" : commands.back()->get_name());

  // The commands that write images need the image module (color/image_io.h): a missing one
  // stops them now rather than after their work. MPI's worker ranks write none.
  if ((render->parsed() && mpi::rank() == 0) || convert->parsed() || merge->parsed()) {
    check_image_io();
  }
  if (render->parsed()) {
    render_options.command_line = quote_command_line(argc, argv);
    return run_render_command(render_options);
  }
  // Under mpirun only `render` runs on every rank: the other commands run on rank 0 alone.
  if (mpi::rank() != 0) return kExitSuccess;
  if (info->parsed()) return run_info_command(info_options);
  if (list->parsed()) return run_list_command();
  if (colorspaces->parsed()) return run_colorspaces_command(ocio_config);
  if (convert->parsed()) return run_convert_command(convert_options);
  if (bench->parsed()) return run_bench_command(bench_options);
  if (validate->parsed()) {
    validate_options.accel_given = validate->count("--accel") > 0;
    validate_options.against_given = validate->count("--against") > 0;
    return run_validate_command(validate_options);
  }
  if (merge->parsed()) {
    merge_options.command_line = quote_command_line(argc, argv);
    return run_merge_command(merge_options);
  }
  std::fputs(app.help().c_str(), stdout);
  return kExitSuccess;
}

}  // namespace prism
