// `--effects all|shadows|mirrors|none|LIST` (render/settings_table.cpp): each preset renders an
// image and records exactly the passes of its effects (off means gone: docs/architecture.md §2.2),
// `mirrors` traces no shadow ray at the bounce loop's hits, a list turns on exactly its effects,
// explicit options override a preset, and the bench scenes made for the presets
// (bench/scenes/effects-*.json) have the triangle counts they promise.
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/bench_plan.h"
#include "app/settings_cli.h"
#include "render/settings_table.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

const std::string kSource = RAYSTER_SOURCE_DIR;
const std::string kShadowsScene = kSource + "/bench/scenes/effects-shadows.json";
const std::string kMirrorsScene = kSource + "/bench/scenes/effects-mirrors.json";

// What one `render --json` run recorded.
struct Recorded {
  std::set<std::string> passes;
  nlohmann::json json;
};

class EffectsPresets : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testDir(); }

  // Renders 64x48, 2 frames, traced primaries (one G-buffer pass whatever the device is fastest
  // at), asserting a sound image; returns the passes its --json lists.
  Recorded run(const std::string& scene, const std::string& args) {
    const auto png = dir_ / "out.png", json = dir_ / "out.json";
    const RunResult r = runRayster("render " + scene + " --size 64x48 --frames 2 --primary rt " + args + " --json " +
                                   json.string() + " -o " + png.string());
    EXPECT_EQ(r.exitCode, 0) << args << "\n" << r.output;
    Recorded rec;
    auto img = readPng(png);
    EXPECT_TRUE(img.ok()) << args;
    if (img.ok()) {
      const auto empty = rejectEmpty(*img, 64, 48);
      EXPECT_FALSE(empty.has_value()) << args << ": " << empty.value_or("");
    }
    std::ifstream f(json);
    rec.json = nlohmann::json::parse(f, nullptr, false);
    if (rec.json.is_discarded() || !rec.json.contains("passes")) {
      ADD_FAILURE() << args << ": no passes in the JSON\n" << r.output;
      return rec;
    }
    for (const auto& p : rec.json["passes"]) rec.passes.insert(p.at("name").get<std::string>());
    return rec;
  }

  std::filesystem::path dir_;
};

using Passes = std::set<std::string>;

TEST_F(EffectsPresets, ShadowsIsPrimaryVisibilityAndOneShadowRayPerPixel) {
  const Recorded r = run(kShadowsScene, "--effects shadows");
  EXPECT_EQ(r.passes, (Passes{"gbuffer-traced", "rt-shadows", "lighting", "tonemap"}));
  for (const auto& p : r.json["passes"]) {
    if (p["name"] == "rt-shadows") {
      EXPECT_EQ(p["rays"], 64u * 48u) << "one light: one shadow ray per pixel";
    }
  }
  EXPECT_EQ(r.json["render_settings"]["effects"], "shadows");
  EXPECT_EQ(r.json["scene_stats"]["triangles"], 59962u) << "3 bunnies, 4 teapots and the floor";
  EXPECT_EQ(r.json["scene_stats"]["spheres"], 3u);
}

TEST_F(EffectsPresets, MirrorsIsTheBounceLoopWithoutShadows) {
  const Recorded r = run(kMirrorsScene, "--effects mirrors");
  // Mirrors and diffuse surfaces only: nothing is traced at half rate, so no rt-specular-fill. The
  // paths that go on after their first bounce are queued (lavapipe launches rays indirectly).
  EXPECT_EQ(r.passes, (Passes{"gbuffer-traced", "rt-specular-queue-clear", "rt-specular", "rt-specular-continue",
                              "lighting", "tonemap"}));
  uint64_t rays = 0;
  for (const auto& p : r.json["passes"]) {
    if (p["name"] == "rt-specular") EXPECT_EQ(p["rays"], 64u * 48u) << "the first bounce of every pixel";
    if (p["name"] == "rt-specular" || p["name"] == "rt-specular-continue") rays += p["rays"].get<uint64_t>();
  }
  // The queue holds a path per 4 pixels; no shadow rays at any hit.
  EXPECT_EQ(rays, 64u * 48u + 64u * 48u / 4u * 3u) << "up to 4 bounces a path, no shadow rays at their hits";
  EXPECT_EQ(r.json["max_depth"], 5u);
  EXPECT_EQ(r.json["render_settings"]["effects"], "mirrors");
  EXPECT_EQ(r.json["scene_stats"]["triangles"], 70690u) << "4 bunnies, 3 teapots and the floor";
}

TEST_F(EffectsPresets, AllIsTheDefaultFrame) {
  const Recorded r = run("builtin:whitted", "--effects all --gi path");
  for (const char* p : {"rt-shadows", "rt-ao", "shadow-temporal", "rt-specular", "reflection-temporal", "rt-indirect",
                        "indirect-temporal", "denoise-surface", "taa"})
    EXPECT_TRUE(r.passes.count(p)) << p;
  EXPECT_EQ(r.json["render_settings"]["effects"], "all");
  const Recorded none = run("builtin:whitted", "--effects none");
  EXPECT_EQ(none.passes, (Passes{"gbuffer-traced", "lighting", "tonemap"}));
}

TEST_F(EffectsPresets, AListTurnsOnExactlyItsEffects) {
  const Recorded r = run(kShadowsScene, "--effects shadows,ao");
  // AO at half rate (the default --ao-rate): its fill pass comes with it.
  EXPECT_EQ(r.passes, (Passes{"gbuffer-traced", "rt-shadows", "rt-ao", "rt-ao-fill", "lighting", "tonemap"}));
  const Recorded d = run(kShadowsScene, "--effects shadows,denoise,taa");
  EXPECT_TRUE(d.passes.count("shadow-temporal") && d.passes.count("denoise-surface") && d.passes.count("taa"));
  EXPECT_FALSE(d.passes.count("rt-ao"));
  EXPECT_EQ(d.json["render_settings"]["effects"], "shadows,denoise,taa");
}

TEST_F(EffectsPresets, ExplicitOptionsOverrideThePresetWhereverTheyStand) {
  for (const char* args : {"--effects shadows --taa on", "--taa on --effects shadows"}) {
    const Recorded r = run(kShadowsScene, args);
    EXPECT_EQ(r.passes, (Passes{"gbuffer-traced", "rt-shadows", "lighting", "taa", "tonemap"})) << args;
    EXPECT_EQ(r.json["render_settings"]["taa"], true) << args;
  }
  const Recorded d = run(kMirrorsScene, "--effects mirrors --max-depth 2");
  EXPECT_EQ(d.json["max_depth"], 2u);
}

// The raster mode follows the same switches: no shadow maps without shadows, no screen-space
// reflections without reflections.
TEST_F(EffectsPresets, RasterModeRecordsOnlyTheEffectsOn) {
  const Recorded shadows = run(kShadowsScene, "--mode raster --effects shadows");
  EXPECT_TRUE(shadows.passes.count("shadow-maps") && shadows.passes.count("shadow-resolve"));
  EXPECT_FALSE(shadows.passes.count("ssr") || shadows.passes.count("lighting-direct") || shadows.passes.count("taa"));
  const Recorded mirrors = run(kMirrorsScene, "--mode raster --effects mirrors");
  EXPECT_TRUE(mirrors.passes.count("ssr"));
  EXPECT_FALSE(mirrors.passes.count("shadow-maps") || mirrors.passes.count("shadow-resolve"));
}

TEST_F(EffectsPresets, AnUnknownEffectIsABadArgument) {
  const RunResult r =
      runRayster("render builtin:whitted --size 16x16 --effects shadows,glare -o " + (dir_ / "bad.png").string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("'glare' is no effect"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "bad.png"));
  const RunResult bench = runRayster("bench --effects ,ao --frames 1");
  EXPECT_EQ(bench.exitCode, 2) << bench.output;
}

// A vertical mirror facing the camera reflects the floor behind the camera; a roof high above
// shadows that floor from a sun overhead, where neither the mirror nor the camera sees it.
// `all` shadows the reflected floor (a shadow ray at the bounce's hit); `mirrors` traces none, so
// the roof changes nothing in its reflection.
TEST_F(EffectsPresets, MirrorsTracesNoShadowRayAtTheReflectionsHits) {
  auto scene = [&](bool roof) {
    const auto path = dir_ / (roof ? "roof.json" : "open.json");
    std::ofstream(path) << R"({"models": [{"path": "builtin:floor:white"},
        {"path": "builtin:floor:mirror", "rotate": [90, 0, 0], "scale": 0.1, "translate": [0, 1, 0]})"
                        << (roof ? R"(, {"path": "builtin:floor:white", "translate": [0, 15, 10]})" : "") << R"(],
      "lights": [{"type": "directional", "direction": [0, -1, 0], "intensity": 3}],
      "cameras": [{"position": [0, 1, 6], "target": [0, 1, 0], "yfov": 30}],
      "environment": "sky"})";
    return path.string();
  };
  auto reflection = [&](const std::string& path, const std::string& effects) {
    auto aovs =
        renderAovs(dir_, path + " --size 48x48 --frames 2 --primary rt --exposure 0 " + effects, {"reflection-raw"});
    return meanLuminance(aovs["reflection-raw"]);
  };
  const double mirrorsOpen = reflection(scene(false), "--effects mirrors");
  const double mirrorsRoof = reflection(scene(true), "--effects mirrors");
  ASSERT_GT(mirrorsOpen, 0.0);
  EXPECT_NEAR(mirrorsRoof, mirrorsOpen, 0.01 * mirrorsOpen) << "no shadow ray: the roof does not darken the reflection";
  // The same preset with --shadows on: only the frame's shadow flag differs, and the hits go dark.
  const double mirrorsShadowedRoof = reflection(scene(true), "--effects mirrors --shadows on");
  EXPECT_LT(mirrorsShadowedRoof, 0.85 * mirrorsRoof);
  const double allOpen = reflection(scene(false), "--effects all --gi path");
  const double allRoof = reflection(scene(true), "--effects all --gi path");
  EXPECT_LT(allRoof, 0.85 * allOpen) << "with shadows the reflected floor lies in the roof's shadow (mirrors: "
                                     << mirrorsOpen << ", " << mirrorsRoof << ")";
}

}  // namespace
}  // namespace rayster::test

namespace rayster::render {
namespace {

TEST(EffectsSettings, PresetsAndListsSetExactlyTheirEffects) {
  const Setting* effects = findSetting("effects");
  ASSERT_NE(effects, nullptr);
  EXPECT_TRUE(effects->preset);
  RenderSettings r;
  EXPECT_EQ(effects->get(r), "all") << "the default frame";
  ASSERT_TRUE(effects->set(r, "shadows").ok());
  EXPECT_TRUE(r.shadows);
  EXPECT_FALSE(r.reflections || r.ao || r.indirect || r.denoise || r.taa);
  ASSERT_TRUE(effects->set(r, "mirrors").ok());
  EXPECT_TRUE(r.reflections);
  EXPECT_FALSE(r.shadows || r.ao || r.indirect || r.denoise || r.taa);
  EXPECT_EQ(r.maxDepth, kMirrorsMaxDepth);
  ASSERT_TRUE(effects->set(r, "gi,taa,shadows").ok());
  EXPECT_TRUE(r.indirect && r.taa && r.shadows);
  EXPECT_FALSE(r.reflections || r.ao || r.denoise);
  EXPECT_EQ(effects->get(r), "shadows,gi,taa") << "a list is written in kEffectNames' order";
  ASSERT_TRUE(effects->set(r, "none").ok());
  EXPECT_EQ(effects->get(r), "none");
  for (const char* bad : {"", "glare", "shadows,", ",ao", "all,ao", "mirrors,ao", "Shadows"}) {
    const Status s = effects->set(r, bad);
    EXPECT_FALSE(s.ok()) << bad;
    if (!s.ok()) {
      EXPECT_EQ(s.error().code, ExitCode::BadArguments);
      EXPECT_NE(s.error().message.find("--effects"), std::string::npos) << s.error().message;
    }
  }
  EXPECT_EQ(effects->typeText(), "all|shadows|mirrors|none|LIST");
}

TEST(EffectsSettings, ExplicitSettingsOverrideAPreset) {
  RenderSettings r;
  // std::map orders the names: "ao" and "denoise" come before "effects", "taa" after it.
  ASSERT_TRUE(app::applySettings({{"effects", "shadows"}, {"ao", "on"}, {"taa", "on"}}, r).ok());
  EXPECT_TRUE(r.shadows && r.ao && r.taa);
  EXPECT_FALSE(r.reflections || r.indirect || r.denoise);
  RenderSettings m;
  ASSERT_TRUE(app::applySettings({{"effects", "mirrors"}, {"max-depth", "3"}, {"denoise", "on"}}, m).ok());
  EXPECT_EQ(m.maxDepth, 3u);
  EXPECT_TRUE(m.denoise && m.reflections);
}

TEST(EffectsSettings, BenchTakesTheMirrorsDepthUnlessGivenOne) {
  app::BenchAxes axes;
  axes.settings = {{"effects", "mirrors"}};
  auto plan = app::planFromAxes(axes);
  ASSERT_TRUE(plan.ok()) << plan.error().message;
  EXPECT_EQ(plan->configs.at(0).maxDepth, kMirrorsMaxDepth);
  axes.maxDepths = {3};
  plan = app::planFromAxes(axes);
  ASSERT_TRUE(plan.ok());
  EXPECT_EQ(plan->configs.at(0).maxDepth, 3u);
  axes = {};
  plan = app::planFromAxes(axes);
  ASSERT_TRUE(plan.ok());
  EXPECT_EQ(plan->configs.at(0).maxDepth, app::kBenchMaxDepth);
}

}  // namespace
}  // namespace rayster::render
