#pragma once
// Every user-facing render setting, described once (docs/architecture.md, "Settings"): its name,
// kind, range or choices, default, help and whether changing it restarts accumulation. The table
// drives the command line of `render`, `view` and `bench` (app/settings_cli.cpp), the viewer's panel
// (app/viewer/ui.cpp) and the "settings" object of the JSON outputs; a new setting is one entry here.
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "render/renderer.h"

namespace rayster::render {

enum class SettingKind {
  Switch,   // on | off
  Choice,   // one of `choices`
  Integer,  // in [min, max]
  Real,     // in [min, max]
};

// Which commands take a setting.
enum SettingUse : uint32_t { kUseRender = 1u, kUseView = 2u, kUseBench = 4u, kUseAll = 7u };

struct Setting {
  std::string name;  // "ao": the option --ao, the JSON key, the panel's label
  SettingKind kind = SettingKind::Switch;
  std::string help;                  // for --help and the panel's tooltip
  std::vector<std::string> choices;  // Switch: {"on", "off"}; Choice: its names; Real: named values ("auto")
  double min = 0.0, max = 0.0;       // Integer and Real: the accepted range
  std::string group;                 // the panel's section: "Render" or "Effects"
  uint32_t uses = kUseAll;
  // Changing it restarts accumulation: the viewer starts a new run (histories, frame count).
  bool restarts = true;
  // A setting that may not be given together with this one (both fix the same thing).
  std::string excludes;
  // A preset sets several other settings (--effects): every command applies it before the settings
  // it sets, so an explicit option overrides it whatever its place on the command line.
  bool preset = false;
  // What --help shows as the type in place of the choices ("all|shadows|mirrors|none|LIST").
  std::string typeHint;
  // The value as text ("on", "quarter", "0.5"), and setting it from text (already range-checked or
  // not: set() checks and fails with a one-line cause).
  std::function<std::string(const RenderSettings&)> get;
  std::function<Status(RenderSettings&, std::string_view)> set;

  // The default (a default-constructed RenderSettings' value).
  std::string defaultText() const;
  // "on|off", "aces|neutral", "0..8", "-1..1": what --help shows as the option's type.
  std::string typeText() const;
};

// `--effects`: the effects of the hybrid frame by name, each one switch of the table ("gi" is
// --indirect), in the order a list of them is written.
inline constexpr const char* kEffectNames[] = {"shadows", "reflections", "ao", "gi", "denoise", "taa"};
// `--effects mirrors` traces the G-buffer surface and up to 4 mirror bounces: --max-depth 5.
inline constexpr uint32_t kMirrorsMaxDepth = 5;

const std::vector<Setting>& settingsTable();
const Setting* findSetting(std::string_view name);

// A setting a pass file declares for itself, so that a new technique's switch touches no central
// file: `const PassSetting kSetting{passSwitch("sky-visibility", "Effects", "help", false)};` at
// namespace scope in the pass file. Its value lives in RenderSettings::passSettings; the frame
// reads it with passSwitchOn(). The table lists it after the built-in entries (the command lines,
// the viewer's panel and the JSON take it like any other). Registered before main() runs.
struct PassSetting {
  explicit PassSetting(Setting setting);
};
Setting passSwitch(std::string name, std::string group, std::string help, bool defaultOn, uint32_t uses = kUseAll,
                   bool restarts = true);
Setting passChoice(std::string name, std::string group, std::string help, std::vector<std::string> choices,
                   std::string defaultChoice, uint32_t uses = kUseAll, bool restarts = true);
// The value of a pass file's switch (its default when never set).
bool passSwitchOn(const RenderSettings& settings, std::string_view name);
// The value of any pass file's setting, as text (its default when never set).
std::string passSettingText(const RenderSettings& settings, std::string_view name);

}  // namespace rayster::render
