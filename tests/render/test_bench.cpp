// `rayster bench` on lavapipe at a tiny size: the results are complete and well formed, the CSV and
// SVG parse, and --compare flags a doctored pass but nothing in a file compared with itself. No
// timing assertions (lavapipe times are not performance).
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/bench_stats.h"
#include "app/build_info.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

using nlohmann::json;

void expectFiniteNumber(const json& j, const std::string& key, const std::string& where) {
  ASSERT_TRUE(j.contains(key)) << where << ": missing " << key;
  ASSERT_TRUE(j[key].is_number()) << where << ": " << key << " is not a number";
  EXPECT_TRUE(std::isfinite(j[key].get<double>())) << where << ": " << key;
  EXPECT_GE(j[key].get<double>(), 0.0) << where << ": " << key;
}

void expectSummary(const json& s, const std::string& where) {
  for (const char* k : {"median", "p5", "p95", "min", "max", "mean"}) expectFiniteNumber(s, k, where);
}

// One bench run shared by the BenchRun tests: two configurations (two sizes), 2 warm-up + 3 frames.
// ctest runs the BenchRun suite as one test, in one process (tests/CMakeLists.txt), so the run is
// made once; a BenchRun test run alone makes it itself. It lives in the process's folder
// (tests/support/test_dirs.h), since it outlives the test that made it.
const std::filesystem::path& benchRun() {
  static const std::filesystem::path dir = [] {
    auto d = processDir() / "bench-run";
    std::filesystem::create_directories(d);
    RunResult r =
        runRayster("bench builtin:cornell --size 64x36,48x32 --primary rt --warmup 2 --frames 3 --raw-rays --json " +
                   (d / "a.json").string());
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return d;
  }();
  return dir;
}

TEST(BenchRun, JsonIsCompleteAndWellFormed) {
  const json j = json::parse(readText(benchRun() / "a.json"));
  EXPECT_EQ(j.value("schema", ""), "rayster-bench/1");
  for (const char* k : {"device", "driver", "commit", "date", "plan", "host"}) EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_FALSE(j["device"].get<std::string>().empty());
  EXPECT_EQ(j["commit"], app::buildCommit());  // stamped by the build (tests/render/test_build_info.cpp)
  ASSERT_EQ(j["configs"].size(), 2u);
  for (const json& c : j["configs"]) {
    const std::string id = c.value("id", "");
    ASSERT_TRUE(c.value("ok", false)) << id << ": " << c.dump();
    for (const char* k : {"width", "height", "max_depth", "warmup", "frames", "seed"}) expectFiniteNumber(c, k, id);
    for (const char* k : {"scene", "mode", "primary", "primary_used", "sweep", "axis", "device", "driver"})
      EXPECT_TRUE(c.contains(k) && c[k].is_string()) << id << ": " << k;
    EXPECT_EQ(c["frames"], 3);
    ASSERT_FALSE(c["passes"].empty()) << id;
    bool tracedSomething = false;
    for (const json& p : c["passes"]) {
      const std::string where = id + " " + p.value("name", "?");
      for (const char* k : {"median_ms", "p95_ms", "min_ms", "p5_ms", "max_ms", "rays", "grays_per_s"})
        expectFiniteNumber(p, k, where);
      ASSERT_EQ(p["samples_ms"].size(), 3u) << where;  // the warm-up frames are left out
      EXPECT_LE(p["min_ms"].get<double>(), p["median_ms"].get<double>()) << where;
      EXPECT_LE(p["median_ms"].get<double>(), p["p95_ms"].get<double>()) << where;
      tracedSomething = tracedSomething || p["rays"].get<uint64_t>() > 0;
    }
    EXPECT_TRUE(tracedSomething) << id;
    // --raw-rays: every ray-traced pass reports its share of the raw ray rate (its raw twin's time
    // over its own); no other pass does. Cornell: no many lights, so no rt-direct.
    const std::set<std::string> twinned = {"gbuffer-traced", "rt-shadows",  "rt-ao",
                                           "rt-direct",      "rt-indirect", "rt-specular"};
    std::set<std::string> withRaw;
    for (const json& p : c["passes"]) {
      const std::string name = p.value("name", "?");
      EXPECT_EQ(p.contains("raw_fraction"), twinned.count(name) > 0) << id << " " << name;
      if (p.contains("raw_fraction")) {
        withRaw.insert(name);
        expectFiniteNumber(p, "raw_fraction", id + " " + name);
        expectFiniteNumber(p, "raw_ms", id + " " + name);
      }
    }
    // Probes are the default indirect light: rt-indirect is not recorded; gi-probe-trace has no raw
    // twin yet.
    EXPECT_EQ(withRaw, (std::set<std::string>{"gbuffer-traced", "rt-shadows", "rt-ao", "rt-specular"})) << id;
    for (const char* k : {"gpu_ms", "cpu_ms", "wall_ms"}) expectSummary(c["frame"][k], id + " frame " + k);
    EXPECT_EQ(c["frame"]["gpu_samples_ms"].size(), 3u);
    expectFiniteNumber(c["frame"], "grays_per_s", id);
    for (const char* k : {"triangles", "spheres", "lights"}) expectFiniteNumber(c["scene_stats"], k, id);
    for (const char* k : {"blas_bytes", "tlas_bytes", "build_ms", "upload_ms"}) expectFiniteNumber(c["accel"], k, id);
    for (const char* k : {"used_bytes", "reserved_bytes", "image_bytes", "buffer_bytes", "accel_bytes", "host_bytes"})
      expectFiniteNumber(c["memory"], k, id);
    EXPECT_GT(c["memory"]["image_bytes"].get<uint64_t>(), 0u) << id;
    EXPECT_GT(c["memory"]["accel_bytes"].get<uint64_t>(), 0u) << id;
    const uint64_t sum = c["memory"]["image_bytes"].get<uint64_t>() + c["memory"]["buffer_bytes"].get<uint64_t>() +
                         c["memory"]["accel_bytes"].get<uint64_t>() + c["memory"]["host_bytes"].get<uint64_t>();
    EXPECT_EQ(sum, c["memory"]["used_bytes"].get<uint64_t>()) << id;
    // Frame resources (G-buffer, targets, histories) are their own figure, part of the images.
    for (const char* k : {"frame_bytes", "transient_bytes", "transient_unaliased_bytes", "history_bytes"})
      expectFiniteNumber(c["memory"], k, id);
    const json& m = c["memory"];
    EXPECT_GT(m["transient_bytes"].get<uint64_t>(), 0u) << id;
    EXPECT_GT(m["history_bytes"].get<uint64_t>(), 0u) << id;
    EXPECT_EQ(m["frame_bytes"].get<uint64_t>(),
              m["transient_bytes"].get<uint64_t>() + m["history_bytes"].get<uint64_t>())
        << id;
    EXPECT_LT(m["transient_bytes"].get<uint64_t>(), m["transient_unaliased_bytes"].get<uint64_t>())
        << id << ": aliasing must save memory in the hybrid frame";
    EXPECT_LE(m["frame_bytes"].get<uint64_t>(), m["image_bytes"].get<uint64_t>()) << id;
  }
  EXPECT_NE(j["configs"][0]["id"], j["configs"][1]["id"]);
}

TEST(BenchRun, CsvParses) {
  std::istringstream csv(readText(benchRun() / "a.csv"));
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  const size_t columns = size_t(std::count(line.begin(), line.end(), ',')) + 1;
  EXPECT_EQ(columns, 16u) << line;
  size_t rows = 0, frameRows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    EXPECT_EQ(size_t(std::count(line.begin(), line.end(), ',')) + 1, columns) << line;
    std::vector<std::string> f;
    std::stringstream ls(line);
    for (std::string cell; std::getline(ls, cell, ',');) f.push_back(cell);
    ASSERT_EQ(f.size(), columns) << line;
    if (f[10] == "frame") ++frameRows;
    for (size_t i = 11; i < 16; ++i) EXPECT_TRUE(std::isfinite(std::stod(f[i]))) << line;
  }
  EXPECT_EQ(frameRows, 2u);
  EXPECT_GT(rows, 2u * 3u);
}

TEST(BenchRun, SvgHasBarsAndSweepLine) {
  const std::string svg = readText(benchRun() / "a.svg");
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("<svg xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_NE(svg.find("class=\"bar\""), std::string::npos);
  EXPECT_NE(svg.find("class=\"sweep-line\""), std::string::npos);  // two sizes: a scaling line
  EXPECT_NE(svg.find("class=\"legend\""), std::string::npos);
  // XML-ish: every opened <g> closes, and no raw '&' outside entities.
  size_t open = 0, close = 0;
  for (size_t p = 0; (p = svg.find("<g ", p)) != std::string::npos; ++p) ++open;
  for (size_t p = 0; (p = svg.find("</g>", p)) != std::string::npos; ++p) ++close;
  EXPECT_EQ(open, close);
  for (size_t p = 0; (p = svg.find('&', p)) != std::string::npos; ++p)
    EXPECT_TRUE(svg.compare(p, 4, "&lt;") == 0 || svg.compare(p, 4, "&gt;") == 0 || svg.compare(p, 5, "&amp;") == 0 ||
                svg.compare(p, 6, "&quot;") == 0);
}

TEST(BenchRun, CompareFlagsOnlyTheDoctoredPass) {
  const auto a = benchRun() / "a.json";
  RunResult same = runRayster("bench --compare " + a.string() + " " + a.string() + " --fail-on-change");
  EXPECT_EQ(same.exitCode, 0) << same.output;
  EXPECT_EQ(same.output.find("CHANGED"), std::string::npos) << same.output;

  // Triple every sample of one pass in the first configuration: one that runs every frame (the
  // probes' warm-up passes run once, after the cut, and one sample is never significant).
  json j = json::parse(readText(a));
  json* every = nullptr;
  for (json& p : j["configs"][0]["passes"])
    if (!every && p["samples_ms"].size() == j["configs"][0]["frame"]["gpu_samples_ms"].size()) every = &p;
  ASSERT_NE(every, nullptr) << "no pass ran in every frame";
  json& pass = *every;
  const std::string name = pass["name"];
  // Every doctored sample above every measured one: lavapipe's timings of 3 frames can spread by 7x
  // (0.75, 5.6, 3.9 ms seen), and a plain 3x + 1 then overlapped and was not significant.
  double top = 0.0;
  for (const auto& v : pass["samples_ms"]) top = std::max(top, v.get<double>());
  for (auto& v : pass["samples_ms"]) v = v.get<double>() * 3.0 + 1.0 + 3.0 * top;
  const auto b = benchRun() / "doctored.json";
  std::ofstream(b) << j.dump();
  RunResult diff = runRayster("bench --compare " + a.string() + " " + b.string() + " --fail-on-change");
  EXPECT_EQ(diff.exitCode, 9) << diff.output;
  EXPECT_NE(diff.output.find(name), std::string::npos) << diff.output;
  EXPECT_EQ(std::count(diff.output.begin(), diff.output.end(), '\n') >= 2, true);
  size_t changed = 0;
  for (size_t p = 0; (p = diff.output.find("CHANGED", p)) != std::string::npos; ++p) ++changed;
  EXPECT_EQ(changed, 1u) << diff.output;  // the frame sum was not doctored
}

TEST(BenchStats, MannWhitneySeparatesShiftedSamples) {
  std::vector<double> a, b;
  for (int i = 0; i < 32; ++i) {
    a.push_back(1.0 + 0.01 * (i % 7));
    b.push_back(1.2 + 0.01 * (i % 5));
  }
  EXPECT_LT(app::mannWhitneyP(a, b), 1e-6);
  EXPECT_GT(app::mannWhitneyP(a, a), 0.5);
}

// The CI plan: JSON sweeps over size, light count (builtin:lights:N) and bounce depth.
TEST(Bench, SmokePlanRunsEverySweep) {
  const auto dir = testDir();
  RunResult r = runRayster("bench --plan " + std::string(RAYSTER_SOURCE_DIR) + "/bench/plans/ci-smoke.json --json " +
                           (dir / "smoke.json").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json j = json::parse(readText(dir / "smoke.json"));
  EXPECT_EQ(j["plan"], "ci-smoke");
  std::map<std::string, int> perSweep;
  for (const json& c : j["configs"]) {
    EXPECT_TRUE(c.value("ok", false)) << c.dump();
    ++perSweep[c.value("sweep", "")];
  }
  EXPECT_EQ(perSweep, (std::map<std::string, int>{{"resolution", 2}, {"lights", 2}, {"depth", 2}}));
  EXPECT_EQ(j["configs"][2]["scene_stats"]["lights"], 1);
  EXPECT_EQ(j["configs"][3]["scene_stats"]["lights"], 16);
  const std::string svg = readText(dir / "smoke.svg");
  for (const char* sweep : {"sweep-resolution", "sweep-lights", "sweep-depth"})
    EXPECT_NE(svg.find(sweep), std::string::npos);
}

TEST(Bench, BadArgumentsFailCleanly) {
  const std::string json = (testDir() / "x.json").string();
  EXPECT_EQ(runRayster("bench --size 12 --json " + json).exitCode, 2);
  EXPECT_EQ(runRayster("bench --max-depth 9 --json " + json).exitCode, 2);
  EXPECT_EQ(runRayster("bench --plan /nonexistent.json").exitCode, 3);
}

}  // namespace
}  // namespace rayster::test
