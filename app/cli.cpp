// Command-line front end: parses arguments with CLI11 and maps every failure to a documented
// exit code with a one-line cause.
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/bench_command.h"
#include "app/build_info.h"
#include "app/commands.h"
#include "app/compare_command.h"
#include "app/farm_command.h"
#include "app/info_command.h"
#include "app/render_command.h"
#include "app/settings_cli.h"
#include "app/viewer/viewer.h"
#include "core/error.h"
#include "core/log.h"

namespace rayster::app {

namespace {
constexpr const char* kExitCodes =
    "Exit codes:\n"
    "  0 ok, 1 other failure (or validation errors with --validation), 2 bad arguments,\n"
    "  3 missing or invalid input file, 4 no Vulkan device (or none matching --device), 5 missing capability\n"
    "  (ray tracing with --require-rt), 6 device lost, 7 out of memory, 8 output could not be written, 9 comparison "
    "over budget,\n"
    "  130/143 render stopped by SIGINT/SIGTERM (the frame being rendered dropped; every file left is whole).\n"
    "  Retryable (--skip-existing resumes a sequence): 4, 6, 7, 8, 130, 143. Permanent (the same command fails\n"
    "  the same way): 2, 3, 5, 9. 1 is unexpected: retry once, then report it.";

bool parseSize(const std::string& text, uint32_t& w, uint32_t& h) {
  unsigned a = 0, b = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%u%c%u%c", &a, &x, &b, &extra) != 3 || (x != 'x' && x != 'X')) return false;
  if (a == 0 || b == 0 || a > 16384 || b > 16384) return false;
  w = a;
  h = b;
  return true;
}

int badArguments(const std::string& message) {
  std::fprintf(stderr, "rayster: error: %s\n", message.c_str());
  return int(ExitCode::BadArguments);
}

// Options every subcommand takes (before or after its name: the subcommands fall through).
struct GlobalOptions {
  bool verbose = false;
  bool validation = std::getenv("RAYSTER_VALIDATION") && std::string(std::getenv("RAYSTER_VALIDATION")) == "1";
  std::string device;
  bool noLabels = false;
};

void addGlobalOptions(CLI::App& cli, GlobalOptions& g) {
  cli.add_flag("-v,--verbose", g.verbose, "Print debug details (device, scene statistics)");
  cli.add_flag("--validation", g.validation,
               "Enable Vulkan validation (also RAYSTER_VALIDATION=1); any error fails the run");
  cli.add_option("--device", g.device,
                 "Use this device: its index or UUID as `rayster info` lists them, or text its name contains "
                 "(the best such device); exit 4 listing the devices when none matches");
  cli.add_flag("--no-debug-labels", g.noLabels, "Do not emit debug labels and object names (on by default)");
  cli.set_version_flag("--version", fmt::format("rayster {} (commit {})", buildVersion(), buildCommit()),
                       "Print the version and the commit this binary was built from");
}

// `rayster render`: what CLI11 fills directly (options) and the words converted after parsing.
struct RenderArgs {
  CLI::App* app = nullptr;
  RenderOptions options;
  std::string size = "1280x720";
  SettingValues settings;  // the settings table's options given (render/settings_table.h)
  uint32_t spp = 0;
  std::vector<std::string> moveInstance;
};

// The four groups below add the options in the order `rayster render --help` lists them.
// Scene, outputs, size and sampling.
void addRenderImageOptions(CLI::App* render, RenderArgs& a) {
  RenderOptions& ro = a.options;
  render->add_option("scene", ro.scene,
                     "Scene: a .gltf/.glb, .obj or .json scene file, or builtin:NAME (cornell, whitted, spheres, "
                     "instances[:N]); default builtin:whitted");
  render->add_option("-o,--output", ro.output, "Output image, .png (tonemapped) or .exr (linear HDR)");
  render->add_option("--hdr", ro.hdrOutput, "Also write the linear HDR image to this .exr");
  render->add_flag("--exr-float", ro.exrFloat,
                   "Write EXR files (-o, --hdr, --aov) with 32-bit float channels instead of half floats, whose "
                   "largest value is 65504 (larger values are clamped there)");
  render->add_option("--size", a.size, "Image size WxH (default 1280x720; 640x360 on a CPU device such as lavapipe)");
  render
      ->add_option("--frames", ro.settings.frames,
                   "Frames to accumulate for the static camera (default 16; 4 on a CPU device such as lavapipe)")
      ->check(CLI::Range(1u, 100000u));
  render->add_option("--seed", ro.settings.seed, "Random seed; the same seed gives the same image");
  render->add_option("--spp", a.spp, "Samples per pixel of --mode pathtrace, one per frame (sets --frames)")
      ->check(CLI::Range(1u, 100000u));
}

// What the frame renders and how the camera and the scene move.
void addRenderFrameOptions(CLI::App* render, RenderArgs& a) {
  RenderOptions& ro = a.options;
  render->add_flag("--require-rt", ro.requireRt,
                   "Exit with code 5 on a device without ray-tracing pipelines instead of rendering with "
                   "--mode raster (the default fallback, announced in one line)");
  render->add_option("--camera", ro.settings.camera, "Camera name from the scene");
  render->add_option(
      "--variant", ro.variant,
      "Material variant by name (glTF KHR_materials_variants; an unknown name lists the scene's variants)");
  render->add_option("--time", ro.settings.time, "Animation time of the first frame, in seconds (default 0)");
  render->add_flag("--pause{false}", ro.settings.animate,
                   "Hold glTF animations at --time instead of playing them at --path-fps");
  render->add_flag("--camera-path", ro.settings.cameraPath,
                   "Fly along the scene file's camera path, one frame per 1/--path-fps seconds");
  render->add_option("--path-fps", ro.settings.pathFps, "Frames per second of path playback (default 60)")
      ->check(CLI::Range(1.0f, 10000.0f));
}

// Image sequences (docs/sequences.md) and progress.
void addRenderSequenceOptions(CLI::App* render, RenderArgs& a) {
  RenderOptions& ro = a.options;
  render->add_option("--frames-out", ro.framesOut,
                     "Write frames FIRST to LAST (every STEP-th) of the animation and camera path, one image each: "
                     "FIRST:LAST[:STEP]; frame F is at --time + F / --path-fps; -o (and --hdr) name each with # "
                     "runs replaced by the zero-padded frame number, e.g. out/shot_####.png. Each frame renders "
                     "--frames frames from fresh histories, ending on it, so a chunk's pixels equal the whole range's");
  render->add_flag("--skip-existing", ro.skipExisting,
                   "With --frames-out: do not render frames whose image (-o, and --hdr if given) exists already, "
                   "to resume an interrupted range");
  render->add_option("--progress", ro.progress,
                     "auto (default: a bar on a terminal, lines elsewhere), bar (frame, rate, ETA redrawn in place), "
                     "lines (one per output frame, at most every 2 s, and every 10 s within a frame) or off");
}

// Timings, memory, intermediate images, raw-rate twins, scripted edits, JSON.
void addRenderReportOptions(CLI::App* render, RenderArgs& a) {
  RenderOptions& ro = a.options;
  render->add_flag("--timings", ro.printTimings, "Print per-pass GPU times");
  render->add_flag("--memory-report", ro.memoryReport,
                   "Print the last frame's images (G-buffer, targets, histories): format, size, bytes, and which "
                   "transients share memory");
  render->add_option("--aov", ro.aovs,
                     "Also write intermediates as <stem>.<name>.png and .exr: all, or a comma-separated list of "
                     "any image of the frame by its name (--memory-report lists them; NAME:LAYER for a layer of "
                     "an array) or of the names depth, normal, albedo, material, emissive, shadow-raw, "
                     "shadow-denoised, reflection-raw, reflection-denoised, ao-raw, ao-denoised, indirect-raw, "
                     "indirect-denoised, and per shadowed light N (0-7) shadowN-raw, shadowN-denoised; --mode "
                     "pathtrace: variance (of the mean); --raw-rays: raw-ao, raw-direct, raw-indirect, raw-specular "
                     "(what each raw twin's rays did)");
  render->add_flag("--raw-rays", ro.settings.rawRays,
                   "Also trace every ray-traced pass's rays with trivial shaders (the bench's raw-rate twins)");
  render->add_option("--move-instance", a.moveInstance,
                     "At frame FRAME (0-based) move the named instance to X,Y,Z: NAME:X,Y,Z@FRAME, repeatable "
                     "(motion vectors and the TLAS follow)");
  render->add_option("--json", ro.jsonOutput,
                     "Write per-pass GPU times and settings as JSON to this file; with --frames-out also a "
                     "\"sequence\" summary (frames written and skipped, wall time, frames/s, encoding time)");
}

void addRenderCommand(CLI::App& cli, RenderArgs& a) {
  a.app = cli.add_subcommand("render", "Render a scene to an image, headless");
  addRenderImageOptions(a.app, a);
  addRenderFrameOptions(a.app, a);
  addSettingOptions(a.app, render::kUseRender, a.settings);  // mode, effects, tonemap, ...: the settings table
  addRenderSequenceOptions(a.app, a);
  addRenderReportOptions(a.app, a);
}

// The parsed words of `rayster render` into its settings.
Status convertRenderArgs(RenderArgs& a, const GlobalOptions& g) {
  RenderOptions& ro = a.options;
  if (!parseSize(a.size, ro.settings.width, ro.settings.height))
    return makeError(ExitCode::BadArguments, "--size must be WxH with 1..16384 each, got '{}'", a.size);
  if (Status applied = applySettings(a.settings, ro.settings); !applied) return applied;
  if (a.spp > 0) ro.settings.frames = a.spp;
  ro.sizeGiven = a.app->count("--size") > 0;
  ro.framesGiven = a.app->count("--frames") > 0 || a.spp > 0;
  if (Status m = parseMoves(a.moveInstance, ro.settings.moves); !m) return m;
  ro.validation = g.validation;
  ro.device = g.device;
  ro.debugLabels = !g.noLabels;
  return okStatus();
}

int runRender(RenderArgs& a, const GlobalOptions& g) {
  if (Status s = convertRenderArgs(a, g); !s) return badArguments(s.error().message);
  return renderCommand(a.options);
}

// `farm slurm`'s pass-through options, parsed and converted as `rayster render ARGS` would.
Status checkRenderArgs(const std::vector<std::string>& args) {
  CLI::App cli;
  GlobalOptions g;
  addGlobalOptions(cli, g);
  RenderArgs a;
  addRenderCommand(cli, a);
  a.app->fallthrough();
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
  reversed.push_back("render");
  try {
    cli.parse(reversed);
  } catch (const CLI::ParseError& e) {
    return makeError(ExitCode::BadArguments, "{}", e.what());
  }
  if (a.app->count("scene") > 0)
    return makeError(ExitCode::BadArguments, "unexpected '{}' (the scene goes before --)", a.options.scene);
  return convertRenderArgs(a, g);
}

CLI::App* addBenchCommand(CLI::App& cli, BenchOptions& bo) {
  CLI::App* bench =
      cli.add_subcommand("bench",
                         "Time scenes x sizes x modes (one process per configuration): per-pass GPU ms, rays, memory; "
                         "writes JSON, CSV and an SVG plot. --compare A.json B.json reports significant changes");
  bench->add_option("scenes", bo.axes.scenes, "Scenes (as for render); default builtin:whitted");
  bench->add_option("--size,--sizes", bo.axes.sizes, "Image sizes WxH, comma-separated (default 1920x1080)")
      ->delimiter(',');
  bench->add_option("--mode,--modes", bo.axes.modes, "Modes, comma-separated: hybrid, pathtrace, raster")
      ->delimiter(',');
  bench->add_option("--primary", bo.axes.primaries, "G-buffer producers, comma-separated: raster, rt, auto")
      ->delimiter(',');
  bench
      ->add_option("--max-depth", bo.axes.maxDepths,
                   "Specular bounce depths, comma-separated (1-8, default 7; 5 with --effects mirrors)")
      ->delimiter(',');
  bench->add_option("--shadow-lights", bo.axes.shadowLights, "As for render (0-8, default 8)");
  bench->add_option("--warmup", bo.axes.warmup, "Frames rendered before measuring (default 16)");
  bench->add_option("--frames", bo.axes.frames, "Frames measured after the warm-up (default 64)")
      ->check(CLI::Range(1u, 100000u));
  bench->add_option("--seed", bo.axes.seed, "Random seed (default 1)");
  bench->add_flag("--raw-rays", bo.axes.rawRays,
                  "Also trace the rays of every ray-traced pass (primary, shadows, AO, direct, indirect, specular) "
                  "with trivial shaders and report each pass's share of that raw ray rate (raw_fraction)");
  addSettingOptions(bench, render::kUseBench, bo.axes.settings);  // applied to every configuration
  bench->add_option("--plan", bo.plan, "A JSON plan of sweeps (bench/plans/*.json) instead of the axes above");
  bench->add_option("--shard", bo.shard,
                    "I/N: run only configurations I, I+N, I+2N, ... of the plan (1-based; docs/farm.md); the JSON "
                    "records the shard for --merge");
  bench
      ->add_option("--merge", bo.merge,
                   "Merge the results of every --shard I/N of one plan into --json, in plan order, instead of running")
      ->expected(1, -1);
  bench->add_option("--json", bo.json, "Results (default bench-out/bench.json); CSV and SVG beside it");
  bench->add_option("--csv", bo.csv, "CSV output (default: the --json path with .csv)");
  bench->add_option("--svg", bo.svg, "SVG plot (default: the --json path with .svg)");
  bench->add_option("--compare", bo.compare, "Compare two result files instead of running: A.json B.json")->expected(2);
  bench->add_option("--min-change", bo.minChange,
                    "--compare reports changes of the median larger than this fraction (default 0.05)");
  bench->add_flag("--fail-on-change", bo.failOnChange, "--compare exits 9 when it reports a change");
  bench->add_option("--child", bo.child, "(internal) run one configuration, given as JSON")->group("");
  bench->add_option("--child-out", bo.childOut, "(internal) where the child writes its JSON")->group("");
  bench->fallthrough();
  return bench;
}

CLI::App* addCompareCommand(CLI::App& cli, CompareOptions& co) {
  CLI::App* compare = cli.add_subcommand(
      "compare", "Compare two images (PNG or EXR): FLIP, HDR-FLIP, PSNR, RMSE, relative MSE (docs/compare.md)");
  compare->add_option("reference", co.reference, "Reference image")->required();
  compare->add_option("test", co.test, "Image to compare with the reference")->required();
  compare
      ->add_option("--metric", co.metrics,
                   "flip, hdr-flip, psnr, rmse, relmse or all (default); repeat or comma-separate")
      ->delimiter(',')
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  compare->add_option("--mask", co.mask, "Only pixels whose rgb is nonzero in this PNG count");
  compare->add_option("--heatmap", co.heatmap,
                      "Write the per-pixel error as a .png: the FLIP map in magma (HDR-FLIP for an HDR reference), "
                      "or an 8-bit difference ramp when no FLIP metric is computed");
  compare->add_option("--json", co.json, "Write every metric, the exposures and budgets as JSON to this file");
  compare
      ->add_option("--budget", co.budgets,
                   "METRIC=VALUE; exit 9 when over it (flip, hdr-flip, rmse, relmse: at most; psnr: at least); "
                   "repeat or comma-separate")
      ->delimiter(',')
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  compare->add_option("--ppd", co.ppd, "FLIP observer, pixels per degree of visual angle (default 67)")
      ->check(CLI::PositiveNumber);
  compare->add_option("--tolerance", co.tolerance, "Per-channel tolerance in 1/255 steps (default 2)");
  compare->add_option("--min-fraction", co.minFraction,
                      "Exit 9 unless at least this fraction of pixels is within tolerance (e.g. 0.999)");
  compare->fallthrough();
  return compare;
}

// Parses the command line. Returns the exit code to end with after --help, --version or a parse
// error (reported in one line), nothing when a subcommand should run.
std::optional<int> parse(CLI::App& cli, int argc, char** argv) {
  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return cli.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return cli.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return cli.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "rayster: error: %s (see rayster --help)\n", e.what());
    return int(ExitCode::BadArguments);
  }
  return std::nullopt;
}

}  // namespace

int run(int argc, char** argv) {
  CLI::App cli{"Rayster: a real-time hybrid (raster + ray-traced) renderer on Vulkan."};
  cli.footer(kExitCodes);
  cli.require_subcommand(1);
  GlobalOptions global;
  addGlobalOptions(cli, global);
  RenderArgs render;
  addRenderCommand(cli, render);
  BenchOptions bo;
  CLI::App* bench = addBenchCommand(cli, bo);
  CLI::App* info = cli.add_subcommand(
      "info", "List Vulkan devices (index and UUID, what --device takes) and their ray-tracing capabilities");
  bool infoJson = false;
  info->add_flag("--json", infoJson, "Print a JSON array, one object per device");
  CompareOptions co;
  CLI::App* compare = addCompareCommand(cli, co);
  ViewCommand view;
  addViewCommand(cli, view);
  FarmOptions farm;
  farm.checkRenderArgs = checkRenderArgs;
  CLI::App* farmApp = addFarmCommand(cli, farm);
  render.app->fallthrough();  // global options (-v, --validation, --device) also after the subcommand
  info->fallthrough();

  if (const std::optional<int> done = parse(cli, argc, argv)) return *done;
  if (global.verbose) log::setLevel(log::Level::Debug);
  // Headless runs need no display, but Mesa and the loader expect a runtime directory.
  setenv("XDG_RUNTIME_DIR", "/tmp", /*overwrite=*/0);

  if (info->parsed()) return infoCommand(infoJson);
  if (bench->parsed()) {
    bo.validation = global.validation;
    bo.device = global.device;
    bo.debugLabels = !global.noLabels;
    return benchCommand(bo);
  }
  if (compare->parsed()) return compareCommand(co);
  if (view.app->parsed()) return viewCommand(view, global.validation, global.device, !global.noLabels);
  if (render.app->parsed()) return runRender(render, global);
  if (farmApp->parsed()) return farmCommand(farm);
  return int(ExitCode::BadArguments);
}

}  // namespace rayster::app
