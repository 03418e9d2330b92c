#pragma once
// `rayster bench` plans: sweeps of configurations (scene × size × mode × primary × bounce depth),
// from the command line or a JSON plan (bench/plans/*.json). One configuration runs per process.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"

namespace rayster::app {

struct BenchConfig {
  std::string sweep;  // the sweep it belongs to (plots group by it)
  std::string axis;   // the sweep's x axis: size, triangles, lights, max_depth, scene
  std::string scene;
  uint32_t width = 1920, height = 1080;
  std::string mode = "hybrid", primary = "auto";
  uint32_t maxDepth = 7;
  uint32_t shadowLights = 8;
  uint32_t warmup = 16, frames = 64;  // frames measured after the warm-up
  uint32_t seed = 1;
  bool rawRays = false;  // also time the raw-rate twins of the primary and shadow rays
  bool culling = true;   // GPU culling of the raster G-buffer's draws (ids of "off" end in /nocull)
  // Settings-table values (render/settings_table.h) by name, e.g. {"ao": "off"}: applied after the
  // fields above; ids list them ("/ao=off").
  std::map<std::string, std::string> settings;
  std::string id() const;  // unique within a plan, stable across runs (compare matches by it)
  nlohmann::json toJson() const;
  static Result<BenchConfig> fromJson(const nlohmann::json& j);
};

struct BenchPlan {
  std::string name = "cli";
  std::vector<BenchConfig> configs;
};

// The bench's specular depth when neither --max-depth nor a preset gives one.
inline constexpr uint32_t kBenchMaxDepth = 7;

// Axes given on the command line; every list but maxDepths holds at least one value.
struct BenchAxes {
  std::vector<std::string> scenes{"builtin:whitted"};
  std::vector<std::string> sizes{"1920x1080"};
  std::vector<std::string> modes{"hybrid"};
  std::vector<std::string> primaries{"auto"};
  // Empty: kBenchMaxDepth, or what a preset of `settings` sets (--effects mirrors: 5).
  std::vector<uint32_t> maxDepths;
  uint32_t shadowLights = 8, warmup = 16, frames = 64, seed = 1;
  bool rawRays = false;
  bool culling = true;
  std::map<std::string, std::string> settings;  // --ao off, ...: the settings table's bench options
};

bool parseSizeText(const std::string& text, uint32_t& w, uint32_t& h);
// The cross product of the axes, as one sweep whose x axis is the first axis with several values.
Result<BenchPlan> planFromAxes(const BenchAxes& axes);
// A JSON plan: {"name", "warmup", "frames", "seed", "sweeps": [{"name", "scenes", "sizes", "modes",
// "primaries", "max_depth", "shadow_lights", "warmup", "frames", "raw_rays", "culling", "axis"}]} (sweep fields default
// to the top).
Result<BenchPlan> loadPlan(const std::string& path);

}  // namespace rayster::app
