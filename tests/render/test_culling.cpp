// Two-phase GPU culling of the raster G-buffer (render/passes/cull.h) through the real binary,
// validation on: culling never changes a pixel, and it drops what lies outside the view or behind
// other geometry. tests/render/test_culling_reference.cpp checks it against a CPU reference.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/render/culling_scenes.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

constexpr int kW = 128, kH = 72;  // 16:9, as the visible counts below assume

struct Culled {
  Image8 image;
  int64_t visible = -1, total = -1;
};

Culled renderCulled(const std::filesystem::path& dir, const std::string& name, const std::string& args, bool culling) {
  const std::string tag = name + (culling ? "-on" : "-off");
  const auto json = dir / (tag + ".json");
  Culled c;
  c.image = renderOk(dir, tag, args + " --culling " + (culling ? "on" : "off") + " --json " + json.string(), kW, kH);
  std::ifstream f(json);
  EXPECT_TRUE(f.good()) << json;
  if (!f) return c;
  const nlohmann::json j = nlohmann::json::parse(f);
  EXPECT_EQ(j.value("culling", !culling), culling);
  if (j.contains("draws")) {
    c.visible = j["draws"]["visible"].get<int64_t>();
    c.total = j["draws"]["total"].get<int64_t>();
  }
  return c;
}

void expectSameImage(const Image8& a, const Image8& b, const std::string& what) {
  ASSERT_EQ(a.rgba.size(), b.rgba.size()) << what;
  size_t differ = 0;
  for (size_t i = 0; i < a.rgba.size(); i += 4)
    differ += a.rgba[i] != b.rgba[i] || a.rgba[i + 1] != b.rgba[i + 1] || a.rgba[i + 2] != b.rgba[i + 2];
  EXPECT_EQ(differ, 0u) << what << ": " << differ << " pixels differ with culling on and off";
}

// builtin:instances:64 (a floor and an 8 × 8 grid of bunnies 1.5 m apart) seen from 4 m straight
// above the centre: a 40° view covers about ±2.6 m × ±1.5 m of floor, so only the two middle rows'
// four middle bunnies (8) and the floor are in view.
std::filesystem::path writeTopDownScene(const std::filesystem::path& dir) {
  auto file = dir / "top-down.json";
  std::ofstream(file) << R"({"models": [{"path": "builtin:instances:64"}],
  "cameras": [{"name": "top", "position": [0, 4, 0], "target": [0, 0, 0], "up": [0, 0, -1],
               "yfov": 40, "znear": 0.05, "zfar": 50}]})";
  return file;
}

TEST(Culling, OnAndOffRenderTheSameImage) {
  auto dir = testDir();
  for (const char* scene : {"builtin:whitted", "builtin:cornell", "builtin:spheres", "builtin:instances:64"}) {
    const std::string args = std::string(scene) + " --mode raster --frames 1";
    std::string name = scene + 8;
    for (char& ch : name)
      if (ch == ':') ch = '-';
    const Culled on = renderCulled(dir, name, args, true), off = renderCulled(dir, name, args, false);
    expectSameImage(on.image, off.image, scene);
    EXPECT_EQ(off.visible, off.total) << scene << ": culling off draws everything";
    EXPECT_GT(on.visible, 0) << scene;
    EXPECT_LE(on.visible, on.total) << scene;
  }
}

TEST(Culling, HybridWithRasterPrimaryMatches) {
  auto dir = testDir();
  const std::string args = "builtin:cornell --primary raster --frames 1";
  expectSameImage(renderCulled(dir, "cornell", args, true).image, renderCulled(dir, "cornell", args, false).image,
                  "hybrid cornell");
}

TEST(Culling, OutOfViewDrawsAreCulled) {
  auto dir = testDir();
  const std::string args = writeTopDownScene(dir).string() + " --mode raster --frames 1";
  const Culled on = renderCulled(dir, "top", args, true), off = renderCulled(dir, "top", args, false);
  expectSameImage(on.image, off.image, "top-down");
  EXPECT_EQ(on.total, 65);  // the floor and 64 bunnies
  EXPECT_EQ(off.visible, 65);
  EXPECT_GE(on.visible, 5) << "the bunnies under the camera and the floor are drawn";
  EXPECT_LE(on.visible, 13) << "most of the grid is outside the view";
}

TEST(Culling, HiddenDrawsAreCulledFromTheSecondFrame) {
  auto dir = testDir();
  const std::string scene = writeWallScene(dir).string() + " --mode raster";
  const Culled first = renderCulled(dir, "first", scene + " --frames 1", true);
  EXPECT_EQ(first.total, 66);  // floor, 64 bunnies, wall
  // The first frame draws everything in view early (no visibility yet): only the frustum culls.
  EXPECT_GE(first.visible, 50);
  const Culled on = renderCulled(dir, "wall", scene + " --frames 3", true);
  const Culled off = renderCulled(dir, "wall", scene + " --frames 3", false);
  expectSameImage(on.image, off.image, "behind the wall");
  EXPECT_LE(on.visible, first.visible / 2) << "mostly what the window shows is drawn";
  EXPECT_GE(on.visible, 4) << "the wall, the floor and bunnies through the window";
}

// The camera turns from the open sky (the whole grid behind it) to the grid: the frame that first
// shows the bunnies draws them (no popping), exactly as without culling.
TEST(Culling, ObjectsTurningIntoViewAreDrawnThatFrame) {
  auto dir = testDir();
  auto file = dir / "turn.json";
  std::ofstream(file) << R"({"models": [{"path": "builtin:instances:64"}],
  "cameras": [{"name": "turn", "position": [0, 1, 12], "target": [0, 1, 30], "yfov": 45, "znear": 0.05, "zfar": 80}],
  "cameraPath": [{"time": 0, "position": [0, 1, 12], "target": [0, 1, 30]},
                 {"time": 1, "position": [0, 1, 12], "target": [0, 0.5, 0]}]})";
  const std::string scene = file.string() + " --mode raster --camera-path --path-fps 2";
  const Culled away = renderCulled(dir, "away", scene + " --frames 1", true);
  EXPECT_EQ(away.visible, 0) << "looking away, nothing is in view (the floor ends behind the camera)";
  const Culled on = renderCulled(dir, "turned", scene + " --frames 3", true);
  const Culled off = renderCulled(dir, "turned", scene + " --frames 3", false);
  expectSameImage(on.image, off.image, "after the turn");
  EXPECT_GT(on.visible, 20) << "facing the grid, most bunnies are drawn";
}

// A skinned mesh is culled by the box of its pose (render/deform.h deformedBounds()): of two copies
// of Debian's simple_skin, the one 50 m to the side is not drawn, the one in view is, and playing
// the animation draws exactly what drawing everything draws.
TEST(Culling, DeformingMeshOutsideTheViewIsCulled) {
  const std::filesystem::path model = "/usr/share/assimp/models/glTF2/simple_skin/simple_skin.gltf";
  if (!std::filesystem::exists(model)) GTEST_SKIP() << "assimp-testmodels is not installed";
  auto dir = testDir();
  auto file = dir / "skins.json";
  std::ofstream(file)
      << R"({"models": [{"path": "simple_skin.gltf"}, {"path": "simple_skin.gltf", "translate": [50, 0, 0]}],
  "cameras": [{"position": [0.5, 1, 4], "target": [0.5, 1, 0], "yfov": 45}]})";
  std::filesystem::copy_file(model, dir / "simple_skin.gltf", std::filesystem::copy_options::overwrite_existing);
  const std::string scene = file.string() + " --mode raster --path-fps 4 --time 0.5";
  const Culled still = renderCulled(dir, "still", scene + " --frames 1 --pause", true);
  EXPECT_EQ(still.total, 2);
  EXPECT_EQ(still.visible, 1) << "the copy outside the view should be culled";
  const Culled on = renderCulled(dir, "playing", scene + " --frames 4", true);
  const Culled off = renderCulled(dir, "playing", scene + " --frames 4", false);
  expectSameImage(on.image, off.image, "a bending skin");
  EXPECT_EQ(on.visible, 1);
}

}  // namespace
}  // namespace rayster::test
