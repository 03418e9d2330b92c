#include "app/settings_cli.h"

#include <algorithm>

#include <CLI/CLI.hpp>

namespace rayster::app {

void addSettingOptions(CLI::App* command, render::SettingUse use, SettingValues& values,
                       const render::RenderSettings& defaults) {
  for (const render::Setting& s : render::settingsTable()) {
    if ((s.uses & use) == 0) continue;
    const std::string name = s.name;
    command
        ->add_option_function<std::string>(
            "--" + name, [&values, name](const std::string& v) { values[name] = v; },
            s.help + " (default " + s.get(defaults) + ")")
        ->type_name(s.typeText())
        ->check(CLI::Validator(
            [&s](std::string& v) -> std::string {
              render::RenderSettings scratch;
              const Status ok = s.set(scratch, v);
              if (ok) return std::string();
              const std::string prefix = "--" + s.name + ": ";  // CLI11 names the option itself
              const std::string& m = ok.error().message;
              return m.rfind(prefix, 0) == 0 ? m.substr(prefix.size()) : m;
            },
            ""));
  }
}

Status applySettings(const SettingValues& values, render::RenderSettings& settings) {
  // Presets first (--effects), then every other setting: an explicit option overrides a preset.
  for (const bool presets : {true, false}) {
    for (const auto& [name, value] : values) {
      const render::Setting* s = render::findSetting(name);
      if (!s) return makeError(ExitCode::BadArguments, "unknown setting '{}'", name);
      if (s->preset != presets) continue;
      if (!s->excludes.empty() && values.count(s->excludes))
        return makeError(ExitCode::BadArguments, "--{} and --{} cannot be given together", s->name, s->excludes);
      if (Status ok = s->set(settings, value); !ok) return ok;
    }
  }
  return okStatus();
}

nlohmann::json settingsJson(const render::RenderSettings& settings) {
  nlohmann::json j = nlohmann::json::object();
  for (const render::Setting& s : render::settingsTable()) {
    const std::string v = s.get(settings);
    switch (s.kind) {
      case render::SettingKind::Switch:
        j[s.name] = v == "on";
        break;
      case render::SettingKind::Integer:
        j[s.name] = std::stoll(v);
        break;
      case render::SettingKind::Real:  // a number, or one of its named values ("auto")
        if (std::find(s.choices.begin(), s.choices.end(), v) != s.choices.end())
          j[s.name] = v;
        else
          j[s.name] = std::stod(v);
        break;
      case render::SettingKind::Choice:
        j[s.name] = v;
        break;
    }
  }
  return j;
}

}  // namespace rayster::app
