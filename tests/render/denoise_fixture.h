#pragma once
// Fixture of tests/render/test_denoise.cpp: a Vulkan context with validation, the denoise
// pipelines, a graph per frame with uploads from and downloads to the CPU, and synthetic inputs.
#include <cmath>
#include <cstring>
#include <deque>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/half.h"
#include "graph/graph.h"
#include "graph/history.h"
#include "render/passes/denoise.h"
#include "render/passes/passes.h"
#include "rhi/commands.h"
#include "rhi/context.h"
#include "rhi/memory.h"
#include "tests/render/denoise_reference.h"

namespace rayster::render::denoise_test {

using test::ref::vec2;
using test::ref::vec3;
using test::ref::vec4;

constexpr int kW = 21, kH = 15, kLights = 2;  // not multiples of the 8×8 workgroups
constexpr float kNear = 0.1f, kFar = 100.0f;
constexpr VkExtent2D kSize{kW, kH};
constexpr size_t kPixels = size_t(kW) * kH;

inline float reversedDepth(float z) { return kNear * (kFar - z) / (z * (kFar - kNear)); }

// Row 0 is sky. Left (x < 8): a sloped plane, id 1, tilted normal. Right: a plane facing the
// camera at z = 5, id 2 (or id 1 and the left plane's normal with `sameIdAndNormal`, so only the
// depth weight separates them); its bottom rows are a mirror (roughness 0), the rest roughness 0.5.
// `shift` moves the boundary between the planes (a disocclusion between frames).
inline test::ref::GBufferCpu makeGBuffer(int shift = 0, bool sameIdAndNormal = false, bool flat = false) {
  test::ref::GBufferCpu g;
  g.w = kW, g.h = kH;
  g.depth.resize(kPixels), g.normals.resize(kPixels * 4), g.id.resize(kPixels), g.material.resize(kPixels * 4);
  const vec3 left = flat ? vec3(0, 0, 1) : glm::normalize(vec3(0.2f, 0.1f, 1.0f)), right(0, 0, 1);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const size_t i = size_t(y) * kW + x;
      const bool isLeft = x < 8 + shift;
      if (y == 0) {
        g.id[i] = gpu::kBackgroundId, g.depth[i] = 0.0f;
      } else {
        g.id[i] = isLeft || sameIdAndNormal ? 1u : 2u;
        g.depth[i] = reversedDepth(isLeft ? (flat ? 2.0f : 2.0f + 0.1f * x + 0.05f * y) : 5.0f);
      }
      vec2 oct = test::ref::octEncode(isLeft || sameIdAndNormal ? left : right);
      g.normals[i * 4 + 0] = int16_t(std::lround(oct.x * 32767.0f));
      g.normals[i * 4 + 1] = int16_t(std::lround(oct.y * 32767.0f));
      g.material[i * 4] = !isLeft && y >= 12 ? 0 : 128;
    }
  return g;
}

inline std::vector<float> roughness(const test::ref::GBufferCpu& g) {
  std::vector<float> r(kPixels);
  for (size_t i = 0; i < kPixels; ++i) r[i] = g.material[i * 4] / 255.0f;
  return r;
}

// Values after a round trip through half floats (what the GPU sees in RG16F / RGBA16F inputs).
inline float viaHalf(float v) { return halfToFloat(floatToHalf(v)); }

class Denoise : public ::testing::Test {
 protected:
  void SetUp() override {
    auto created = rhi::Context::create({/*validation*/ true, /*requireRayTracing*/ false, ""});
    if (!created) GTEST_SKIP() << "no Vulkan device: " << created.error().message;
    ctx_ = std::move(created.value());
    pipes_ = std::make_unique<rhi::PipelineLibrary>(*ctx_, VK_NULL_HANDLE);
    sampler_ = rhi::Sampler(*ctx_, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    commands_ = std::make_unique<rhi::CommandList>(*ctx_);
  }
  void TearDown() override {
    if (!ctx_) return;
    ctx_->waitIdle();
    histories_.clear();
    pool_ = {};
    commands_.reset();
    pipes_.reset();
    sampler_ = {};
    ctx_->collectGarbage();
    EXPECT_EQ(ctx_->validationErrors(), 0u) << "validation errors during the test";
    ctx_.reset();
  }

  DenoiseInputs inputs() const { return {*pipes_, sampler_.handle(), kSize}; }

 public:
  // One graph: uploads from the CPU, the passes under test, downloads to the CPU.
  class Frame {
   public:
    // Frames of one test follow each other: each reads the histories (graph/history.h) the last wrote.
    explicit Frame(Denoise& t) : graph(t.ctx_.get(), &t.pool_, &t.histories_), t_(t) {
      t.histories_.beginFrame(t.frames_, false);
    }
    graph::RenderGraph graph;

    graph::ImageHandle upload(const std::string& name, VkFormat format, uint32_t layers, const void* data,
                              size_t bytes) {
      rhi::Buffer& staging =
          buffers_.emplace_back(*t_.ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, rhi::MemoryUsage::Upload, "staging");
      std::memcpy(staging.mapped(), data, bytes);
      graph::BufferHandle src = graph.importBuffer(name + "-staging", &staging, &states_.emplace_back());
      graph::ImageHandle image = graph.createImage(
          name,
          {format, kW, kH, layers,
           VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, layers > 1});
      graph.addPass(
          "upload",
          [&](graph::PassBuilder& b) {
            b.read(src, graph::Use::TransferSrc);
            b.write(image, graph::Use::TransferDst);
          },
          [src, image, layers](graph::PassContext& pc) {
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, layers};
            region.imageExtent = {kW, kH, 1};
            vkCmdCopyBufferToImage(pc.cmd, pc.buffer(src).handle(), pc.image(image).handle(),
                                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
          });
      return image;
    }
    template <class T>
    graph::ImageHandle upload(const std::string& name, VkFormat format, uint32_t layers, const std::vector<T>& v) {
      return upload(name, format, layers, v.data(), v.size() * sizeof(T));
    }
    graph::ImageHandle uploadHalves(const std::string& name, VkFormat format, uint32_t layers,
                                    const std::vector<float>& v) {
      std::vector<uint16_t> h(v.size());
      for (size_t i = 0; i < v.size(); ++i) h[i] = floatToHalf(v[i]);
      return upload(name, format, layers, h);
    }
    // G-buffer → surface image (through writeSurface).
    graph::ImageHandle surface(const std::string& name, const test::ref::GBufferCpu& g, graph::ImageHandle out = {}) {
      auto depth = upload(name + "-depth", VK_FORMAT_R32_SFLOAT, 1, g.depth);
      auto normals = upload(name + "-normals", VK_FORMAT_R16G16B16A16_SNORM, 1, g.normals);
      auto id = upload(name + "-id", VK_FORMAT_R32_UINT, 1, g.id);
      auto material = upload(name + "-material", VK_FORMAT_R8G8B8A8_UNORM, 1, g.material);
      if (!out.valid()) out = graph.createImage(name, surfaceDesc(kSize));
      return writeSurface(graph, t_.inputs(), depth, normals, id, material, out, kNear, kFar);
    }
    // Filled by run(): the image's bytes, every layer.
    std::vector<uint8_t>& download(graph::ImageHandle image) {
      const rhi::ImageDesc& d = graph.imageDesc(image);
      const size_t bytes = size_t(d.width) * d.height * d.layers * texelBytes(d.format);
      rhi::Buffer& buffer = buffers_.emplace_back(*t_.ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                  rhi::MemoryUsage::Readback, "download");
      readback(graph, image, graph.importBuffer("download", &buffer, &states_.emplace_back()));
      downloads_.push_back({&buffer, std::make_unique<std::vector<uint8_t>>(bytes)});
      return *downloads_.back().second;
    }
    void run() {
      VkCommandBuffer cmd = t_.commands_->begin();
      graph.execute(cmd, nullptr);
      t_.ctx_->wait(t_.commands_->submit());
      t_.histories_.endFrame();
      ++t_.frames_;
      for (auto& [buffer, bytes] : downloads_) std::memcpy(bytes->data(), buffer->mapped(), bytes->size());
    }

   private:
    static uint32_t texelBytes(VkFormat f) {
      switch (f) {
        case VK_FORMAT_R16_SFLOAT:
          return 2;
        case VK_FORMAT_R32_SFLOAT:
        case VK_FORMAT_R8G8B8A8_UNORM:
          return 4;
        case VK_FORMAT_R16G16B16A16_SFLOAT:
        case VK_FORMAT_R32G32_SFLOAT:
        case VK_FORMAT_R32G32_UINT:
          return 8;
        default:
          return 16;
      }
    }
    Denoise& t_;
    std::deque<rhi::Buffer> buffers_;
    std::deque<graph::ResourceState> states_;
    std::vector<std::pair<rhi::Buffer*, std::unique_ptr<std::vector<uint8_t>>>> downloads_;
  };

 protected:
  std::unique_ptr<rhi::Context> ctx_;
  std::unique_ptr<rhi::PipelineLibrary> pipes_;
  rhi::Sampler sampler_;
  std::unique_ptr<rhi::CommandList> commands_;
  graph::TransientPool pool_;
  graph::HistoryStore histories_;
  uint32_t frames_ = 0;
};

// ---- decoding downloads ----

inline std::vector<test::ref::Surf> surfacesOf(const std::vector<uint8_t>& bytes) {
  return test::ref::decodeSurfaces(reinterpret_cast<const uint32_t*>(bytes.data()), kW, kH);
}
inline std::vector<float> floatsOf(const std::vector<uint8_t>& bytes) {
  std::vector<float> v(bytes.size() / 4);
  std::memcpy(v.data(), bytes.data(), bytes.size());
  return v;
}
inline std::vector<float> halvesOf(const std::vector<uint8_t>& bytes) {
  std::vector<float> v(bytes.size() / 2);
  for (size_t i = 0; i < v.size(); ++i) v[i] = halfToFloat(reinterpret_cast<const uint16_t*>(bytes.data())[i]);
  return v;
}
inline std::vector<vec4> vec4sOf(const std::vector<float>& f) {
  std::vector<vec4> v(f.size() / 4);
  for (size_t i = 0; i < v.size(); ++i) v[i] = vec4(f[i * 4], f[i * 4 + 1], f[i * 4 + 2], f[i * 4 + 3]);
  return v;
}
inline std::vector<float> flatten(const std::vector<vec4>& v) {
  std::vector<float> f;
  for (const vec4& x : v) f.insert(f.end(), {x.x, x.y, x.z, x.w});
  return f;
}
inline std::vector<float> flatten(const std::vector<vec2>& v) {
  std::vector<float> f;
  for (const vec2& x : v) f.insert(f.end(), {x.x, x.y});
  return f;
}

inline void expectNear(const std::vector<float>& gpu, const std::vector<float>& cpu, float tolerance,
                       const char* what) {
  ASSERT_EQ(gpu.size(), cpu.size()) << what;
  int bad = 0;
  for (size_t i = 0; i < gpu.size(); ++i) {
    ASSERT_TRUE(std::isfinite(gpu[i])) << what << " [" << i << "] = " << gpu[i];
    if (std::abs(gpu[i] - cpu[i]) > tolerance * (1.0f + std::abs(cpu[i])) && ++bad <= 5)
      ADD_FAILURE() << what << " [" << i << "]: gpu " << gpu[i] << ", cpu " << cpu[i];
  }
}

inline std::vector<float> noise(size_t n, uint32_t seed, float lo = 0.0f, float hi = 1.0f) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> d(lo, hi);
  std::vector<float> v(n);
  for (float& x : v) x = d(rng);
  return v;
}
// Radiance noise, exactly representable in half floats (as the raw RGBA16F input holds it).
inline std::vector<vec4> radianceNoise(uint32_t seed, float scale = 2.0f) {
  std::vector<float> f = noise(kPixels * 4, seed, 0.0f, scale);
  for (float& x : f) x = viaHalf(x);
  return vec4sOf(f);
}
inline std::vector<float> visibilityNoise(uint32_t seed) {
  std::vector<float> f = noise(kPixels * kLights, seed);
  for (float& x : f) x = viaHalf(x);
  return f;
}
// A fractional motion, exact in half floats: (+0.25, −0.5) pixels at 16 px.
inline std::vector<vec2> fractionalMotion() { return std::vector<vec2>(kPixels, vec2(1.0f / 64.0f, -1.0f / 32.0f)); }
inline std::vector<float> motionFloats(const std::vector<vec2>& m) {
  std::vector<float> f;
  for (vec2 v : m) f.insert(f.end(), {v.x, v.y});
  return f;
}

}  // namespace rayster::render::denoise_test
