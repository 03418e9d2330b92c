// Probe cascades (render/passes/gi_probes.cpp fitProbeGrid, lib/probes.glsl): a small scene keeps
// the one grid fitted to its bounds; a large one gets finer cascades whose windows follow the
// camera inside the coarsest grid. On a large scene a room is lit by probes inside it, not by the
// sunlit ones outside it; a window that scrolls with the camera leaves no light of the place its
// probes held before.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "render/passes/passes.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

using render::fitProbeGrid;

glm::ivec3 window(const gpu::ProbeGrid& g, uint32_t k) {
  const uint32_t w = g.cascadeCells[k].x;
  return {int(w & 0xffu), int((w >> 8) & 0xffu), int((w >> 16) & 0xffu)};
}
glm::vec3 spacing(const gpu::ProbeGrid& g, uint32_t k) {
  const uint32_t w = g.cascadeCells[k].x >> 24;
  return g.spacing / glm::vec3(float(1u << (w & 3u)), float(1u << ((w >> 2) & 3u)), float(1u << ((w >> 4) & 3u)));
}

TEST(ProbeCascades, SmallScenesKeepOneGridFittedToTheirBounds) {
  // The built-in Cornell box's bounds: 8 probes per axis, one cascade, as before cascades existed.
  const gpu::ProbeGrid g = fitProbeGrid({0, 0, 0}, {5.56f, 5.488f, 5.592f}, {2.78f, 2.7f, -8.0f}, 0);
  EXPECT_EQ(g.cascades, 1u);
  EXPECT_EQ(g.counts, glm::uvec3(8, 8, 8));
  EXPECT_EQ(window(g, 0), glm::ivec3(0));
  EXPECT_EQ(g.cascadeCells[0].x & gpu::kProbeWindowMoved, 0u);
  EXPECT_NEAR(g.spacing.x, 5.56f * 0.96f / 7.0f, 1e-4f);
  // builtin:whitted (16 × 4.25 × 16 m) is not large either.
  EXPECT_EQ(fitProbeGrid({-8, 0, -8}, {8, 4.25f, 8}, {0, 2, 10}, 0).cascades, 1u);
}

TEST(ProbeCascades, LargeScenesNestFinerWindowsAroundTheCamera) {
  const glm::vec3 lo{-48, 0, -48}, hi{48, 3, 48}, eye{1.5f, 1.5f, 1.5f};
  const gpu::ProbeGrid g = fitProbeGrid(lo, hi, eye, 0);
  ASSERT_EQ(g.cascades, 4u);
  EXPECT_EQ(g.counts, glm::uvec3(8, 4, 8)) << "the flat scene's height gets 4 probes in every cascade";
  const glm::vec3 finest = spacing(g, 0);
  EXPECT_LE(std::max(finest.x, std::max(finest.y, finest.z)), 2.5f);
  EXPECT_EQ(spacing(g, g.cascades - 1), g.spacing) << "the coarsest cascade is the fitted grid";
  EXPECT_EQ(window(g, g.cascades - 1), glm::ivec3(0));
  const glm::vec3 coarseMax = g.origin + g.spacing * glm::vec3(g.counts - 1u);
  for (uint32_t k = 0; k + 1 < g.cascades; ++k) {
    const glm::vec3 s = spacing(g, k), next = spacing(g, k + 1);
    for (int a : {0, 2}) EXPECT_FLOAT_EQ(s[a] * 2.0f, next[a]) << "cascade " << k;
    const glm::vec3 wMin = g.origin + glm::vec3(window(g, k)) * s, wMax = wMin + s * glm::vec3(g.counts - 1u);
    for (int a = 0; a < 3; ++a) {
      EXPECT_LE(wMin[a], eye[a] + 1e-4f) << "cascade " << k << " axis " << a;
      EXPECT_GE(wMax[a], eye[a] - 1e-4f) << "cascade " << k << " axis " << a;
      // Centred to within one cell (snapped to the lattice), and inside the coarsest grid.
      EXPECT_NEAR(0.5f * (wMin[a] + wMax[a]), eye[a], a == 1 ? 3.0f : s[a]) << "cascade " << k << " axis " << a;
      EXPECT_GE(wMin[a], g.origin[a] - 1e-4f);
      EXPECT_LE(wMax[a], coarseMax[a] + 1e-4f);
    }
  }
  // A camera at the scene's edge: the windows stop at the coarsest grid's faces.
  const gpu::ProbeGrid edge = fitProbeGrid(lo, hi, {60, 1, 60}, 0);
  for (uint32_t k = 0; k < edge.cascades; ++k) {
    const glm::vec3 s = spacing(edge, k);
    const glm::vec3 wMax = edge.origin + (glm::vec3(window(edge, k)) + glm::vec3(edge.counts - 1u)) * s;
    EXPECT_NEAR(wMax.x, coarseMax.x, 1e-3f) << "cascade " << k;
  }
  // One finest cell to the right moves the finest window by one cell, the coarser ones by at most one.
  const gpu::ProbeGrid moved = fitProbeGrid(lo, hi, eye + glm::vec3(finest.x, 0, 0), 0);
  EXPECT_EQ(window(moved, 0).x, window(g, 0).x + 1);
  for (uint32_t k = 1; k < g.cascades; ++k) EXPECT_LE(window(moved, k).x - window(g, k).x, 1);
  // Asked for: exactly that many, each halving the longest axis' spacing.
  const gpu::ProbeGrid two = fitProbeGrid(lo, hi, eye, 2);
  EXPECT_EQ(two.cascades, 2u);
  EXPECT_FLOAT_EQ(spacing(two, 0).x * 2.0f, two.spacing.x);
  EXPECT_EQ(fitProbeGrid({0, 0, 0}, {1, 1, 1}, eye, 1).cascades, 1u);
}

class ProbeCascadesRender : public ::testing::Test {
 protected:
  // A large scene (a 96 m floor under a strong sun and a sky) with a closed 4 × 3 × 4 m room in its
  // middle, lit inside by one point light; the camera is in the room. One grid over the whole
  // scene (13.7 m apart) has no probe in the room: its irradiance there is the sunlit outside's.
  void SetUp() override {
    dir_ = testDir();
    std::ofstream(dir_ / "grey.mtl") << "newmtl grey\nKd 0.6 0.6 0.6\nNs 0\nillum 2\n";
    std::ofstream obj(dir_ / "world.obj");
    obj << "mtllib grey.mtl\nusemtl grey\n";
    obj << "v -48 0 48\nv 48 0 48\nv 48 0 -48\nv -48 0 -48\nf 1 2 3 4\n";
    obj << "v -2 0 -2\nv 2 0 -2\nv 2 3 -2\nv -2 3 -2\nv -2 0 2\nv 2 0 2\nv 2 3 2\nv -2 3 2\n";
    // Walls and ceiling facing into the room (as a room is modelled: seen from inside).
    obj << "f 6 7 8 5\nf 12 11 10 9\nf 8 12 9 5\nf 10 11 7 6\nf 7 11 12 8\n";
    obj.close();
    std::ofstream(dir_ / "large.json") << R"({"models": [{"path": "world.obj"}],
  "lights": [{"type": "directional", "direction": [-0.3, -1, -0.2], "intensity": 20},
             {"type": "point", "position": [0, 2.4, 0], "intensity": 10}],
  "cameras": [{"name": "corner", "position": [1.5, 1.5, 1.5], "target": [-1, 1, -1], "yfov": 70},
              {"name": "wall", "position": [1.5, 1.5, 1], "target": [1.5, 1.2, 100], "yfov": 70}],
  "cameraPath": [{"time": 0, "position": [1.5, 1.5, -20], "target": [1.5, 1.2, 100]},
                 {"time": 1, "position": [1.5, 1.5, 1], "target": [1.5, 1.2, 100]},
                 {"time": 2, "position": [1.5, 1.5, 1], "target": [1.5, 1.2, 100]}],
  "environment": "sky"})";
    scene_ = (dir_ / "large.json").string();
  }

  ImageF render(const std::string& name, const std::string& args) {
    const auto out = dir_ / (name + ".exr");
    RunResult r = runRayster("render " + scene_ + " --size 64x48 --exposure 0 " + args + " -o " + out.string());
    EXPECT_EQ(r.exitCode, 0) << r.output;
    auto img = readExr(out);
    EXPECT_TRUE(img.ok()) << r.output;
    if (!img.ok()) return {};
    EXPECT_EQ(img->width, 64);
    EXPECT_EQ(img->height, 48);
    for (float v : img->rgba) EXPECT_TRUE(std::isfinite(v));
    return std::move(*img);
  }

  std::filesystem::path dir_;
  std::string scene_;
};

TEST_F(ProbeCascadesRender, ARoomInALargeSceneIsLitByItsOwnProbes) {
  const ImageF reference = render("reference", "--mode pathtrace --frames 256 --max-depth 16");
  const ImageF one = render("one", "--frames 16 --probe-cascades 1");
  const ImageF cascades = render("cascades", "--frames 16");
  const double ref = meanLuminance(reference);
  ASSERT_GT(ref, 0.0);
  const double eOne = meanLuminance(one) / ref - 1.0, eCascades = meanLuminance(cascades) / ref - 1.0;
  std::printf("room in a large scene, mean luminance vs the path tracer: one grid %+.3f, cascades %+.3f\n", eOne,
              eCascades);
  RecordProperty("energy_one_grid", std::to_string(eOne));
  RecordProperty("energy_cascades", std::to_string(eCascades));
  EXPECT_LT(std::abs(eCascades), 0.5 * std::abs(eOne));
  EXPECT_LT(std::abs(eCascades), 0.10);
}

// The camera walks 21 m from the sunlit outside into the room (no cut: slow for its distant target)
// and stays there: every probe of the finest window, and some of the next, entered it on the way
// (a window is 12 m long), in slots whose atlases held the light of the places left behind. Each
// such probe starts without history (probeFresh()), so 16 frames after arriving the probes' light
// in the room is what a still render from there sees; the light of the stale slots would decay only
// as 0.97 per frame.
TEST_F(ProbeCascadesRender, ScrollingWindowsLeaveNoLightOfWhereTheyWere) {
  auto irradiance = [&](const std::string& name, const std::string& args) {
    std::filesystem::create_directories(dir_ / name);
    auto aovs = renderAovs(dir_ / name, scene_ + " --size 64x48 --exposure 0 --frames 32 " + args, {"gi-irradiance"});
    EXPECT_EQ(aovs.size(), 1u);
    return aovs.empty() ? 0.0 : meanLuminance(aovs["gi-irradiance"]);
  };
  const double still = irradiance("still", "--camera wall");
  const double walked = irradiance("walked", "--camera wall --camera-path --path-fps 16");
  ASSERT_GT(still, 0.0);
  std::printf("probe irradiance in the room after walking in, vs a still render there: %+.4f\n", walked / still - 1.0);
  RecordProperty("walked_vs_still", std::to_string(walked / still - 1.0));
  EXPECT_NEAR(walked / still, 1.0, 0.05);
}

}  // namespace
}  // namespace rayster::test
