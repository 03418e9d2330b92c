// `rayster bench --shard I/N` and `--merge` (app/bench_shard.h, docs/farm.md): the shards of a plan
// run every N-th configuration, and their merge equals one process's run of the whole plan but for
// the timings; incomplete or mixed sets of shards are refused. On lavapipe, at a tiny size.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/bench_shard.h"
#include "app/farm_slurm.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json readJsonFile(const fs::path& p) {
  std::ifstream f(p);
  return json::parse(f);
}

// Everything but what a clock measured: keys ending in _ms, rates and the start date.
json withoutTimings(const json& j) {
  if (j.is_array()) {
    json out = json::array();
    for (const json& v : j) out.push_back(withoutTimings(v));
    return out;
  }
  if (!j.is_object()) return j;
  json out = json::object();
  for (const auto& [key, value] : j.items()) {
    if (key == "date" || key == "grays_per_s" || key == "raw_fraction" || key.ends_with("_ms")) continue;
    out[key] = withoutTimings(value);
  }
  return out;
}

// Three configurations: shard 1/2 runs the first and the third, shard 2/2 the second. Without
// probes and AO (what they cost is not what this checks).
constexpr const char* kPlan = R"({"name": "tiny", "warmup": 1, "frames": 2, "primaries": ["rt"],
  "sweeps": [{"name": "sizes", "scenes": ["builtin:cornell"], "sizes": ["32x24", "40x30", "48x36"],
              "settings": {"indirect": "off", "ao": "off"}}]})";

TEST(FarmBench, MergedShardsEqualOneProcessRunButForTimings) {
  const fs::path dir = testDir();
  std::ofstream(dir / "plan.json") << kPlan;
  const std::string plan = " --plan " + (dir / "plan.json").string();
  RunResult all = runRayster("bench" + plan + " --json " + (dir / "all.json").string());
  ASSERT_EQ(all.exitCode, 0) << all.output;
  for (int i = 1; i <= 2; ++i) {
    RunResult s = runRayster("bench" + plan + " --shard " + std::to_string(i) + "/2 --json " +
                             (dir / ("s" + std::to_string(i) + ".json")).string());
    ASSERT_EQ(s.exitCode, 0) << s.output;
  }
  const json whole = readJsonFile(dir / "all.json"), s1 = readJsonFile(dir / "s1.json"),
             s2 = readJsonFile(dir / "s2.json");
  ASSERT_EQ(whole["configs"].size(), 3u);
  ASSERT_EQ(s1["configs"].size(), 2u);
  ASSERT_EQ(s2["configs"].size(), 1u);
  EXPECT_EQ(s1["configs"][0]["id"], whole["configs"][0]["id"]);
  EXPECT_EQ(s1["configs"][1]["id"], whole["configs"][2]["id"]);
  EXPECT_EQ(s2["configs"][0]["id"], whole["configs"][1]["id"]);
  EXPECT_EQ(s2["shard"], (json{{"index", 2}, {"count", 2}, {"plan_configs", 3}}));

  // Given in any order.
  RunResult merge = runRayster("bench --merge " + (dir / "s2.json").string() + " " + (dir / "s1.json").string() +
                               " --json " + (dir / "merged.json").string());
  ASSERT_EQ(merge.exitCode, 0) << merge.output;
  const json merged = readJsonFile(dir / "merged.json");
  EXPECT_FALSE(merged.contains("shard"));
  EXPECT_EQ(withoutTimings(merged), withoutTimings(whole));
  EXPECT_TRUE(fs::exists(dir / "merged.csv") && fs::exists(dir / "merged.svg"));
  // The timings are there, only left out of the comparison.
  EXPECT_GT(merged["configs"][1]["frame"]["gpu_ms"].value("median", 0.0), 0.0);

  // Refused: a shard missing, one given twice, a file that is no shard's; bad --shard.
  const std::pair<std::string, int> refused[] = {
      {"bench --merge " + (dir / "s1.json").string(), 3},
      {"bench --merge " + (dir / "s1.json").string() + " " + (dir / "s1.json").string(), 3},
      {"bench --merge " + (dir / "s1.json").string() + " " + (dir / "all.json").string(), 3},
      {"bench --merge " + (dir / "nothing.json").string(), 3},
      {"bench" + plan + " --shard 0/2", 2},
      {"bench" + plan + " --shard 3/2", 2},
      {"bench" + plan + " --shard 1/x", 2},
      {"bench" + plan + " --shard 1/2 --merge " + (dir / "s1.json").string(), 2},
  };
  for (const auto& [args, code] : refused) {
    RunResult r = runRayster(args + " --json " + (dir / "refused.json").string());
    EXPECT_EQ(r.exitCode, code) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("rayster: error: "), std::string::npos) << args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(dir / "refused.json")) << args;
  }
}

TEST(FarmBench, ShardsSplitAPlanRoundRobinAndAMergeRefusesMixedSets) {
  app::BenchPlan plan;
  for (int k = 0; k < 7; ++k) {
    app::BenchConfig c;
    c.scene = "s" + std::to_string(k);
    plan.configs.push_back(c);
  }
  const app::BenchPlan third = app::shardOf(plan, {3, 3});
  ASSERT_EQ(third.configs.size(), 2u);  // positions 2 and 5
  EXPECT_EQ(third.configs[0].scene, "s2");
  EXPECT_EQ(third.configs[1].scene, "s5");
  EXPECT_TRUE(app::shardOf(plan, {3, 9}).configs.size() == 1 && app::shardOf(plan, {8, 9}).configs.empty());
  for (const char* bad : {"0/3", "4/3", "1/0", "-1/3", "1/-3", "1", "1/3/5", "1/3x", "a/b", ""})
    EXPECT_FALSE(app::parseShard(bad).ok()) << bad;
  ASSERT_TRUE(app::parseShard("2/3").ok());
  EXPECT_EQ(app::parseShard("2/3")->index, 2u);

  auto shard = [](uint32_t i, uint32_t n, size_t total, size_t configs, const char* commit) {
    json j = {{"plan", "p"}, {"commit", commit}, {"configs", json::array()}, {"shard", {{"index", i}, {"count", n}}}};
    j["shard"]["plan_configs"] = total;
    for (size_t k = 0; k < configs; ++k) j["configs"].push_back({{"id", fmt::format("{}-{}", i, k)}});
    return j;
  };
  auto ok = app::mergeShards({shard(2, 2, 3, 1, "c"), shard(1, 2, 3, 2, "c")}, {"b", "a"});
  ASSERT_TRUE(ok.ok()) << ok.error().message;
  EXPECT_EQ((*ok)["configs"], (json{{{"id", "1-0"}}, {{"id", "2-0"}}, {{"id", "1-1"}}}));
  EXPECT_FALSE(app::mergeShards({shard(1, 2, 3, 2, "c"), shard(2, 2, 3, 1, "d")}, {"a", "b"}).ok());  // commits
  EXPECT_FALSE(app::mergeShards({shard(1, 2, 3, 2, "c"), shard(2, 3, 3, 1, "c")}, {"a", "b"}).ok());  // counts
  EXPECT_FALSE(app::mergeShards({shard(1, 2, 3, 1, "c"), shard(2, 2, 3, 1, "c")}, {"a", "b"}).ok());  // a config lost
}

TEST(FarmBench, FarmSlurmWritesOneShardPerTask) {
  const fs::path dir = testDir();
  std::ofstream(dir / "plan.json") << kPlan;
  RunResult r = runRayster("farm slurm --bench-plan " + (dir / "plan.json").string() + " --shards 3 --json " +
                           (dir / "res" / "bench.json").string() + " --script -");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("#SBATCH --array=1-3\n"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("#SBATCH --gres=gpu:1\n"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("out='" + (dir / "res" / "bench").string() + "'.shard-$task-of-$shards.json"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("bench --plan '" + (dir / "plan.json").string() + "' --shard \"$task/$shards\""),
            std::string::npos)
      << r.output;
  EXPECT_EQ(app::benchShardPath("/r/bench.json", 2, 3), "/r/bench.shard-2-of-3.json");
}

}  // namespace
}  // namespace rayster::test
