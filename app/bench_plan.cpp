#include "app/bench_plan.h"

#include "render/settings_table.h"

#include <cstdio>
#include <fstream>

#include <fmt/format.h>

namespace rayster::app {

bool parseSizeText(const std::string& text, uint32_t& w, uint32_t& h) {
  unsigned a = 0, b = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%u%c%u%c", &a, &x, &b, &extra) != 3 || (x != 'x' && x != 'X')) return false;
  if (a == 0 || b == 0 || a > 16384 || b > 16384) return false;
  w = a;
  h = b;
  return true;
}

std::string BenchConfig::id() const {
  std::string s = scene.rfind("builtin:", 0) == 0 ? scene.substr(8) : scene;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-') c = '_';
  std::string extra;
  for (const auto& [name, value] : settings) extra += "/" + name + "=" + value;
  return fmt::format("{}/{}x{}/{}/{}/d{}/l{}{}{}", s, width, height, mode, primary, maxDepth, shadowLights,
                     culling ? "" : "/nocull", extra);
}

nlohmann::json BenchConfig::toJson() const {
  return {{"sweep", sweep},      {"axis", axis},          {"scene", scene},
          {"width", width},      {"height", height},      {"mode", mode},
          {"primary", primary},  {"max_depth", maxDepth}, {"shadow_lights", shadowLights},
          {"warmup", warmup},    {"frames", frames},      {"seed", seed},
          {"raw_rays", rawRays}, {"culling", culling},    {"settings", settings}};
}

Result<BenchConfig> BenchConfig::fromJson(const nlohmann::json& j) {
  try {
    BenchConfig c;
    c.sweep = j.at("sweep").get<std::string>();
    c.axis = j.at("axis").get<std::string>();
    c.scene = j.at("scene").get<std::string>();
    c.width = j.at("width").get<uint32_t>();
    c.height = j.at("height").get<uint32_t>();
    c.mode = j.at("mode").get<std::string>();
    c.primary = j.at("primary").get<std::string>();
    c.maxDepth = j.at("max_depth").get<uint32_t>();
    c.shadowLights = j.at("shadow_lights").get<uint32_t>();
    c.warmup = j.at("warmup").get<uint32_t>();
    c.frames = j.at("frames").get<uint32_t>();
    c.seed = j.at("seed").get<uint32_t>();
    c.rawRays = j.value("raw_rays", false);
    c.culling = j.value("culling", true);
    if (j.contains("settings")) c.settings = j.at("settings").get<std::map<std::string, std::string>>();
    return c;
  } catch (const std::exception& e) {
    return makeError(ExitCode::BadArguments, "bench configuration: {}", e.what());
  }
}

namespace {

Status checkAxes(const BenchAxes& a) {
  uint32_t w = 0, h = 0;
  for (const auto& s : a.sizes)
    if (!parseSizeText(s, w, h)) return makeError(ExitCode::BadArguments, "bench: size '{}' is not WxH", s);
  for (const auto& m : a.modes)
    if (m != "hybrid" && m != "pathtrace" && m != "raster")
      return makeError(ExitCode::BadArguments, "bench: unknown mode '{}'", m);
  for (const auto& p : a.primaries)
    if (p != "raster" && p != "rt" && p != "auto")
      return makeError(ExitCode::BadArguments, "bench: unknown primary '{}'", p);
  for (uint32_t d : a.maxDepths)
    if (d < 1 || d > 8) return makeError(ExitCode::BadArguments, "bench: max depth {} is outside 1..8", d);
  if (a.scenes.empty() || a.sizes.empty() || a.modes.empty() || a.primaries.empty())
    return makeError(ExitCode::BadArguments, "bench: an axis has no values");
  if (a.frames == 0) return makeError(ExitCode::BadArguments, "bench: --frames must be at least 1");
  if (a.shadowLights > 8) return makeError(ExitCode::BadArguments, "bench: shadow lights must be 0..8");
  return okStatus();
}

// The depths a sweep runs: the axis given, else the bench's default or what a preset of the
// sweep's settings sets (--effects mirrors: its 4 bounces), an explicit --max-depth winning as for render.
std::vector<uint32_t> sweepDepths(const BenchAxes& a) {
  if (!a.maxDepths.empty()) return a.maxDepths;
  render::RenderSettings s;
  s.maxDepth = kBenchMaxDepth;
  for (const auto& [name, value] : a.settings)
    if (const render::Setting* setting = render::findSetting(name); setting && setting->preset)
      (void)setting->set(s, value);  // checked by checkSettings
  return {s.maxDepth};
}

void appendSweep(BenchPlan& plan, const std::string& name, const BenchAxes& a) {
  const std::vector<uint32_t> depths = sweepDepths(a);
  const std::string axis = a.sizes.size() > 1       ? "size"
                           : depths.size() > 1      ? "max_depth"
                           : a.scenes.size() > 1    ? "scene"
                           : a.primaries.size() > 1 ? "primary"
                                                    : "mode";
  for (const auto& scene : a.scenes)
    for (const auto& size : a.sizes)
      for (const auto& mode : a.modes)
        for (const auto& primary : a.primaries)
          for (uint32_t depth : depths) {
            BenchConfig c;
            c.sweep = name;
            c.axis = axis;
            c.scene = scene;
            parseSizeText(size, c.width, c.height);
            c.mode = mode;
            c.primary = primary;
            c.maxDepth = depth;
            c.shadowLights = a.shadowLights;
            c.warmup = a.warmup;
            c.frames = a.frames;
            c.seed = a.seed;
            c.rawRays = a.rawRays;
            c.culling = a.culling;
            c.settings = a.settings;
            plan.configs.push_back(c);
          }
}

template <typename T>
void readList(const nlohmann::json& j, const char* key, std::vector<T>& out) {
  if (!j.contains(key)) return;
  out.clear();
  if (j[key].is_array())
    for (const auto& v : j[key]) out.push_back(v.get<T>());
  else
    out.push_back(j[key].get<T>());
}

}  // namespace

// Settings-table values a plan or the command line gives: known to the table, for bench, and valid.
Status checkSettings(const std::map<std::string, std::string>& settings) {
  for (const auto& [name, value] : settings) {
    const render::Setting* s = render::findSetting(name);
    if (!s || (s->uses & render::kUseBench) == 0)
      return makeError(ExitCode::BadArguments, "\"{}\" is not a bench setting", name);
    render::RenderSettings scratch;
    if (Status ok = s->set(scratch, value); !ok) return ok;
  }
  return okStatus();
}

Result<BenchPlan> planFromAxes(const BenchAxes& axes) {
  if (auto s = checkAxes(axes); !s) return s.error();
  if (auto s = checkSettings(axes.settings); !s) return s.error();
  BenchPlan plan;
  appendSweep(plan, "cli", axes);
  return plan;
}

Result<BenchPlan> loadPlan(const std::string& path) {
  std::ifstream f(path);
  if (!f) return makeError(ExitCode::BadInput, "cannot read plan '{}'", path);
  BenchPlan plan;
  try {
    const nlohmann::json j = nlohmann::json::parse(f);
    plan.name = j.value("name", "plan");
    BenchAxes defaults;
    defaults.warmup = j.value("warmup", defaults.warmup);
    defaults.frames = j.value("frames", defaults.frames);
    defaults.seed = j.value("seed", defaults.seed);
    defaults.shadowLights = j.value("shadow_lights", defaults.shadowLights);
    defaults.rawRays = j.value("raw_rays", defaults.rawRays);
    readList(j, "sizes", defaults.sizes);
    readList(j, "primaries", defaults.primaries);
    if (!j.contains("sweeps") || !j["sweeps"].is_array() || j["sweeps"].empty())
      return makeError(ExitCode::BadInput, "plan '{}': needs a non-empty \"sweeps\" array", path);
    for (const auto& s : j["sweeps"]) {
      BenchAxes a = defaults;
      readList(s, "scenes", a.scenes);
      readList(s, "sizes", a.sizes);
      readList(s, "modes", a.modes);
      readList(s, "primaries", a.primaries);
      readList(s, "max_depth", a.maxDepths);
      a.shadowLights = s.value("shadow_lights", a.shadowLights);
      a.warmup = s.value("warmup", a.warmup);
      a.frames = s.value("frames", a.frames);
      a.rawRays = s.value("raw_rays", a.rawRays);
      a.culling = s.value("culling", a.culling);
      // "settings": {"ao": "off", ...}: the settings table's names and values, as on the command line.
      if (s.contains("settings"))
        for (const auto& [name, value] : s["settings"].items()) a.settings[name] = value.get<std::string>();
      if (auto st = checkAxes(a); !st) return makeError(ExitCode::BadInput, "plan '{}': {}", path, st.error().message);
      if (auto st = checkSettings(a.settings); !st)
        return makeError(ExitCode::BadInput, "plan '{}': {}", path, st.error().message);
      const size_t before = plan.configs.size();
      appendSweep(plan, s.value("name", fmt::format("sweep{}", before)), a);
      // A sweep may name its x axis ("triangles", "lights") when the scenes carry it.
      if (s.contains("axis"))
        for (size_t i = before; i < plan.configs.size(); ++i) plan.configs[i].axis = s["axis"].get<std::string>();
    }
  } catch (const std::exception& e) {
    return makeError(ExitCode::BadInput, "plan '{}': {}", path, e.what());
  }
  return plan;
}

}  // namespace rayster::app
