// Skinning and morph targets (render/deform.h): a skinned and a morphed glTF from Debian's
// assimp-testmodels, rendered at several times, draw the G-buffer of a static copy of the same
// pose deformed on the CPU (scene::bakePose, written as a plain glTF) — with raster and traced
// primaries — and differ from the rest pose; the path tracer renders the pose of --time; and a
// deforming mesh has motion vectors while it plays.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/image_io.h"
#include "core/metrics.h"
#include "scene/animation.h"
#include "scene/loader.h"
#include "scene/skinning.h"
#include "tests/render/bake_gltf.h"
#include "tests/render/run_rayster.h"

namespace fs = std::filesystem;

namespace rayster::test {
namespace {

constexpr int kW = 96, kH = 72;
const fs::path kModels = "/usr/share/assimp/models/glTF2";

struct Model {
  const char* path;  // under kModels
  const char* name;
};
const Model kModelsUnderTest[] = {{"simple_skin/simple_skin.gltf", "skin"},
                                  {"glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf", "morph"}};

// Pixels where any channel of a and b differs by more than `tolerance`.
size_t differingPixels(const ImageF& a, const ImageF& b, float tolerance) {
  size_t n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const float *p = a.pixel(x, y), *q = b.pixel(x, y);
      bool differs = false;
      for (int c = 0; c < 3; ++c) differs |= !(std::abs(p[c] - q[c]) <= tolerance);
      n += differs;
    }
  return n;
}

// Largest vertex displacement of the pose at `t` from the rest pose, over the posed mesh's size.
float relativeDeformation(scene::Scene scene, float t) {
  const scene::Scene before = scene::bakePose(scene);
  scene::evaluateAnimations(scene, t);
  const scene::Scene after = scene::bakePose(scene);
  float moved = 0.0f;
  scene::Aabb size;
  for (size_t m = 0; m < after.meshes.size(); ++m)
    for (size_t p = 0; p < after.meshes[m].primitives.size(); ++p)
      for (size_t v = 0; v < after.meshes[m].primitives[p].positions.size(); ++v) {
        size.extend(after.meshes[m].primitives[p].positions[v]);
        moved = std::max(moved, glm::length(after.meshes[m].primitives[p].positions[v] -
                                            before.meshes[m].primitives[p].positions[v]));
      }
  return moved / glm::length(size.max - size.min);
}

class Deformation : public ::testing::TestWithParam<std::tuple<Model, const char*>> {};

TEST_P(Deformation, GBufferEqualsAStaticCopyOfThePose) {
  const auto [model, primary] = GetParam();
  const fs::path file = kModels / model.path;
  if (!fs::exists(file)) GTEST_SKIP() << "assimp-testmodels is not installed";
  auto loaded = scene::loadScene(file.string());
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const fs::path dir = testDir();
  const std::string common = std::string(" --taa off --frames 1 --pause --primary ") + primary + " --size " +
                             std::to_string(kW) + "x" + std::to_string(kH);
  const std::vector<std::string> aovs = {"depth", "normal", "albedo"};
  std::map<std::string, ImageF> rest;
  for (float t : {0.5f, 1.5f}) {
    SCOPED_TRACE(std::string(model.name) + " at t = " + std::to_string(t));
    ASSERT_GT(relativeDeformation(*loaded, t), 0.05f) << "the pose should deform the mesh visibly";
    scene::Scene posed = *loaded;
    scene::evaluateAnimations(posed, t);
    const fs::path baked = writeBakedGltf(scene::bakePose(posed), loaded->cameras.front(),
                                          dir / (std::string(model.name) + "-baked.gltf"));
    const fs::path a = dir / "animated", b = dir / "baked";
    fs::create_directories(a);
    fs::create_directories(b);
    auto animated = renderAovs(a, file.string() + common + " --time " + std::to_string(t), aovs);
    auto reference = renderAovs(b, baked.string() + common, aovs);
    ASSERT_EQ(animated.size(), aovs.size());
    ASSERT_EQ(reference.size(), aovs.size());
    // Not empty: the albedo shows the mesh on the sky's black, finite everywhere.
    size_t covered = 0;
    for (float v : animated["albedo"].rgba) {
      ASSERT_TRUE(std::isfinite(v));
      covered += v > 0.05f;
    }
    EXPECT_GT(covered, size_t(kW * kH / 50)) << "the mesh should cover part of the frame";
    for (const std::string& aov : aovs) {
      const ImageF &x = animated[aov], &y = reference[aov];
      ASSERT_EQ(x.width, kW);
      ASSERT_EQ(y.width, kW);
      // GPU and CPU deformation differ by float rounding: a silhouette pixel may flip, no more.
      const size_t differ = differingPixels(x, y, 2e-3f);
      EXPECT_LE(differ, size_t(kW * kH / 200)) << aov << ": " << differ << " pixels differ from the static copy";
    }
    // The pose must show: the rest pose's G-buffer differs from this one.
    if (rest.empty()) {
      const fs::path r = dir / "rest";
      fs::create_directories(r);
      rest = renderAovs(r, file.string() + common + " --time 0", aovs);
    }
    ASSERT_EQ(rest.size(), aovs.size());
    EXPECT_GT(differingPixels(rest["depth"], animated["depth"], 1e-3f), size_t(kW * kH / 100))
        << "the posed mesh should not look like the rest pose";
  }
}

INSTANTIATE_TEST_SUITE_P(Models, Deformation,
                         ::testing::Combine(::testing::ValuesIn(kModelsUnderTest), ::testing::Values("raster", "rt")),
                         [](const auto& info) {
                           return std::string(std::get<0>(info.param).name) + "_" + std::get<1>(info.param);
                         });

// The path tracer renders the pose of --time (a hybrid frame poses the scene for it): the same
// image as the path-traced static copy of that pose, up to float rounding of the deformation.
TEST(Deformation, PathTracerRendersThePoseOfTime) {
  const fs::path file = kModels / "simple_skin/simple_skin.gltf";
  if (!fs::exists(file)) GTEST_SKIP() << "assimp-testmodels is not installed";
  auto loaded = scene::loadScene(file.string());
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const fs::path dir = testDir();
  scene::Scene posed = *loaded;
  scene::evaluateAnimations(posed, 1.0f);
  const fs::path baked = writeBakedGltf(scene::bakePose(posed), loaded->cameras.front(), dir / "baked.gltf");
  const std::string common = " --mode pathtrace --spp 16 --exposure 0";
  Image8 at0 = renderOk(dir, "t0", file.string() + common + " --time 0", kW, kH);
  Image8 at1 = renderOk(dir, "t1", file.string() + common + " --time 1", kW, kH);
  Image8 copy = renderOk(dir, "copy", baked.string() + common, kW, kH);
  ASSERT_FALSE(HasFailure());
  const ImageDiff moved = compare(at0, at1, 8), same = compare(copy, at1, 8);
  EXPECT_LT(moved.fractionWithinTolerance, 0.97) << "the poses at --time 0 and 1 should differ";
  EXPECT_GT(same.fractionWithinTolerance, 0.99) << "--time 1 should path-trace like the static copy of its pose";
}

// A deforming emitter lights the path tracer's scene from where its pose puts it: the emissive
// triangles it samples (render/gpu_emissive.cpp) follow the pose of --time, as its BLAS does.
// simple_skin's strip made emissive, the only light, standing on a floor: path-traced at --time 1
// it lights the floor as the static copy of that pose does (the rest pose's upright strip lights
// it differently where the strip bends away).
TEST(Deformation, PathTracedDeformingEmitterLightsFromItsPose) {
  const fs::path file = kModels / "simple_skin/simple_skin.gltf";
  if (!fs::exists(file)) GTEST_SKIP() << "assimp-testmodels is not installed";
  const fs::path dir = testDir();
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(file));
  doc["materials"] = {{{"emissiveFactor", {1.0, 1.0, 1.0}}, {"doubleSided", true}}};
  doc["meshes"][0]["primitives"][0]["material"] = 0;
  const fs::path emitter = dir / "emissive_skin.gltf";
  std::ofstream(emitter) << doc.dump();
  auto loaded = scene::loadScene(emitter.string());
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  ASSERT_GT(relativeDeformation(*loaded, 1.0f), 0.05f);
  scene::Scene posed = *loaded;
  scene::evaluateAnimations(posed, 1.0f);
  const fs::path baked = writeBakedGltf(
      scene::bakePose(posed), loaded->cameras.empty() ? scene::Camera{} : loaded->cameras.front(), dir / "baked.gltf");
  std::ofstream(dir / "floor.mtl") << "newmtl grey\nKd 0.8 0.8 0.8\nNs 0\nillum 1\n";
  std::ofstream(dir / "floor.obj") << "mtllib floor.mtl\nusemtl grey\n"
                                      "v -3 -0.01 3\nv 4 -0.01 3\nv 4 -0.01 -3\nv -3 -0.01 -3\nf 1 2 3 4\n";
  // The scene's only light is the strip: a light of intensity 0 keeps the default sun away.
  auto sceneFile = [&](const fs::path& model, const char* name) {
    const fs::path path = dir / name;
    std::ofstream(path) << R"({"models": [{"path": ")" << model.filename().string() << R"("}, {"path": "floor.obj"}],
      "lights": [{"type": "point", "position": [0, 50, 0], "intensity": 0}],
      "cameras": [{"position": [0.5, 3.5, 4.5], "target": [0.5, 0.3, 0], "yfov": 50}]})";
    return path.string();
  };
  const std::string common = " --mode pathtrace --spp 32 --seed 3 --exposure 0";
  Image8 at0 = renderOk(dir, "t0", sceneFile(emitter, "animated.json") + common + " --time 0", kW, kH);
  Image8 at1 = renderOk(dir, "t1", sceneFile(emitter, "animated.json") + common + " --time 1", kW, kH);
  Image8 copy = renderOk(dir, "copy", sceneFile(baked, "baked.json") + common, kW, kH);
  ASSERT_FALSE(HasFailure());
  const ImageDiff moved = compare(at0, at1, 8), same = compare(copy, at1, 8);
  EXPECT_LT(moved.fractionWithinTolerance, 0.97) << "the poses at --time 0 and 1 should light the floor differently";
  EXPECT_GT(same.fractionWithinTolerance, 0.99)
      << "--time 1 should light the floor as the static copy of its pose does (rmse " << same.rmse << ")";
}

// A playing skin has motion vectors where it moves.
TEST(Deformation, PlayingSkinHasMotionVectors) {
  const fs::path file = kModels / "simple_skin/simple_skin.gltf";
  if (!fs::exists(file)) GTEST_SKIP() << "assimp-testmodels is not installed";
  const fs::path dir = testDir();
  for (const char* primary : {"raster", "rt"}) {
    SCOPED_TRACE(primary);
    auto images = renderAovs(dir,
                             file.string() + " --taa off --frames 6 --path-fps 10 --time 0.3 --primary " + primary +
                                 " --size " + std::to_string(kW) + "x" + std::to_string(kH),
                             {"motion"});
    ASSERT_EQ(images.size(), 1u);
    const ImageF& m = images["motion"];
    float largest = 0.0f;
    for (int y = 0; y < m.height; ++y)
      for (int x = 0; x < m.width; ++x) largest = std::max(largest, std::hypot(m.pixel(x, y)[0], m.pixel(x, y)[1]));
    // The joint turns by tens of degrees a second: at 10 fps its tip moves pixels per frame.
    EXPECT_GT(largest * kW, 0.5f) << "no pixel moves";
  }
}

}  // namespace
}  // namespace rayster::test
