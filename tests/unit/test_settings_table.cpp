// The settings table (render/settings_table.h): every entry round-trips its values and refuses
// what its range or choices exclude, and the table is what `render`, `view` and `bench` take on
// the command line and what `render --json` records.
#include <fstream>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/settings_cli.h"
#include "render/settings_table.h"
#include "tests/render/run_rayster.h"

namespace rayster::render {
namespace {

TEST(SettingsTable, EveryEntryRoundTripsItsValuesAndRefusesOthers) {
  std::set<std::string> names;
  for (const Setting& s : settingsTable()) {
    EXPECT_TRUE(names.insert(s.name).second) << "two entries named " << s.name;
    EXPECT_FALSE(s.help.empty()) << s.name;
    EXPECT_TRUE(s.group == "Render" || s.group == "Effects") << s.name;
    ASSERT_TRUE(s.get && s.set) << s.name;
    RenderSettings r;
    EXPECT_TRUE(s.set(r, s.defaultText()).ok()) << s.name;
    EXPECT_EQ(s.get(r), s.defaultText()) << s.name;
    EXPECT_FALSE(s.set(r, "").ok()) << s.name;
    EXPECT_FALSE(s.set(r, "nonsense").ok()) << s.name;
    switch (s.kind) {
      case SettingKind::Switch:
      case SettingKind::Choice:
        for (const std::string& c : s.choices) {
          ASSERT_TRUE(s.set(r, c).ok()) << s.name << " " << c;
          EXPECT_EQ(s.get(r), c) << s.name;
        }
        break;
      case SettingKind::Integer:
      case SettingKind::Real: {
        for (double v : {s.min, s.max}) {
          if (v >= 1e9) continue;
          ASSERT_TRUE(s.set(r, std::to_string(v)).ok()) << s.name << " " << v;
          EXPECT_NEAR(std::stod(s.get(r)), v, 1e-4) << s.name;
        }
        const Status below = s.set(r, std::to_string(s.min - 1.0));
        EXPECT_FALSE(below.ok()) << s.name;
        if (!below.ok()) {
          EXPECT_NE(below.error().message.find("--" + s.name), std::string::npos) << below.error().message;
        }
        if (s.kind == SettingKind::Integer) {
          EXPECT_FALSE(s.set(r, std::to_string(s.min) + ".5").ok()) << s.name;
        }
        break;
      }
    }
  }
  // The table binds the fields it names.
  RenderSettings r;
  ASSERT_TRUE(findSetting("ao")->set(r, "off").ok());
  EXPECT_FALSE(r.ao);
  ASSERT_TRUE(findSetting("indirect")->set(r, "off").ok());
  EXPECT_FALSE(r.indirect);
  ASSERT_TRUE(findSetting("indirect")->set(r, "on").ok());
  EXPECT_TRUE(r.indirect);
  EXPECT_FALSE(findSetting("indirect")->set(r, "auto").ok()) << "auto (on for two built-in scenes) is gone";
  ASSERT_TRUE(findSetting("tonemap")->set(r, "neutral").ok());
  EXPECT_EQ(r.tonemap, Tonemapper::Neutral);
  ASSERT_TRUE(findSetting("shadow-lights")->set(r, "3").ok());
  EXPECT_EQ(r.shadowLights, 3u);
  EXPECT_EQ(findSetting("no-such-setting"), nullptr);
  EXPECT_FALSE(findSetting("tonemap")->restarts) << "tonemapping keeps the accumulated frames";
  EXPECT_TRUE(findSetting("ao")->restarts);
}

TEST(SettingsTable, JsonHasEveryEntryWithItsType) {
  RenderSettings r;
  r.ao = false;
  const nlohmann::json j = app::settingsJson(r);
  ASSERT_EQ(j.size(), settingsTable().size());
  EXPECT_EQ(j.at("ao"), false);
  EXPECT_EQ(j.at("tonemap"), "aces");
  EXPECT_TRUE(j.at("shadow-lights").is_number_integer());
  EXPECT_EQ(j.at("exposure"), "auto");  // a named value of a number setting
  EXPECT_EQ(j.at("ev100"), "off");
}

// Each command's --help lists the table's entries it takes, with their defaults; a bad value is a
// parse error (exit 2) naming the option.
TEST(SettingsTable, DrivesTheCommandLineOfRenderViewAndBench) {
  for (auto [command, use] : {std::pair{"render", kUseRender}, {"view", kUseView}, {"bench", kUseBench}}) {
    const test::RunResult help = test::runRayster(std::string(command) + " --help");
    ASSERT_EQ(help.exitCode, 0) << help.output;
    for (const Setting& s : settingsTable()) {
      // bench sweeps these as axes of its own (lists of values), not as table options
      const bool axis = use == kUseBench &&
                        (s.name == "mode" || s.name == "primary" || s.name == "max-depth" || s.name == "shadow-lights");
      if (axis) continue;
      const bool listed = help.output.find("--" + s.name + " ") != std::string::npos;
      EXPECT_EQ(listed, (s.uses & use) != 0) << command << " --" << s.name;
    }
  }
  const test::RunResult bad = test::runRayster("render --denoise maybe -o /dev/null");
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.output.find("--denoise"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("on|off"), std::string::npos) << bad.output;
}

TEST(SettingsTable, RenderJsonRecordsTheSettingsItRanWith) {
  const auto dir = test::testDir();
  const test::RunResult r = test::runRayster(
      "render builtin:cornell --size 32x18 --frames 1 --ao off --tonemap neutral "
      "--json " +
      (dir / "r.json").string() + " -o " + (dir / "r.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream f(dir / "r.json");
  const nlohmann::json j = nlohmann::json::parse(f);
  const nlohmann::json& s = j.at("render_settings");
  EXPECT_EQ(s.size(), settingsTable().size());
  EXPECT_EQ(s.at("ao"), false);
  EXPECT_EQ(s.at("tonemap"), "neutral");
  EXPECT_EQ(s.at("denoise"), true);
}

}  // namespace
}  // namespace rayster::render
