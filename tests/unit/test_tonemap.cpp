// The tonemap operators (docs/techniques.md §19): the C++ mirror's curves (0 → 0, monotonic, known
// points, the PBR Neutral guarantees), and the real GPU pass against that mirror on lavapipe, with
// a constant radiance per pixel and the dither off, so the 8-bit values can be compared exactly.
#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "core/half.h"
#include "core/image_io.h"
#include "graph/graph.h"
#include "render/gpu_scene.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"
#include "render/tonemap_curves.h"
#include "rhi/commands.h"
#include "rhi/context.h"
#include "rhi/resources.h"
#include "scene/builtin.h"

namespace rayster::render {
namespace {

glm::vec3 grey(float v) { return glm::vec3(v); }

TEST(TonemapCurves, BlackStaysBlack) {
  for (Tonemapper t : {Tonemapper::Aces, Tonemapper::Neutral}) {
    const glm::vec3 c = applyTonemapper(t, glm::vec3(0.0f));
    EXPECT_EQ(c, glm::vec3(0.0f)) << tonemapperName(t);
  }
}

TEST(TonemapCurves, MonotonicAndBounded) {
  for (Tonemapper t : {Tonemapper::Aces, Tonemapper::Neutral}) {
    float previous = -1.0f;
    for (int i = 0; i <= 20000; ++i) {
      const float x = std::pow(10.0f, -4.0f + 7.0f * float(i) / 20000.0f);  // 1e-4 .. 1e3
      const glm::vec3 c = applyTonemapper(t, grey(x));
      EXPECT_GE(c.g, previous - 1e-6f) << tonemapperName(t) << " at " << x;  // float rounding near 1
      EXPECT_GE(c.g, 0.0f);
      EXPECT_LE(c.g, 1.0f);
      previous = c.g;
    }
  }
}

TEST(TonemapCurves, AcesKnownPoints) {
  // From the fit's published constants, evaluated in double precision (grey in, grey out).
  const std::pair<float, float> points[] = {{0.01f, 0.0010525f}, {0.18f, 0.105591f}, {0.5f, 0.374308f},
                                            {1.0f, 0.619115f},   {2.0f, 0.803562f},  {4.0f, 0.909014f},
                                            {16.0f, 0.989935f},  {100.0f, 1.0f}};
  for (auto [in, out] : points) EXPECT_NEAR(acesFitted(grey(in)).r, out, 2e-5f) << in;
}

TEST(TonemapCurves, NeutralSpecification) {
  // c_out = c_in − f below the compression start: the F90 = 0.04 offset above min = 0.08, and the
  // quadratic toe x − 6.25·x² below it (continuous at 0.08, where both give 0.04).
  EXPECT_FLOAT_EQ(pbrNeutral(grey(0.5f)).r, 0.46f);
  EXPECT_FLOAT_EQ(pbrNeutral(grey(0.08f)).r, 0.04f);
  EXPECT_FLOAT_EQ(pbrNeutral(grey(0.04f)).r, 0.04f - 0.04f + 6.25f * 0.04f * 0.04f);
  const glm::vec3 base(0.7f, 0.3f, 0.1f);  // every channel in [0.08, 0.8]: reproduced minus F90
  const glm::vec3 mapped = pbrNeutral(base);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mapped[c], base[c] - 0.04f, 1e-6f);
  const glm::vec3 dark(0.06f, 0.03f, 0.01f);  // min 0.01: offset 0.01 − 6.25·0.0001
  const float f = 0.01f - 6.25f * 0.01f * 0.01f;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(pbrNeutral(dark)[c], dark[c] - f, 1e-7f);
  // Peak compression: grey p = x − 0.04 ≥ Ks maps to 1 − d²/(p + d − Ks), d = 1 − Ks = 0.24.
  for (float x : {0.8f, 1.0f, 2.0f, 10.0f}) {
    const float p = x - 0.04f;
    EXPECT_NEAR(pbrNeutral(grey(x)).r, 1.0f - 0.0576f / (p + 0.24f - 0.76f), 1e-6f) << x;
  }
  // Saturated highlights keep their hue's order and move towards grey (desaturation).
  const glm::vec3 hot = pbrNeutral(glm::vec3(8.0f, 2.0f, 0.5f));
  EXPECT_GT(hot.r, hot.g);
  EXPECT_GT(hot.g, hot.b);
  EXPECT_GT(hot.b / hot.r, (0.5f - 0.04f) / (8.0f - 0.04f));
  EXPECT_LE(hot.r, 1.0f);
}

// The real tonemap pass on the device, against the mirror.
class TonemapDevice : public ::testing::Test {
 protected:
  void SetUp() override {
    auto created = rhi::Context::create({/*validation*/ true, /*requireRayTracing*/ true, ""});
    if (!created) GTEST_SKIP() << "no ray-tracing Vulkan device: " << created.error().message;
    ctx_ = std::move(created.value());
  }
  void TearDown() override {
    if (!ctx_) return;
    ctx_->waitIdle();
    ctx_->collectGarbage();
    EXPECT_EQ(ctx_->validationErrors(), 0u);
    ctx_.reset();
  }

  // Tonemaps one RGBA16F image of the given linear colours (one pixel each) × exposure, as the frame
  // stores them pre-exposed, and reads back RGBA8.
  std::vector<uint8_t> run(const std::vector<glm::vec3>& colours, Tonemapper op, float exposure) {
    auto scene = scene::makeBuiltinScene("cornell");
    EXPECT_TRUE(scene.ok());
    auto gpu = uploadScene(*ctx_, *scene);
    EXPECT_TRUE(gpu.ok());
    rhi::PipelineLibrary pipelines(*ctx_, gpu->bindless->layout());
    rhi::Sampler nearest(*ctx_, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    rhi::Sampler linear(*ctx_, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    rhi::Buffer constants(*ctx_, 256, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, rhi::MemoryUsage::Upload, "constants");
    const uint32_t w = uint32_t(colours.size()), h = 1;
    rhi::Buffer staging(*ctx_, w * 8, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, rhi::MemoryUsage::Upload, "hdr-staging");
    auto* halves = static_cast<uint16_t*>(staging.mapped());
    for (uint32_t i = 0; i < w; ++i)
      for (int c = 0; c < 4; ++c) halves[i * 4 + c] = floatToHalf(c < 3 ? colours[i][c] * exposure : 1.0f);
    rhi::Image hdrImage(*ctx_, {kHdrFormat, w, h, 1, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT},
                        "hdr-constant");
    rhi::Buffer readbackBuffer(*ctx_, w * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, rhi::MemoryUsage::Readback, "ldr");
    graph::ResourceState stagingState, hdrState, readbackState;
    graph::TransientPool transients;
    graph::RenderGraph graph(ctx_.get(), &transients);
    const graph::AccelHandle tlas = beginFrameGraph(graph, *gpu, constants, nearest);
    FrameInputs in{pipelines, *gpu, constants, nearest, linear, {w, h}, tlas};
    graph::BufferHandle src = graph.importBuffer("hdr-staging", &staging, &stagingState);
    graph::ImageHandle hdr = graph.importImage("hdr-constant", &hdrImage, &hdrState);
    graph.addPass(
        "upload",
        [&](graph::PassBuilder& b) {
          b.read(src, graph::Use::TransferSrc);
          b.write(hdr, graph::Use::TransferDst);
        },
        [src, hdr, w, h](graph::PassContext& pc) {
          VkBufferImageCopy region{};
          region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
          region.imageExtent = {w, h, 1};
          vkCmdCopyBufferToImage(pc.cmd, pc.buffer(src).handle(), pc.image(hdr).handle(),
                                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        });
    graph::ImageHandle ldr = tonemap(graph, in, hdr, {op, 0, /*dither*/ false});
    readback(graph, ldr, graph.importBuffer("ldr", &readbackBuffer, &readbackState));
    rhi::CommandList commands(*ctx_);
    graph.execute(commands.begin(), nullptr);
    ctx_->wait(commands.submit());
    const auto* bytes = static_cast<const uint8_t*>(readbackBuffer.mapped());
    return std::vector<uint8_t>(bytes, bytes + w * 4);
  }

  std::unique_ptr<rhi::Context> ctx_;
};

TEST_F(TonemapDevice, PassMatchesTheCurvesWithExactSrgb) {
  std::vector<glm::vec3> colours;
  for (int i = 0; i < 48; ++i) colours.push_back(grey(0.002f * std::pow(1.2f, float(i))));  // 0.002 .. ~10
  colours.push_back(grey(0.0f));
  colours.push_back({0.7f, 0.3f, 0.1f});
  colours.push_back({8.0f, 2.0f, 0.5f});
  colours.push_back({0.02f, 0.5f, 3.0f});
  const float exposure = 0.75f;
  for (Tonemapper op : {Tonemapper::Aces, Tonemapper::Neutral}) {
    const std::vector<uint8_t> gpuBytes = run(colours, op, exposure);
    for (size_t i = 0; i < colours.size(); ++i) {
      // The fp16 image holds the input rounded to half; mirror that.
      glm::vec3 in;
      for (int c = 0; c < 3; ++c) in[c] = halfToFloat(floatToHalf(colours[i][c] * exposure));
      const glm::vec3 display = applyTonemapper(op, in);
      for (int c = 0; c < 3; ++c) {
        const float encoded = linearToSrgb(display[c]) * 255.0f;  // exact piecewise sRGB
        const int got = gpuBytes[i * 4 + c];
        // UNORM stores round to nearest; allow one step where the value sits near a rounding edge.
        EXPECT_NEAR(got, encoded, 0.5f + 0.02f) << tonemapperName(op) << " pixel " << i << " channel " << c;
      }
      EXPECT_EQ(gpuBytes[i * 4 + 3], 255);
    }
    EXPECT_EQ(gpuBytes[48 * 4], 0) << "black must stay 0 (no lifted black)";
  }
}

}  // namespace
}  // namespace rayster::render
