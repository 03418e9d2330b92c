// `rayster bench`: the parent runs each configuration of a plan in a child process (itself, through
// /proc/self/exe: a fresh device per configuration, since re-creating targets at another size in
// one process was seen to slow later passes 2–4× on the H100), collects each child's JSON and
// writes the results as JSON, CSV and SVG.
#include "app/bench_command.h"
#include "app/settings_cli.h"

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include <fmt/format.h>

#include "app/bench_report.h"
#include "app/bench_shard.h"
#include "app/build_info.h"
#include "app/device_option.h"
#include "core/log.h"
#include "render/renderer.h"
#include "rhi/context.h"
#include "scene/loader.h"

namespace rayster::app {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

int fail(const Error& e) {
  std::fprintf(stderr, "rayster: error: %s\n", e.message.c_str());
  return int(e.code);
}

Status writeText(const std::string& path, const std::string& text) {
  const fs::path p(path);
  if (p.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(p.parent_path(), ec);
  }
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp);
    f << text;
    if (!f) return makeError(ExitCode::OutputFailed, "cannot write {}", path);
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) return makeError(ExitCode::OutputFailed, "cannot write {}: {}", path, ec.message());
  return okStatus();
}

Result<json> readJson(const std::string& path) {
  std::ifstream f(path);
  if (!f) return makeError(ExitCode::BadInput, "cannot read '{}'", path);
  try {
    return json::parse(f);
  } catch (const std::exception& e) {
    return makeError(ExitCode::BadInput, "'{}' is not JSON: {}", path, e.what());
  }
}

double graysPerSecond(uint64_t rays, double ms) { return ms > 0 ? double(rays) / ms * 1e-6 : 0.0; }

// ---- child: one configuration in this process ----

json passJson(const render::PassStats& p) {
  const Summary s = summarize(p.samplesMs);
  return {{"name", p.name},
          {"median_ms", p.medianMs},
          {"p95_ms", p.p95Ms},
          {"min_ms", p.minMs},
          {"p5_ms", s.p5},
          {"max_ms", s.max},
          {"frames", p.samples},
          {"samples_ms", p.samplesMs},
          {"rays", p.info.rays},
          {"rays_exact", p.info.raysExact},
          {"grays_per_s", graysPerSecond(p.info.rays, p.medianMs)}};
}

json configResult(const rhi::Context& ctx, const BenchConfig& c, const render::RenderSettings& s,
                  const render::RenderOutput& out) {
  json j = c.toJson();
  j["id"] = c.id();
  j["render_settings"] = settingsJson(s);  // every setting of the table, as this configuration ran
  j["ok"] = true;
  j["device"] = ctx.info().name;
  j["driver"] = ctx.info().driverInfo;
  j["primary_used"] = render::primaryName(out.primaryUsed);
  j["shadow_layers"] = out.shadowLayers;
  if (out.visibleDraws >= 0) j["draws"] = {{"visible", out.visibleDraws}, {"total", out.totalDraws}};
  if (out.rasterGBufferMs >= 0)
    j["auto"] = {{"raster_gbuffer_ms", out.rasterGBufferMs}, {"traced_gbuffer_ms", out.tracedGBufferMs}};
  uint64_t rays = 0;
  for (const auto& p : out.passes) {
    json pj = passJson(p);
    // The raw-rate twin traced the same rays with trivial shaders: the pass reaches raw/pass of its rate.
    for (const auto& r : out.passes)
      if (r.info.twinOf == p.name && p.medianMs > 0) {
        pj["raw_ms"] = r.medianMs;
        pj["raw_fraction"] = r.medianMs / p.medianMs;
      }
    j["passes"].push_back(pj);
    if (p.info.kind == graph::PassKind::Frame) rays += p.info.rays;
  }
  const Summary gpu = summarize(out.frameGpuMs);
  j["frame"] = {{"gpu_ms", summaryJson(gpu)},
                {"cpu_ms", summaryJson(summarize(out.frameCpuMs))},
                {"wall_ms", summaryJson(summarize(out.frameWallMs))},
                {"gpu_samples_ms", out.frameGpuMs},
                {"cpu_samples_ms", out.frameCpuMs},
                {"rays", rays},
                {"grays_per_s", graysPerSecond(rays, gpu.median)}};
  const auto& st = out.scene;
  j["scene_stats"] = {{"triangles", st.triangles}, {"spheres", st.spheres}, {"lights", st.lights}};
  j["accel"] = {{"blas_bytes", st.blasBytes},
                {"blas_compacted_bytes", st.blasCompactedBytes},
                {"tlas_bytes", st.tlasBytes},
                {"build_ms", st.accelBuildMs},
                {"upload_ms", st.uploadMs}};
  j["memory"] = {{"used_bytes", st.deviceBytesUsed},
                 {"reserved_bytes", st.deviceBytesReserved},
                 {"image_bytes", st.imageBytes},
                 {"buffer_bytes", st.bufferBytes},
                 {"accel_bytes", st.accelBytes},
                 {"host_bytes", st.hostBytes},
                 {"frame_bytes", st.frameBytes},
                 {"transient_bytes", st.transientBytes},
                 {"transient_unaliased_bytes", st.transientUnaliasedBytes},
                 {"history_bytes", st.historyBytes}};
  return j;
}

Result<json> runConfig(const BenchOptions& o, const BenchConfig& c) {
  auto scene = scene::loadScene(c.scene);
  if (!scene) return scene.error();
  auto ctx = rhi::Context::create({o.validation, true, deviceSelector(o.device), o.debugLabels});
  if (!ctx) return ctx.error();
  json result;
  {
    auto renderer = render::Renderer::create(**ctx, *scene);
    if (!renderer) return renderer.error();
    render::RenderSettings s;
    s.width = c.width;
    s.height = c.height;
    s.frames = c.warmup + c.frames;
    s.warmupFrames = c.warmup;
    s.seed = c.seed;
    s.mode = c.mode == "pathtrace" ? render::Mode::PathTrace
             : c.mode == "raster"  ? render::Mode::Raster
                                   : render::Mode::Hybrid;
    s.primary = c.primary == "raster" ? render::Primary::Raster
                : c.primary == "rt"   ? render::Primary::Traced
                                      : render::Primary::Auto;
    s.maxDepth = c.maxDepth;
    s.shadowLights = c.shadowLights;
    s.rawRays = c.rawRays;
    s.culling = c.culling;
    if (Status applied = applySettings(c.settings, s); !applied) return applied.error();
    s.maxDepth = c.maxDepth;  // the plan's depth already holds a preset's (bench_plan.cpp sweepDepths)
    auto out = (*renderer)->render(s);
    if (!out) return out.error();
    result = configResult(**ctx, c, s, *out);
  }
  if ((*ctx)->validationEnabled() && (*ctx)->validationErrors() > 0)
    return makeError(ExitCode::Failure, "{} Vulkan validation error(s)", (*ctx)->validationErrors());
  return result;
}

int childCommand(const BenchOptions& o) {
  json cj;
  try {
    cj = json::parse(o.child);
  } catch (const std::exception& e) {
    return fail(makeError(ExitCode::BadArguments, "--child: {}", e.what()));
  }
  auto config = BenchConfig::fromJson(cj);
  if (!config) return fail(config.error());
  auto result = runConfig(o, *config);
  if (!result) return fail(result.error());
  if (auto s = writeText(o.childOut, result->dump() + "\n"); !s) return fail(s.error());
  return 0;
}

// ---- parent: spawn a child per configuration ----

// Runs this binary with `args`; returns its exit status (-1: it could not start or was killed).
int spawnSelf(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  static const char* kSelf = "/proc/self/exe";
  argv.push_back(const_cast<char*>(kSelf));
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    execv(kSelf, argv.data());
    _exit(127);
  }
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string isoDate() {
  const std::time_t now = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return buf;
}

std::string withExtension(const std::string& path, const char* ext) {
  return fs::path(path).replace_extension(ext).string();
}

void printSummary(const json& c) {
  std::fflush(stderr);
  std::printf("%-48s frame %8.3f ms (p95 %.3f), CPU %.3f ms, %.2f G rays/s\n", c.value("id", "").c_str(),
              c["frame"]["gpu_ms"].value("median", 0.0), c["frame"]["gpu_ms"].value("p95", 0.0),
              c["frame"]["cpu_ms"].value("median", 0.0), c["frame"].value("grays_per_s", 0.0));
  std::fflush(stdout);
}

// The results as JSON, CSV and SVG (the CSV and SVG beside the JSON unless given).
Status writeResults(const BenchOptions& o, const json& results) {
  const std::string csvPath = o.csv.empty() ? withExtension(o.json, ".csv") : o.csv;
  const std::string svgPath = o.svg.empty() ? withExtension(o.json, ".svg") : o.svg;
  if (auto s = writeText(o.json, results.dump(1) + "\n"); !s) return s;
  if (auto s = writeText(csvPath, benchCsv(results)); !s) return s;
  if (auto s = writeText(svgPath, benchSvg(results)); !s) return s;
  size_t failures = 0;
  for (const auto& c : results["configs"]) failures += c.value("ok", false) ? 0 : 1;
  log::info("wrote {}, {}, {} ({} configuration(s), {} failed)", o.json, csvPath, svgPath, results["configs"].size(),
            failures);
  return okStatus();
}

int parentCommand(const BenchOptions& o) {
  auto plan = o.plan.empty() ? planFromAxes(o.axes) : loadPlan(o.plan);
  if (!plan) return fail(plan.error());
  if (fs::path(o.json).extension() != ".json")
    return fail(makeError(ExitCode::BadArguments, "--json '{}' must end in .json", o.json));
  std::optional<Shard> shard;
  const size_t planConfigs = plan->configs.size();
  if (!o.shard.empty()) {
    auto s = parseShard(o.shard);
    if (!s) return fail(s.error());
    shard = *s;
    *plan = shardOf(*plan, *shard);
    log::info("bench: shard {}/{} runs {} of the plan's {} configuration(s)", shard->index, shard->count,
              plan->configs.size(), planConfigs);
  }
  const fs::path work = fs::path(o.json).string() + ".parts";
  std::error_code ec;
  fs::create_directories(work, ec);
  if (ec) return fail(makeError(ExitCode::OutputFailed, "cannot create {}: {}", work.string(), ec.message()));

  json results = {{"schema", "rayster-bench/1"}, {"plan", plan->name}, {"date", isoDate()},
                  {"commit", buildCommit()},     {"device", ""},       {"driver", ""}};
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  results["host"] = host;
  results["configs"] = json::array();
  if (shard) results["shard"] = shardJson(*shard, planConfigs);
  size_t failures = 0;
  for (size_t i = 0; i < plan->configs.size(); ++i) {
    const BenchConfig& c = plan->configs[i];
    const std::string part = (work / fmt::format("{:04}.json", i)).string();
    fs::remove(part, ec);
    log::info("bench {}/{}: {}", i + 1, plan->configs.size(), c.id());
    std::vector<std::string> args = {"bench", "--child", c.toJson().dump(), "--child-out", part};
    if (o.validation) args.push_back("--validation");
    if (!o.device.empty()) args.insert(args.end(), {"--device", o.device});
    if (!o.debugLabels) args.push_back("--no-debug-labels");
    const int code = spawnSelf(args);
    json r;
    if (code == 0) {
      auto parsed = readJson(part);
      if (parsed) r = std::move(*parsed);
    }
    if (r.is_null()) {
      // A failed configuration is recorded, and the others still run.
      r = c.toJson();
      r["id"] = c.id();
      r["ok"] = false;
      r["error"] = fmt::format("child exited with code {}", code);
      ++failures;
      std::fprintf(stderr, "rayster: bench: %s failed (exit code %d)\n", c.id().c_str(), code);
    } else {
      if (results["device"] == "") {
        results["device"] = r.value("device", "");
        results["driver"] = r.value("driver", "");
      }
      printSummary(r);
    }
    results["configs"].push_back(r);
  }
  fs::remove_all(work, ec);
  if (auto s = writeResults(o, results); !s) return fail(s.error());
  return failures == 0 ? 0 : int(ExitCode::Failure);
}

int mergeCommand(const BenchOptions& o) {
  if (fs::path(o.json).extension() != ".json")
    return fail(makeError(ExitCode::BadArguments, "--json '{}' must end in .json", o.json));
  std::vector<json> shards;
  for (const std::string& path : o.merge) {
    auto j = readJson(path);
    if (!j) return fail(j.error());
    shards.push_back(std::move(*j));
  }
  auto merged = mergeShards(shards, o.merge);
  if (!merged) return fail(merged.error());
  if (auto s = writeResults(o, *merged); !s) return fail(s.error());
  for (const auto& c : (*merged)["configs"])
    if (!c.value("ok", false)) return int(ExitCode::Failure);  // as the unsharded run would
  return 0;
}

int compareCommandBench(const BenchOptions& o) {
  auto a = readJson(o.compare[0]);
  if (!a) return fail(a.error());
  auto b = readJson(o.compare[1]);
  if (!b) return fail(b.error());
  const auto changes = compareResults(*a, *b, o.minChange);
  size_t flagged = 0;
  std::printf("%-44s %-22s %10s %10s %8s %-13s %8s\n", "config", "pass", "A ms", "B ms", "change", "test", "p");
  for (const auto& c : changes) {
    if (!c.flagged) continue;
    ++flagged;
    std::printf("%-44s %-22s %10.4f %10.4f %+7.1f%% %-13s %8s  CHANGED\n", c.config.c_str(), c.pass.c_str(), c.medianA,
                c.medianB, 100.0 * c.relative, c.test.c_str(), c.p < 0 ? "-" : fmt::format("{:.2g}", c.p).c_str());
  }
  std::printf("%zu of %zu pass(es) changed by more than %.0f %% and significantly (%s vs %s)\n", flagged,
              changes.size(), 100.0 * o.minChange, o.compare[0].c_str(), o.compare[1].c_str());
  if (changes.empty()) std::fprintf(stderr, "rayster: bench --compare: no configuration in common\n");
  return flagged > 0 && o.failOnChange ? int(ExitCode::TestFailed) : 0;
}

}  // namespace

int benchCommand(const BenchOptions& o) {
  if (!o.compare.empty()) {
    if (o.compare.size() != 2) return fail(makeError(ExitCode::BadArguments, "--compare takes two result files"));
    return compareCommandBench(o);
  }
  if (!o.child.empty()) return childCommand(o);
  if (!o.merge.empty()) {
    if (!o.shard.empty() || !o.plan.empty())
      return fail(makeError(ExitCode::BadArguments, "--merge runs nothing: it takes no --plan or --shard"));
    return mergeCommand(o);
  }
  return parentCommand(o);
}

}  // namespace rayster::app
