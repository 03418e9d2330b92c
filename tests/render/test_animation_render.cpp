// glTF animations on the GPU: a played frame matches the paused pose at the same time (the
// instance table and the refitted TLAS follow the animation, for raster and traced primaries,
// shadows included), and moving instances get motion vectors.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "tests/render/fixtures.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

constexpr int kW = 96, kH = 72;

class AnimationRender : public ::testing::TestWithParam<const char*> {
 protected:
  // Hard light, black environment, no TAA: every frame is deterministic, so images compare exactly.
  std::string args() const { return std::string(" --taa off --primary ") + GetParam(); }
};

TEST_P(AnimationRender, PlayedFrameMatchesThePausedPose) {
  auto dir = testDir();
  auto scene = writeAnimatedGltf(dir).string();
  // Frame 1 at 1 fps is t = 1 s: the slider at x = +1.5, as the paused pose at --time 1. The final
  // images differ where the denoisers blend in the moving frame's history; the G-buffer and the
  // raw shadow rays of the last frame must not.
  const std::string aovs = " --aov albedo,shadow-raw";
  Image8 played = renderOk(dir, "played", scene + args() + aovs + " --frames 2 --path-fps 1", kW, kH);
  Image8 paused = renderOk(dir, "paused", scene + args() + aovs + " --frames 1 --time 1 --pause", kW, kH);
  Image8 start = renderOk(dir, "start", scene + args() + " --frames 1 --time 0 --pause", kW, kH);
  ASSERT_FALSE(HasFailure());
  for (const char* aov : {"albedo", "shadow-raw"}) {
    auto a = readExr(dir / (std::string("played.") + aov + ".exr"));
    auto b = readExr(dir / (std::string("paused.") + aov + ".exr"));
    ASSERT_TRUE(a.ok() && b.ok()) << aov;
    ASSERT_EQ(a->rgba.size(), b->rgba.size());
    size_t differ = 0;
    for (size_t i = 0; i < a->rgba.size(); ++i) differ += std::abs(a->rgba[i] - b->rgba[i]) > 1e-3f;
    // The traced G-buffer and every shadow ray see the refitted TLAS; the raster one the new
    // instance table: exactly the paused pose's.
    EXPECT_EQ(differ, 0u) << aov << ": " << differ << " channel values differ";
  }
  ImageDiff moved = compare(start, played, 8);
  EXPECT_LT(moved.fractionWithinTolerance, 0.9) << "the slider (and its shadow) should have moved";
  // The slider is left of centre at t = 0 and right of it at t = 1: its red shows on that side.
  auto redAt = [](const Image8& img, int x) {
    const uint8_t* p = img.pixel(x, kH / 2);
    return p[0] > 2 * p[1] + 30;
  };
  EXPECT_TRUE(redAt(start, kW * 3 / 10));
  EXPECT_FALSE(redAt(start, kW * 7 / 10));
  EXPECT_TRUE(redAt(played, kW * 7 / 10));
  EXPECT_FALSE(redAt(played, kW * 3 / 10));
}

TEST_P(AnimationRender, MovingInstanceHasMotionVectors) {
  auto dir = testDir();
  auto scene = writeAnimatedGltf(dir).string();
  // 10 fps: between frames 4 and 5 the slider moves 0.3 m to the right.
  RunResult r = runRayster("render " + scene + args() + " --frames 5 --path-fps 10 --aov motion --size " +
                           std::to_string(kW) + "x" + std::to_string(kH) + " -o " + (dir / "m.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  auto mv = readExr(dir / "m.motion.exr");
  ASSERT_TRUE(mv.ok());
  auto png = readPng(dir / "m.png");
  ASSERT_TRUE(png.ok());
  int red = 0, floor = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const uint8_t* p = png->pixel(x, y);
      const float* m = mv->pixel(x, y);
      if (p[0] > 2 * p[1] + 30) {  // the slider: moving right on screen
        EXPECT_GT(m[0], 0.01f) << x << "," << y;
        ++red;
      } else if (y > kH * 9 / 10) {  // the floor near the camera: static
        EXPECT_EQ(m[0], 0.0f) << x << "," << y;
        EXPECT_EQ(m[1], 0.0f) << x << "," << y;
        ++floor;
      }
    }
  EXPECT_GT(red, 50);
  EXPECT_GT(floor, 50);
}

INSTANTIATE_TEST_SUITE_P(Producers, AnimationRender, ::testing::Values("raster", "rt"));

}  // namespace
}  // namespace rayster::test

namespace rayster::test {
namespace {

// A moving occluder leaves no trail (docs/techniques.md §11): with a hard light every shadow ray of a
// frame is exact, so the denoised shadow of the last frame of a moving sequence must agree with
// that frame's raw shadow — a ghost of where the slider's shadow was shows up as a disagreement.
TEST(AnimationRender, MovingShadowLeavesNoTrail) {
  auto dir = testDir();
  auto scene = writeAnimatedGltf(dir).string();
  // 10 fps, 8 frames: the slider and its shadow sweep 2.1 m to the right.
  RunResult r = runRayster("render " + scene + " --taa off --frames 8 --path-fps 10 --aov shadow-raw,shadow-denoised" +
                           " --size 96x72 -o " + (dir / "m.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  auto raw = readExr(dir / "m.shadow-raw.exr");
  auto denoised = readExr(dir / "m.shadow-denoised.exr");
  ASSERT_TRUE(raw.ok() && denoised.ok());
  const int w = raw->width, h = raw->height;
  auto litAround = [&](int x, int y) {  // lit in the whole 3×3 neighbourhood: away from today's edges
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        int qx = std::clamp(x + dx, 0, w - 1), qy = std::clamp(y + dy, 0, h - 1);
        if (raw->pixel(qx, qy)[0] < 0.5f) return false;
      }
    return true;
  };
  size_t shadowed = 0, ghosts = 0, pixels = size_t(w) * h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      shadowed += raw->pixel(x, y)[0] < 0.5f;
      // Lit now, but the denoised image still shows some of the shadow that passed over it.
      ghosts += litAround(x, y) && denoised->pixel(x, y)[0] < 0.9f;
    }
  EXPECT_GT(shadowed, pixels / 50) << "the slider's shadow should be in view";
  EXPECT_LT(ghosts, pixels / 200) << ghosts << " lit pixels still carry the old shadow";
}

}  // namespace
}  // namespace rayster::test

namespace rayster::test {
namespace {

// A camera on an animated node follows it: with the camera made a child of the slider, the slider
// stays in the middle of the frame at t = 0 and t = 1 (it is left of it, then right, seen from a
// fixed camera: PlayedFrameMatchesThePausedPose), in the hybrid and in the path tracer.
TEST(AnimatedCamera, FollowsItsAnimatedNode) {
  auto dir = testDir();
  const std::filesystem::path fixed = writeAnimatedGltf(dir);
  std::string text;
  {
    std::ifstream in(fixed);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  auto replace = [&](const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  replace(R"("scenes": [{"nodes": [0, 1, 2, 3]}])", R"("scenes": [{"nodes": [0, 1, 3]}])");
  replace(R"("name": "slider", "translation": [-1.5, 0, 0]})",
          R"("name": "slider", "translation": [-1.5, 0, 0], "children": [2]})");
  const std::filesystem::path follow = dir / "follow.gltf";
  std::ofstream(follow) << text;
  ASSERT_FALSE(HasFailure());
  auto redAt = [](const Image8& img, int x) {
    const uint8_t* p = img.pixel(x, kH / 2);
    return p[0] > 2 * p[1] + 30;
  };
  for (const char* mode : {"hybrid", "pathtrace"}) {
    SCOPED_TRACE(mode);
    const std::string args = follow.string() + " --taa off --frames 1 --pause --spp 8 --mode " + mode;
    Image8 start = renderOk(dir, std::string(mode) + "0", args + " --time 0", kW, kH);
    Image8 end = renderOk(dir, std::string(mode) + "1", args + " --time 1", kW, kH);
    ASSERT_FALSE(HasFailure());
    EXPECT_TRUE(redAt(start, kW / 2));
    EXPECT_TRUE(redAt(end, kW / 2));
    EXPECT_FALSE(redAt(end, kW * 9 / 10));
  }
}

}  // namespace
}  // namespace rayster::test

namespace rayster::test {
namespace {

// A light on an animated node moves with it (glTF 2.0: a light is placed by its node): with the
// point light made a child of the slider, the floor is lit from further left at t = 0 and further
// right at t = 1 than with the light left where it was, in the hybrid, the raster mode and the path
// tracer (the slider itself is in the same place in both, so only the light makes the difference).
TEST(AnimatedLight, FollowsItsAnimatedNode) {
  auto dir = testDir();
  const std::filesystem::path fixed = writeAnimatedGltf(dir);
  std::string text;
  {
    std::ifstream in(fixed);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  auto replace = [&](const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  replace(R"("scenes": [{"nodes": [0, 1, 2, 3]}])", R"("scenes": [{"nodes": [0, 1, 2]}])");
  replace(R"("name": "slider", "translation": [-1.5, 0, 0]})",
          R"("name": "slider", "translation": [-1.5, 0, 0], "children": [3]})");
  const std::filesystem::path follow = dir / "follow.gltf";
  std::ofstream(follow) << text;
  ASSERT_FALSE(HasFailure());
  // Right half minus left half of the floor (the bottom 40 % of the image), in mean luminance.
  auto rightMinusLeft = [](const Image8& img) {
    double left = 0, right = 0;
    for (int y = kH * 6 / 10; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const uint8_t* p = img.pixel(x, y);
        (x < kW / 2 ? left : right) += 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
      }
    return (right - left) / double(kW / 2 * (kH - kH * 6 / 10));
  };
  for (const char* mode : {"hybrid", "raster", "pathtrace"}) {
    SCOPED_TRACE(mode);
    const std::string args = " --taa off --frames 1 --pause --spp 8 --mode " + std::string(mode);
    double asym[2][2];  // [follows][time]
    for (int t = 0; t < 2; ++t) {
      const std::string time = " --time " + std::to_string(t);
      Image8 moving = renderOk(dir, std::string(mode) + "f" + std::to_string(t), follow.string() + args + time, kW, kH);
      Image8 still = renderOk(dir, std::string(mode) + "s" + std::to_string(t), fixed.string() + args + time, kW, kH);
      ASSERT_FALSE(HasFailure());
      asym[1][t] = rightMinusLeft(moving);
      asym[0][t] = rightMinusLeft(still);
    }
    std::printf("[animated light] %-9s right-left t0: follows %.1f fixed %.1f  t1: follows %.1f fixed %.1f\n", mode,
                asym[1][0], asym[0][0], asym[1][1], asym[0][1]);
    // The light goes from x = -1 to x = +2 (the fixed one stays at x = 0.5).
    EXPECT_LT(asym[1][0], asym[0][0] - 3.0) << "t = 0: lit from the left";
    EXPECT_GT(asym[1][1], asym[0][1] + 3.0) << "t = 1: lit from the right";
  }
}

}  // namespace
}  // namespace rayster::test
