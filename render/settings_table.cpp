#include "render/settings_table.h"

#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "render/tonemap_curves.h"

namespace rayster::render {
namespace {

std::string realText(double v) {
  std::string t = fmt::format("{:.4f}", v);
  while (t.back() == '0') t.pop_back();
  if (t.back() == '.') t.pop_back();
  return t;
}

Status parseNumber(const Setting& s, std::string_view text, double& out) {
  const std::string t(text);
  char* end = nullptr;
  out = std::strtod(t.c_str(), &end);
  if (t.empty() || *end != '\0' || !std::isfinite(out))
    return makeError(ExitCode::BadArguments, "--{}: '{}' is not a number", s.name, t);
  if (s.kind == SettingKind::Integer && out != std::floor(out))
    return makeError(ExitCode::BadArguments, "--{}: '{}' is not a whole number", s.name, t);
  if (out < s.min || out > s.max)
    return makeError(ExitCode::BadArguments, "--{}: {} is outside {}", s.name, t, s.typeText());
  return okStatus();
}

Status checkChoice(const Setting& s, std::string_view text) {
  for (const std::string& c : s.choices)
    if (c == text) return okStatus();
  return makeError(ExitCode::BadArguments, "--{}: '{}' is not one of {}", s.name, std::string(text), s.typeText());
}

// Entries by kind: each binds a RenderSettings member.
Setting onOff(std::string name, std::string group, std::string help, bool RenderSettings::*field,
              uint32_t uses = kUseAll, bool restarts = true) {
  Setting s{std::move(name), SettingKind::Switch, std::move(help), {"on", "off"}, 0, 0, std::move(group), uses,
            restarts};
  s.get = [field](const RenderSettings& r) { return std::string(r.*field ? "on" : "off"); };
  s.set = [field, s](RenderSettings& r, std::string_view t) -> Status {
    if (Status c = checkChoice(s, t); !c) return c;
    r.*field = t == "on";
    return okStatus();
  };
  return s;
}

template <class T>
Setting number(std::string name, SettingKind kind, std::string group, std::string help, T RenderSettings::*field,
               double min, double max, uint32_t uses = kUseAll, bool restarts = true) {
  Setting s{std::move(name), kind, std::move(help), {}, min, max, std::move(group), uses, restarts};
  s.get = [field, kind](const RenderSettings& r) {
    return kind == SettingKind::Integer ? std::to_string(r.*field) : realText(double(r.*field));
  };
  s.set = [field, s](RenderSettings& r, std::string_view t) -> Status {
    double v = 0;
    if (Status n = parseNumber(s, t, v); !n) return n;
    r.*field = T(v);
    return okStatus();
  };
  return s;
}

// A choice between enumerators, by the names `names` gives them (in the enum's order).
template <class E>
Setting choice(std::string name, std::string group, std::string help, E RenderSettings::*field,
               std::vector<std::string> names, uint32_t uses = kUseAll, bool restarts = true) {
  Setting s{std::move(name), SettingKind::Choice, std::move(help), names, 0, 0, std::move(group), uses, restarts};
  s.get = [field, names](const RenderSettings& r) { return names[size_t(r.*field)]; };
  s.set = [field, s, names](RenderSettings& r, std::string_view t) -> Status {
    if (Status c = checkChoice(s, t); !c) return c;
    for (size_t i = 0; i < names.size(); ++i)
      if (names[i] == t) r.*field = E(i);
    return okStatus();
  };
  return s;
}

// --effects: a preset or a list of kEffectNames, each name one switch of this table.
template <class R>  // RenderSettings or const RenderSettings
auto effectField(R& r, std::string_view name) -> decltype(&r.shadows) {
  if (name == "shadows") return &r.shadows;
  if (name == "reflections") return &r.reflections;
  if (name == "ao") return &r.ao;
  if (name == "gi") return &r.indirect;
  if (name == "denoise") return &r.denoise;
  if (name == "taa") return &r.taa;
  return nullptr;
}

Setting effectsPreset() {
  Setting s{"effects",
            SettingKind::Choice,
            "The frame's effects: all (every effect, the default), shadows (primary visibility and one "
            "shadow ray per pixel and light, lighting and tonemap only), mirrors (reflections and refractions "
            "without shadows, --max-depth 5: up to 4 mirror bounces), none, or a comma-separated LIST of shadows, "
            "reflections, ao, gi, denoise, taa turning on exactly those; options given explicitly (--taa on) "
            "override it",
            {"all", "shadows", "mirrors", "none"},
            0,
            0,
            "Effects",
            kUseAll,
            true};
  s.preset = true;
  s.typeHint = "all|shadows|mirrors|none|LIST";
  s.get = [](const RenderSettings& r) {
    std::string list;
    size_t on = 0;
    for (const char* name : kEffectNames)
      if (*effectField(r, name)) {
        list += (list.empty() ? "" : ",") + std::string(name);
        ++on;
      }
    if (on == std::size(kEffectNames)) return std::string("all");
    if (on == 0) return std::string("none");
    if (list == "reflections" && r.maxDepth == kMirrorsMaxDepth) return std::string("mirrors");
    return list;
  };
  s.set = [](RenderSettings& r, std::string_view text) -> Status {
    std::vector<std::string> names;
    if (text == "all") {
      names.assign(std::begin(kEffectNames), std::end(kEffectNames));
    } else if (text == "mirrors") {
      names = {"reflections"};
    } else if (text != "none") {
      size_t start = 0;
      while (start <= text.size()) {
        const size_t comma = std::min(text.find(',', start), text.size());
        const std::string name(text.substr(start, comma - start));
        if (!effectField(r, name))
          return makeError(ExitCode::BadArguments,
                           "--effects: '{}' is no effect (all, shadows, mirrors, none, or a list of shadows, "
                           "reflections, ao, gi, denoise, taa)",
                           name);
        names.push_back(name);
        start = comma + 1;
      }
    }
    for (const char* name : kEffectNames) *effectField(r, name) = false;
    for (const std::string& name : names) *effectField(r, name) = true;
    if (text == "mirrors") r.maxDepth = kMirrorsMaxDepth;
    return okStatus();
  };
  return s;
}

std::vector<Setting> makeTable() {
  std::vector<Setting> t;
  const uint32_t renderView = kUseRender | kUseView;  // bench sweeps these as axes of its own
  t.push_back(choice("mode", "Render",
                     "hybrid (raster/traced G-buffer + ray-traced effects), pathtrace (the reference) or raster "
                     "(no ray tracing)",
                     &RenderSettings::mode, {"hybrid", "pathtrace", "raster"}, renderView));
  t.push_back(choice("primary", "Render", "G-buffer producer: raster, rt (traced primary rays) or auto (the faster)",
                     &RenderSettings::primary, {"raster", "rt", "auto"}, renderView));
  {
    // A Real with a named value: "auto" (the default), or a fixed multiplier 2^EV.
    Setting s{"exposure",
              SettingKind::Real,
              "auto (metered from each frame's luminance histogram, adapted over time) or a fixed exposure in EV "
              "stops: light x 2^EV",
              {"auto"},
              -40.0,
              40.0,
              "Render",
              kUseAll,
              true};
    s.get = [](const RenderSettings& r) {
      return r.exposureMode == ExposureMode::Ev ? realText(r.exposureEv) : std::string("auto");
    };
    s.set = [s](RenderSettings& r, std::string_view text) -> Status {
      if (text == "auto") {
        if (r.exposureMode == ExposureMode::Ev) r.exposureMode = ExposureMode::Auto;
        return okStatus();
      }
      double v = 0;
      if (Status n = parseNumber(s, text, v); !n) return n;
      r.exposureMode = ExposureMode::Ev;
      r.exposureEv = float(v);
      return okStatus();
    };
    t.push_back(std::move(s));
  }
  {
    Setting s{"ev100",
              SettingKind::Real,
              "A fixed photographic exposure: EV at ISO 100 (a camera's EV100: 15 for a sunny day, 7 indoors), "
              "light x 1/(1.2 x 2^EV100); off: --exposure decides",
              {"off"},
              -20.0,
              40.0,
              "Render",
              kUseAll,
              true};
    s.excludes = "exposure";
    s.get = [](const RenderSettings& r) {
      return r.exposureMode == ExposureMode::Ev100 ? realText(r.ev100) : std::string("off");
    };
    s.set = [s](RenderSettings& r, std::string_view text) -> Status {
      if (text == "off") {
        if (r.exposureMode == ExposureMode::Ev100) r.exposureMode = ExposureMode::Auto;
        return okStatus();
      }
      double v = 0;
      if (Status n = parseNumber(s, text, v); !n) return n;
      r.exposureMode = ExposureMode::Ev100;
      r.ev100 = float(v);
      return okStatus();
    };
    t.push_back(std::move(s));
  }
  t.push_back(number("exposure-compensation", SettingKind::Real, "Render",
                     "EV stops added to the automatic exposure (positive: brighter)",
                     &RenderSettings::exposureCompensation, -20.0, 20.0, kUseAll, /*restarts*/ false));
  t.push_back(choice("tonemap", "Render", "Tonemap operator: aces (fitted ACES) or neutral (Khronos PBR Neutral)",
                     &RenderSettings::tonemap, {"aces", "neutral"}, kUseAll, /*restarts*/ false));
  t.push_back(onOff("taa", "Render",
                    "Temporal anti-aliasing with sub-pixel jitter; a static view converges to a supersampled image",
                    &RenderSettings::taa));
  t.push_back(onOff("culling", "Render", "GPU frustum culling of the raster G-buffer's draws (indirect draws)",
                    &RenderSettings::culling));
  t.push_back(effectsPreset());
  t.push_back(onOff("shadows", "Effects",
                    "Shadows: ray-traced shadow rays at the G-buffer surface and at reflection, refraction and "
                    "indirect hits (raster: shadow maps); off: every light reaches what faces it, no shadow ray",
                    &RenderSettings::shadows));
  t.push_back(onOff("reflections", "Effects",
                    "Ray-traced reflections and refractions (rt-specular); off: mirrors, glossy surfaces and glass "
                    "take the environment approximation",
                    &RenderSettings::reflections));
  t.push_back(number("max-depth", SettingKind::Integer, "Effects",
                     "Surface interactions along a path after the camera ray: the path tracer's vertices, and the "
                     "G-buffer surface plus up to N-1 (at most 8) reflection/refraction rays in hybrid mode",
                     &RenderSettings::maxDepth, 1, 64, renderView));
  t.push_back(number("shadow-lights", SettingKind::Integer, "Effects",
                     "Lights with their own shadow layer; a scene with more lights picks one light per pixel by "
                     "importance instead",
                     &RenderSettings::shadowLights, 0, 8, renderView));
  t.push_back(
      onOff("ao", "Effects", "Ray-traced ambient occlusion of ambient and environment light", &RenderSettings::ao));
  {
    // 0 (the default) means the scene-relative radius; RenderSettings keeps that as a negative value.
    Setting s{"ao-radius",
              SettingKind::Real,
              "AO ray length in scene units; 0: 0.1 x the scene's bounding-box diagonal",
              {},
              0.0,
              1e9,
              "Effects",
              kUseAll,
              true};
    s.get = [](const RenderSettings& r) { return r.aoRadius > 0.0f ? realText(r.aoRadius) : std::string("0"); };
    s.set = [s](RenderSettings& r, std::string_view text) -> Status {
      double v = 0;
      if (Status n = parseNumber(s, text, v); !n) return n;
      r.aoRadius = v > 0.0 ? float(v) : -1.0f;
      return okStatus();
    };
    t.push_back(std::move(s));
  }
  t.push_back(onOff("indirect", "Effects",
                    "Ray-traced diffuse indirect light, as --gi computes it (off: ambient and the environment's SH "
                    "irradiance instead)",
                    &RenderSettings::indirect));
  t.push_back(choice("indirect-rate", "Effects",
                     "Pixels the indirect diffuse traces per frame: quarter (one of each 2x2 block, rotating over 4 "
                     "frames, the rest filled from traced neighbours of similar depth and normal) or full",
                     &RenderSettings::indirectRate, {"full", "quarter"}));
  t.push_back(number("glossy-threshold", SettingKind::Real, "Effects",
                     "Trace glossy reflections (one GGX VNDF sample per pixel) up to this roughness; rougher surfaces "
                     "fade to the environment approximation over 0.1 more",
                     &RenderSettings::glossyThreshold, 0.0, 1.0));
  t.push_back(number("mirror-roughness", SettingKind::Real, "Effects",
                     "Surfaces at most this rough reflect as perfect mirrors (negative: none, every opaque reflection "
                     "is VNDF-sampled)",
                     &RenderSettings::mirrorRoughness, -1.0, 1.0));
  t.push_back(onOff("denoise", "Effects",
                    "The hybrid's denoisers of shadows, AO, reflections and indirect light; off: lighting takes the "
                    "raw one-sample signals",
                    &RenderSettings::denoise));
  return t;
}

}  // namespace

std::string Setting::defaultText() const { return get(RenderSettings{}); }

std::string Setting::typeText() const {
  if (!typeHint.empty()) return typeHint;
  switch (kind) {
    case SettingKind::Switch:
    case SettingKind::Choice: {
      std::string t;
      for (const std::string& c : choices) t += (t.empty() ? "" : "|") + c;
      return t;
    }
    case SettingKind::Integer:
      return fmt::format("{}..{}", int64_t(min), int64_t(max));
    case SettingKind::Real: {
      std::string t;
      for (const std::string& c : choices) t += c + "|";  // named values ("auto")
      return t + realText(min) + ".." + (max >= 1e9 ? std::string("") : realText(max));
    }
  }
  return "";
}

namespace {
std::vector<Setting>& passSettings() {
  static std::vector<Setting> settings;  // filled by PassSetting objects during static initialisation
  return settings;
}
}  // namespace

PassSetting::PassSetting(Setting setting) { passSettings().push_back(std::move(setting)); }

Setting passSwitch(std::string name, std::string group, std::string help, bool defaultOn, uint32_t uses,
                   bool restarts) {
  Setting s{name, SettingKind::Switch, std::move(help), {"on", "off"}, 0, 0, std::move(group), uses, restarts};
  const std::string fallback = defaultOn ? "on" : "off";
  s.get = [name, fallback](const RenderSettings& r) {
    auto it = r.passSettings.find(name);
    return it == r.passSettings.end() ? fallback : it->second;
  };
  s.set = [name, s](RenderSettings& r, std::string_view t) -> Status {
    if (Status c = checkChoice(s, t); !c) return c;
    r.passSettings[name] = std::string(t);
    return okStatus();
  };
  return s;
}

Setting passChoice(std::string name, std::string group, std::string help, std::vector<std::string> choices,
                   std::string defaultChoice, uint32_t uses, bool restarts) {
  Setting s{name, SettingKind::Choice, std::move(help), std::move(choices), 0, 0, std::move(group), uses, restarts};
  s.get = [name, defaultChoice](const RenderSettings& r) {
    auto it = r.passSettings.find(name);
    return it == r.passSettings.end() ? defaultChoice : it->second;
  };
  s.set = [name, s](RenderSettings& r, std::string_view t) -> Status {
    if (Status c = checkChoice(s, t); !c) return c;
    r.passSettings[name] = std::string(t);
    return okStatus();
  };
  return s;
}

std::string passSettingText(const RenderSettings& settings, std::string_view name) {
  const Setting* s = findSetting(name);
  RAYSTER_ASSERT(s, "passSettingText() of a name that is no registered setting");
  return s->get(settings);
}

bool passSwitchOn(const RenderSettings& settings, std::string_view name) {
  const Setting* s = findSetting(name);
  RAYSTER_ASSERT(s && s->kind == SettingKind::Switch, "passSwitchOn() of a name that is no registered switch");
  return s->get(settings) == "on";
}

const std::vector<Setting>& settingsTable() {
  static const std::vector<Setting> table = [] {
    std::vector<Setting> t = makeTable();
    for (const Setting& s : passSettings()) {
      for (const Setting& existing : t)
        RAYSTER_ASSERT(existing.name != s.name, "a pass file declares a setting the table already has");
      t.push_back(s);
    }
    return t;
  }();
  return table;
}

const Setting* findSetting(std::string_view name) {
  for (const Setting& s : settingsTable())
    if (s.name == name) return &s;
  return nullptr;
}

}  // namespace rayster::render
