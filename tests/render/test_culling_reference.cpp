// Two-phase GPU culling (render/passes/cull.h) in-process, validation on: the GPU's per-draw
// visibility against a CPU reference of the same frustum and box-versus-depth-pyramid test, and a
// moving camera rendered with culling on and off, frame by frame.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render/gpu_scene.h"
#include "render/jitter.h"
#include "render/passes/cull.h"
#include "render/renderer.h"
#include "rhi/context.h"
#include "scene/loader.h"
#include "tests/render/culling_scenes.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

constexpr uint32_t kW = 128, kH = 72;

// A validation-on context, the scene and its renderer; skips without a Vulkan device.
struct CullScene {
  std::unique_ptr<rhi::Context> ctx;
  scene::Scene scene;
  std::unique_ptr<render::Renderer> renderer;

  bool create(const std::filesystem::path& file) {
    auto created = rhi::Context::create({/*validation*/ true, /*requireRayTracing*/ false, ""});
    if (!created) return false;
    ctx = std::move(created.value());
    auto loaded = scene::loadScene(file.string());
    EXPECT_TRUE(loaded.ok()) << (loaded.ok() ? "" : loaded.error().message);
    if (!loaded.ok()) return false;
    scene = std::move(loaded.value());
    auto r = render::Renderer::create(*ctx, scene);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    if (!r.ok()) return false;
    renderer = std::move(r.value());
    return true;
  }
  ~CullScene() {
    if (!ctx) return;
    ctx->waitIdle();
    renderer.reset();
    ctx->collectGarbage();
    EXPECT_EQ(ctx->validationErrors(), 0u) << "validation errors during the test";
  }
};

render::RenderSettings rasterSettings(bool culling) {
  render::RenderSettings s;
  s.width = kW, s.height = kH;
  s.mode = render::Mode::Raster;
  s.culling = culling;
  s.taa = true;  // jittered primaries: the cull must use the very matrix rasterised
  // A fixed exposure: auto exposure carries its metered value from one run into the next, and the
  // runs compared here must differ in culling alone.
  s.exposureMode = render::ExposureMode::Ev;
  return s;
}

// ---- the CPU reference: what cull.comp computes, written independently ----

// The frame's jittered clipFromWorld, as the renderer builds it (reversed Z, Vulkan y down).
glm::mat4 clipFromWorld(const scene::Camera& cam, uint32_t frame) {
  const glm::mat4 view = glm::lookAt(cam.position, cam.target, cam.up);
  glm::mat4 proj = glm::perspective(cam.yFov, float(kW) / float(kH), cam.zFar, cam.zNear);
  proj[1][1] *= -1.0f;
  return render::jitteredClipFromWorld(proj * view, render::jitterNdc(frame, kW, kH));
}

// Level 0 is the depth image; each next level the MIN (reversed Z: farthest) of the 2 × 2 texels it
// covers, ceil-sized, clamped at the edge.
struct Pyramid {
  std::vector<std::vector<float>> levels;
  std::vector<glm::ivec2> sizes;

  explicit Pyramid(const ImageF& depth) {
    sizes.push_back({depth.width, depth.height});
    std::vector<float> level0(size_t(depth.width) * depth.height);
    for (int y = 0; y < depth.height; ++y)
      for (int x = 0; x < depth.width; ++x) level0[size_t(y) * depth.width + x] = depth.pixel(x, y)[0];
    levels.push_back(std::move(level0));
    while (sizes.back() != glm::ivec2(1)) {
      const glm::ivec2 ps = sizes.back(), s = glm::max((ps + 1) / 2, glm::ivec2(1));
      std::vector<float> next(size_t(s.x) * s.y);
      const std::vector<float>& prev = levels.back();
      for (int y = 0; y < s.y; ++y)
        for (int x = 0; x < s.x; ++x) {
          const int x0 = 2 * x, y0 = 2 * y, x1 = std::min(x0 + 1, ps.x - 1), y1 = std::min(y0 + 1, ps.y - 1);
          next[size_t(y) * s.x + x] = std::min(std::min(prev[size_t(y0) * ps.x + x0], prev[size_t(y0) * ps.x + x1]),
                                               std::min(prev[size_t(y1) * ps.x + x0], prev[size_t(y1) * ps.x + x1]));
        }
      levels.push_back(std::move(next));
      sizes.push_back(s);
    }
  }
  float at(size_t level, glm::ivec2 p) const { return levels[level][size_t(p.y) * sizes[level].x + p.x]; }
};

enum class Cull { Outside, Occluded, Visible };

glm::vec3 corner(const render::GpuScene::Draw& d, int k) {
  return {(k & 1) ? d.aabbMax.x : d.aabbMin.x, (k & 2) ? d.aabbMax.y : d.aabbMin.y,
          (k & 4) ? d.aabbMax.z : d.aabbMin.z};
}

Cull cpuCull(const render::GpuScene::Draw& d, const glm::mat4& clipFromObject, const Pyramid& hiz) {
  // Frustum: every corner outside one and the same clip plane.
  uint32_t allOutside = 0x3F;
  for (int k = 0; k < 8; ++k) {
    const glm::vec4 c = clipFromObject * glm::vec4(corner(d, k), 1.0f);
    allOutside &= (c.x < -c.w ? 1u : 0u) | (c.x > c.w ? 2u : 0u) | (c.y < -c.w ? 4u : 0u) | (c.y > c.w ? 8u : 0u) |
                  (c.z < 0.0f ? 16u : 0u) | (c.z > c.w ? 32u : 0u);
  }
  if (allOutside != 0) return Cull::Outside;
  // Occlusion: the box's screen rectangle, a pixel wider, at the level where it spans ≤ 4 × 4.
  glm::vec2 lo(1e30f), hi(-1e30f);
  float nearest = 0.0f;
  for (int k = 0; k < 8; ++k) {
    const glm::vec4 c = clipFromObject * glm::vec4(corner(d, k), 1.0f);
    if (c.w <= 1e-6f) return Cull::Visible;
    const glm::vec3 ndc = glm::vec3(c) / c.w;
    lo = glm::min(lo, glm::vec2(ndc)), hi = glm::max(hi, glm::vec2(ndc));
    nearest = std::max(nearest, ndc.z);
  }
  if (nearest >= 1.0f) return Cull::Visible;
  const glm::ivec2 size = hiz.sizes[0], last = size - 1;
  const glm::ivec2 p0 =
      glm::clamp(glm::ivec2(glm::floor((lo * 0.5f + 0.5f) * glm::vec2(size))) - 1, glm::ivec2(0), last);
  const glm::ivec2 p1 =
      glm::clamp(glm::ivec2(glm::floor((hi * 0.5f + 0.5f) * glm::vec2(size))) + 1, glm::ivec2(0), last);
  size_t level = 0;
  const int span = int(gpu::kHizFootprint) - 1;
  while (level + 1 < hiz.levels.size() &&
         ((p1.x >> level) - (p0.x >> level) > span || (p1.y >> level) - (p0.y >> level) > span))
    ++level;
  const glm::ivec2 t0(p0.x >> level, p0.y >> level), t1(p1.x >> level, p1.y >> level);
  float farthest = 1.0f;
  for (int y = t0.y; y <= t1.y; ++y)
    for (int x = t0.x; x <= t1.x; ++x) farthest = std::min(farthest, hiz.at(level, {x, y}));
  return nearest < farthest ? Cull::Occluded : Cull::Visible;
}

const ImageF* findAov(const render::RenderOutput& out, const std::string& name) {
  for (const auto& [n, image] : out.aovs)
    if (n == name) return &image;
  return nullptr;
}

// A static view rendered a few frames: the last frame's late phase drew nothing new, so the depth
// read back is the depth its pyramid was built from, and the CPU test on that depth must agree with
// the GPU's visibility draw by draw.
TEST(CullingReference, GpuVisibilityMatchesCpuCullDrawByDraw) {
  auto dir = testDir();
  CullScene t;
  if (!t.create(writeWallScene(dir))) {
    if (!t.ctx) GTEST_SKIP() << "no Vulkan device";
    return;
  }
  render::RenderSettings s = rasterSettings(true);
  constexpr uint32_t kFrames = 3;
  s.frames = kFrames;
  s.aovs = {"depth"};
  auto rendered = t.renderer->render(s);
  ASSERT_TRUE(rendered.ok()) << rendered.error().message;
  const render::RenderOutput& out = *rendered;
  const render::GpuScene& gpu = t.renderer->gpuScene();
  ASSERT_EQ(gpu.draws.size(), 66u);  // floor, 64 bunnies, wall
  const render::CullCounts counts = render::cullCounts(gpu);
  ASSERT_EQ(counts.late, 0u) << "a static view's last frame draws everything visible in the early phase";
  const ImageF* depth = findAov(out, "depth");
  ASSERT_NE(depth, nullptr);
  ASSERT_EQ(depth->width, int(kW));
  ASSERT_EQ(depth->height, int(kH));

  const Pyramid hiz(*depth);
  const glm::mat4 clip = clipFromWorld(t.scene.cameras.front(), kFrames - 1);
  const std::vector<uint8_t> gpuVisible = render::drawVisibility(gpu);
  ASSERT_EQ(gpuVisible.size(), gpu.draws.size());
  int outside = 0, occluded = 0, visible = 0;
  for (size_t i = 0; i < gpu.draws.size(); ++i) {
    const render::GpuScene::Draw& d = gpu.draws[i];
    const Cull cpu = cpuCull(d, clip * gpu.instanceRecords.at(d.instance).worldFromObject, hiz);
    outside += cpu == Cull::Outside, occluded += cpu == Cull::Occluded, visible += cpu == Cull::Visible;
    EXPECT_EQ(gpuVisible[i] != 0, cpu == Cull::Visible)
        << "draw " << i << " (instance row " << d.instance << "): CPU says "
        << (cpu == Cull::Outside    ? "outside the frustum"
            : cpu == Cull::Occluded ? "occluded"
                                    : "visible");
  }
  EXPECT_GE(outside, 8) << "the grid's outer columns lie outside the view";
  EXPECT_GE(occluded, 20) << "most of the grid is behind the wall";
  EXPECT_GE(visible, 4) << "the wall, the floor and bunnies through the window";
  EXPECT_EQ(int64_t(visible), out.visibleDraws) << "a static view draws exactly the visible set";
  EXPECT_LT(out.visibleDraws, int64_t(out.totalDraws));
}

// The camera moves along the wall and towards it, so bunnies come into view through the window and
// others leave it: with culling on every frame equals the frame with culling off (no popping, no
// missing object), while fewer draws are rasterised than are in view.
TEST(CullingReference, MovingCameraFramesEqualWithCullingOnAndOff) {
  auto dir = testDir();
  CullScene t;
  if (!t.create(writeWallScene(dir))) {
    if (!t.ctx) GTEST_SKIP() << "no Vulkan device";
    return;
  }
  constexpr int kFrames = 6;
  std::vector<scene::Camera> path;
  for (int f = 0; f < kFrames; ++f) {
    scene::Camera cam = t.scene.cameras.front();
    const float u = float(f) / float(kFrames - 1);
    cam.position = glm::vec3(-0.9f + 1.8f * u, 0.8f, 9.0f - 1.2f * u);
    cam.target = glm::vec3(0.6f - 1.2f * u, 0.6f, 0.0f);
    path.push_back(cam);
  }
  // Frame by frame (Renderer::renderFrame) is the hybrid pipeline's API; its primaries are the
  // same raster G-buffer. AO and indirect light stay off to keep lavapipe quick.
  if (!t.ctx->caps().rayTracing()) GTEST_SKIP() << "the hybrid pipeline needs ray tracing";
  // Per frame with culling on: draws in view (the CPU frustum test), visible after the late phase,
  // rasterised early and late.
  struct Counts {
    int inView = 0, visible = 0;
    render::CullCounts drawn;
  };
  std::vector<Counts> counts;
  auto record = [&](int f) {
    const render::GpuScene& gpu = t.renderer->gpuScene();
    Counts c;
    const glm::mat4 clip = clipFromWorld(path[f], uint32_t(f));
    const Pyramid empty(ImageF::make(kW, kH));  // all far: hides nothing
    for (const render::GpuScene::Draw& d : gpu.draws)
      c.inView += cpuCull(d, clip * gpu.instanceRecords.at(d.instance).worldFromObject, empty) != Cull::Outside;
    for (uint8_t v : render::drawVisibility(gpu)) c.visible += v;
    c.drawn = render::cullCounts(gpu);
    counts.push_back(c);
  };
  auto runFrames = [&](bool culling, std::vector<Image8>& images, std::vector<int64_t>& drawn) {
    render::RenderSettings s = rasterSettings(culling);
    s.mode = render::Mode::Hybrid;
    s.primary = render::Primary::Raster;
    s.ao = false;
    s.indirect = false;
    s.frames = kFrames;
    const Status begun = t.renderer->beginRun(s);
    ASSERT_TRUE(begun.ok()) << begun.error().message;
    for (int f = 0; f < kFrames; ++f) {
      render::FrameControl control;
      control.camera = path[f];
      control.moving = true;
      control.readback = true;
      drawn.push_back(t.renderer->renderFrame(control).visibleDraws);
      if (culling) record(f);
      images.push_back(t.renderer->readbackImages().ldr);
    }
    (void)t.renderer->endRun();
  };
  std::vector<Image8> on, off;
  std::vector<int64_t> drawnOn, drawnOff;
  runFrames(false, off, drawnOff);
  runFrames(true, on, drawnOn);
  ASSERT_EQ(on.size(), size_t(kFrames));
  ASSERT_EQ(off.size(), size_t(kFrames));
  const uint32_t total = uint32_t(t.renderer->gpuScene().draws.size());
  ASSERT_EQ(counts.size(), size_t(kFrames));
  uint32_t lateDraws = 0;
  for (int f = 0; f < kFrames; ++f) {
    auto empty = rejectEmpty(on[f], kW, kH);
    EXPECT_FALSE(empty.has_value()) << "frame " << f << ": " << empty.value_or("");
    ASSERT_EQ(on[f].rgba.size(), off[f].rgba.size());
    int maxDiff = 0;
    size_t differ = 0;
    for (size_t i = 0; i < on[f].rgba.size(); ++i) {
      const int diff = std::abs(int(on[f].rgba[i]) - int(off[f].rgba[i]));
      maxDiff = std::max(maxDiff, diff);
      differ += diff != 0;
    }
    EXPECT_LE(maxDiff, 1) << "frame " << f << ": " << differ << " channels differ with culling on and off";
    EXPECT_EQ(drawnOff[f], int64_t(total)) << "frame " << f << ": culling off draws everything";
    const Counts& c = counts[f];
    EXPECT_EQ(drawnOn[f], int64_t(c.drawn.early + c.drawn.late)) << "frame " << f;
    EXPECT_LT(c.visible, c.inView - 10) << "frame " << f << ": the wall hides part of what is in view";
    EXPECT_GE(c.visible, 3) << "frame " << f << ": the wall, the floor and what the window shows";
    if (f > 0) {  // the first frame has no visibility yet: it draws everything in view early
      EXPECT_LT(drawnOn[f], int64_t(c.inView)) << "frame " << f << ": occlusion culls while the camera moves";
      lateDraws += c.drawn.late;
    }
  }
  EXPECT_GT(lateDraws, 0u) << "the moving view uncovers draws that the late phase draws in the same frame";
  // Frames differ from each other: the camera really moved.
  EXPECT_NE(on.front().rgba, on.back().rgba);
}

}  // namespace
}  // namespace rayster::test
