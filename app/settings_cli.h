#pragma once
// The render settings table (render/settings_table.h) on the command line: one option per setting
// a command takes, with the table's help, type and default; and the same settings as JSON.
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "render/settings_table.h"

namespace CLI {
class App;
}

namespace rayster::app {

// The values given on one command line, by setting name, as text.
using SettingValues = std::map<std::string, std::string>;

// Adds --NAME for every setting whose uses include `use`; given values land in `values`, checked
// by the table when parsed (a bad value is a parse error naming the option and what it takes).
// `defaults`: the command's settings before any option (what --help shows as the default).
void addSettingOptions(CLI::App* command, render::SettingUse use, SettingValues& values,
                       const render::RenderSettings& defaults = {});
// Applies the given values to `settings` (each already checked): presets (--effects) first, so the
// settings given explicitly override what a preset set.
Status applySettings(const SettingValues& values, render::RenderSettings& settings);
// Every setting of the table, as the JSON outputs record it: switches as booleans, numbers as
// numbers, choices as their names.
nlohmann::json settingsJson(const render::RenderSettings& settings);

}  // namespace rayster::app
