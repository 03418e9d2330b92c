// The Blender-exported corpus (assets/corpus, made by scripts/corpus/make_corpus.py with Debian's
// blender; docs/corpus.md): every file loads, with its lights and camera, and renders a non-empty
// image in the hybrid and the path tracer. Their energy against the path tracer and Cycles is in
// docs/corpus.md; frozen per-scene budgets are issue 14's next step.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "scene/loader.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

const std::filesystem::path kCorpus = std::filesystem::path(RAYSTER_SOURCE_DIR) / "assets" / "corpus";
const char* const kScenes[] = {"room.glb", "atrium.glb", "product.json", "foliage.json"};

TEST(Corpus, EveryFileLoadsWithItsLightsAndCamera) {
  for (const char* name : kScenes) {
    auto scene = scene::loadScene((kCorpus / name).string());
    ASSERT_TRUE(scene.ok()) << name << ": " << scene.error().message;
    EXPECT_FALSE(scene->lights.empty()) << name;
    EXPECT_FALSE(scene->cameras.empty()) << name << ": the exported camera";
    EXPECT_GE(scene->triangleCount(), 24u) << name;  // the room: 96 (walls and two boxes)
  }
}

TEST(Corpus, EveryFileRendersInTheHybridAndThePathTracer) {
  auto dir = testDir();
  for (const char* name : kScenes) {
    const std::string stem = std::filesystem::path(name).stem().string();
    const std::string file = (kCorpus / name).string();
    // One hybrid render: it exits cleanly, warns about nothing and writes a non-empty image.
    const auto hybrid = dir / (stem + "-hybrid.png");
    RunResult r = runRayster("render " + file + " --size 64x48 --frames 2 --seed 1 -o " + hybrid.string());
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << name << ": " << r.output;
    auto img = readPng(hybrid);
    EXPECT_TRUE(img.ok()) << name << ": " << (img.ok() ? "" : img.error().message);
    if (img.ok()) {
      auto empty = rejectEmpty(*img, 64, 48);
      EXPECT_FALSE(empty.has_value()) << stem << "-hybrid: " << empty.value_or("");
    }
    (void)renderOk(dir, stem + "-pt", file + " --mode pathtrace --frames 4 --seed 1", 64, 48);
  }
}

}  // namespace
}  // namespace rayster::test
