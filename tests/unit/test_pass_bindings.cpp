// Passes bind by name (docs/architecture.md §4): descriptor layouts come from the SPIR-V
// (rhi/spirv_reflect.h), one PassBuilder::bind call records the access and the descriptor, push
// constants are the shared structs of shaders/shared/, and pipelines are created on first use.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "graph/graph.h"
#include "rhi/context.h"
#include "rhi/pipeline_library.h"
#include "rhi/spirv_reflect.h"
#include "shaders/embedded.h"
#include "shaders/shared/denoise.h"
#include "shaders/shared/push.h"

namespace rayster {
namespace {

rhi::ShaderInterface reflect(const char* shader, VkShaderStageFlagBits stage) {
  std::string error;
  auto iface = rhi::reflectSpirv(shaders::get(shader), stage, &error);
  EXPECT_TRUE(iface.has_value()) << shader << ": " << error;
  return iface.value_or(rhi::ShaderInterface{});
}

TEST(SpirvReflect, LightingDeclaresItsBindingsByName) {
  const rhi::ShaderInterface l = reflect("lighting.comp", VK_SHADER_STAGE_COMPUTE_BIT);
  const rhi::ShaderBinding* frame = l.find("FrameBlock");  // an anonymous block: its type's name
  ASSERT_NE(frame, nullptr);
  EXPECT_EQ(frame->binding, 0u);
  EXPECT_EQ(frame->type, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  const rhi::ShaderBinding* depth = l.find("depthTex");
  ASSERT_NE(depth, nullptr);
  EXPECT_EQ(depth->binding, 1u);
  EXPECT_EQ(depth->type, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
  const rhi::ShaderBinding* out = l.find("outColor");
  ASSERT_NE(out, nullptr);
  EXPECT_EQ(out->binding, 7u);
  EXPECT_EQ(out->type, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
  EXPECT_TRUE(out->nonReadable);  // writeonly
  EXPECT_FALSE(out->nonWritable);
  EXPECT_TRUE(l.usesSet(1));  // the bindless textures
  const rhi::ShaderBinding* textures = l.at(1, 0);
  ASSERT_NE(textures, nullptr);
  EXPECT_EQ(textures->count, 0u);  // runtime-sized
  EXPECT_EQ(l.pushConstantBytes, 0u);
  // Binding numbers 0..14 of set 0, each once; the last the G-buffer's layers (an unsigned texture).
  uint32_t set0 = 0;
  for (const rhi::ShaderBinding& b : l.bindings) set0 += b.set == 0 ? 1u : 0u;
  EXPECT_EQ(set0, 15u);
  const rhi::ShaderBinding* layers = l.find("layersTex");
  ASSERT_NE(layers, nullptr);
  EXPECT_EQ(layers->binding, 14u);
  EXPECT_EQ(layers->type, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
}

TEST(SpirvReflect, RayTracingStagesAndReadWriteImages) {
  const rhi::ShaderInterface ao = reflect("ao.rgen", VK_SHADER_STAGE_RAYGEN_BIT_KHR);
  const rhi::ShaderBinding* tlas = ao.find("tlas");
  ASSERT_NE(tlas, nullptr);
  EXPECT_EQ(tlas->type, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR);
  EXPECT_EQ(tlas->stages, VkShaderStageFlags(VK_SHADER_STAGE_RAYGEN_BIT_KHR));
  const rhi::ShaderInterface fill = reflect("specular_fill.comp", VK_SHADER_STAGE_COMPUTE_BIT);
  const rhi::ShaderBinding* inPlace = fill.find("specular");  // neither readonly nor writeonly
  ASSERT_NE(inPlace, nullptr);
  EXPECT_FALSE(inPlace->nonReadable);
  EXPECT_FALSE(inPlace->nonWritable);
  const rhi::ShaderInterface pt = reflect("pathtrace.rgen", VK_SHADER_STAGE_RAYGEN_BIT_KHR);
  ASSERT_NE(pt.find("prevMean"), nullptr);
  EXPECT_TRUE(pt.find("prevMean")->nonWritable);  // readonly
}

// Every push-constant block is one of the shared structs: the SPIR-V's block is as large as the
// struct the pass pushes (Pipeline::pushConstants refuses any other size).
TEST(SpirvReflect, PushBlocksAreTheSharedStructs) {
  struct Case {
    const char* shader;
    VkShaderStageFlagBits stage;
    uint32_t bytes;
  };
  const Case cases[] = {
      {"taa.comp", VK_SHADER_STAGE_COMPUTE_BIT, sizeof(gpu::TaaPush)},
      {"tonemap.comp", VK_SHADER_STAGE_COMPUTE_BIT, sizeof(gpu::TonemapPush)},
      {"raster_constants.comp", VK_SHADER_STAGE_COMPUTE_BIT, sizeof(gpu::SizePush)},
      {"gbuffer.vert", VK_SHADER_STAGE_VERTEX_BIT, sizeof(gpu::GBufferDrawPush)},
      {"gbuffer_sphere.vert", VK_SHADER_STAGE_VERTEX_BIT, sizeof(gpu::GBufferDrawPush)},
      {"shadow_map.vert", VK_SHADER_STAGE_VERTEX_BIT, sizeof(gpu::ShadowMapPush)},
      {"shadow_sphere.frag", VK_SHADER_STAGE_FRAGMENT_BIT, sizeof(gpu::ShadowSpherePush)},
      {"cull.comp", VK_SHADER_STAGE_COMPUTE_BIT, sizeof(gpu::CullPush)},
      {"deform.comp", VK_SHADER_STAGE_COMPUTE_BIT, sizeof(gpu::DeformPush)},
      {"hiz.comp", VK_SHADER_STAGE_COMPUTE_BIT, sizeof(gpu::HizPush)},
      {"surface.comp", VK_SHADER_STAGE_COMPUTE_BIT, sizeof(gpu::SurfacePush)},
      {"shadow_temporal.comp", VK_SHADER_STAGE_COMPUTE_BIT, sizeof(gpu::TemporalPush)},
      {"svgf_atrous.comp", VK_SHADER_STAGE_COMPUTE_BIT, sizeof(gpu::AtrousPush)},
      {"lighting.comp", VK_SHADER_STAGE_COMPUTE_BIT, 0},
  };
  for (const Case& c : cases) EXPECT_EQ(reflect(c.shader, c.stage).pushConstantBytes, c.bytes) << c.shader;
}

TEST(SpirvReflect, RefusesWordsThatAreNotSpirv) {
  std::string error;
  const std::vector<uint32_t> words = {0x12345678u, 0, 0, 0, 0, 0};
  EXPECT_FALSE(rhi::reflectSpirv(words, VK_SHADER_STAGE_COMPUTE_BIT, &error).has_value());
  EXPECT_NE(error.find("not a SPIR-V module"), std::string::npos) << error;
  // A module cut in the middle of an instruction.
  auto taa = shaders::get("taa.comp");
  std::vector<uint32_t> cut(taa.begin(), taa.begin() + 7);
  cut[5] = (50u << 16) | 5u;  // an OpName claiming 50 words
  EXPECT_FALSE(rhi::reflectSpirv(cut, VK_SHADER_STAGE_COMPUTE_BIT, &error).has_value());
  EXPECT_NE(error.find("truncated"), std::string::npos) << error;
}

TEST(SpirvReflect, MergeRefusesOneBindingOfTwoKinds) {
  rhi::ShaderInterface a = reflect("tonemap.comp", VK_SHADER_STAGE_COMPUTE_BIT);  // binding 2: storage image
  rhi::ShaderInterface b = reflect("taa.comp", VK_SHADER_STAGE_COMPUTE_BIT);      // binding 2: sampled depth
  std::string error;
  EXPECT_FALSE(rhi::mergeInterface(a, b, &error));
  EXPECT_NE(error.find("binding 2"), std::string::npos) << error;
  // The same shader as two stages merges into one binding list with both stages.
  rhi::ShaderInterface vs = reflect("shadow_sphere.vert", VK_SHADER_STAGE_VERTEX_BIT);
  EXPECT_TRUE(rhi::mergeInterface(vs, reflect("shadow_sphere.frag", VK_SHADER_STAGE_FRAGMENT_BIT), &error)) << error;
  EXPECT_EQ(vs.stages, VkShaderStageFlags(VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT));
  EXPECT_EQ(vs.pushConstantBytes, sizeof(gpu::ShadowSpherePush));
}

class PassBindings : public ::testing::Test {
 protected:
  void SetUp() override {
    auto created = rhi::Context::create({/*validation*/ true, /*requireRayTracing*/ false, ""});
    if (!created) GTEST_SKIP() << "no Vulkan device: " << created.error().message;
    ctx_ = std::move(created.value());
  }
  void TearDown() override {
    if (!ctx_) return;
    ctx_->waitIdle();
    EXPECT_EQ(ctx_->validationErrors(), 0u);
  }
  static rhi::ImageDesc desc(VkFormat format) {
    return {format, 16, 16, 1, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT};
  }
  std::unique_ptr<rhi::Context> ctx_;
};

TEST_F(PassBindings, PipelinesAreCreatedOnFirstUseAndKeptByName) {
  rhi::PipelineLibrary lib(*ctx_, VK_NULL_HANDLE);
  EXPECT_EQ(lib.size(), 0u);
  const rhi::Pipeline& a = lib.compute("tonemap.comp");
  const rhi::Pipeline& b = lib.compute("tonemap.comp");
  EXPECT_EQ(&a, &b);
  EXPECT_EQ(lib.size(), 1u);
  EXPECT_TRUE(lib.contains("tonemap.comp"));
  EXPECT_FALSE(lib.contains("taa.comp"));
  EXPECT_EQ(a.interface().pushConstantBytes, sizeof(gpu::TonemapPush));
  lib.clear();
  EXPECT_EQ(lib.size(), 0u);
}

// One bind() per descriptor: the graph derives the barrier of each from what the GLSL declares.
TEST_F(PassBindings, EachBindRecordsTheAccessItsDescriptorImplies) {
  rhi::PipelineLibrary lib(*ctx_, VK_NULL_HANDLE);
  rhi::Sampler nearest(*ctx_, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  graph::TransientPool pool;
  graph::RenderGraph graph(ctx_.get(), &pool);
  graph.setGlobals({VK_NULL_HANDLE, nearest.handle(), {}});
  const graph::ImageHandle hdr = graph.createImage("hdr", desc(VK_FORMAT_R16G16B16A16_SFLOAT));
  const graph::ImageHandle ldr = graph.createImage("ldr", desc(VK_FORMAT_R8G8B8A8_UNORM));
  graph.addPass(
      "fill", [&](graph::PassBuilder& b) { b.write(hdr, graph::Use::StorageWriteCompute); },
      [](graph::PassContext&) {});
  graph.addPass(
      "tonemap",
      [&](graph::PassBuilder& b) {
        b.pipeline(lib.compute("tonemap.comp")).bind("hdrTex", hdr).bind("outLdr", ldr);
        b.sideEffect();
      },
      [](graph::PassContext&) {});
  const std::vector<graph::PlannedPass> plan = graph.compile();
  ASSERT_EQ(plan.size(), 2u);
  bool sampled = false, written = false;
  for (const graph::PlannedBarrier& pb : plan[1].barriers) {
    if (pb.resource == hdr.id) {
      sampled = pb.barrier.newLayout == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL &&
                (pb.barrier.dstAccess & VK_ACCESS_2_SHADER_SAMPLED_READ_BIT) != 0 &&
                (pb.barrier.srcAccess & VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT) != 0;
    }
    if (pb.resource == ldr.id) written = pb.barrier.newLayout == VK_IMAGE_LAYOUT_GENERAL;
  }
  EXPECT_TRUE(sampled) << "hdrTex (sampler2D) must be read after the write of 'fill'";
  EXPECT_TRUE(written) << "outLdr (writeonly image2D) must be in GENERAL for its write";
}

using PassBindingsDeathTest = PassBindings;

TEST_F(PassBindingsDeathTest, AnUnboundDescriptorIsRefusedWithItsName) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  auto record = [&](bool bindAll, const char* name) {
    rhi::PipelineLibrary lib(*ctx_, VK_NULL_HANDLE);
    rhi::Sampler nearest(*ctx_, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    graph::RenderGraph graph(nullptr, nullptr);
    graph.setGlobals({VK_NULL_HANDLE, nearest.handle(), {}});
    const graph::ImageHandle hdr = graph.createImage("hdr", desc(VK_FORMAT_R16G16B16A16_SFLOAT));
    graph.addPass(
        "tonemap",
        [&](graph::PassBuilder& b) {
          b.pipeline(lib.compute("tonemap.comp")).bind(name, hdr);
          if (bindAll) b.bind("outLdr", hdr);
        },
        [](graph::PassContext&) {});
  };
  EXPECT_DEATH(record(false, "hdrTex"), "pass 'tonemap', descriptor 'outLdr': declared by the shaders but not bound");
  // A misspelt name binds nothing, so the descriptor it meant is reported unbound.
  EXPECT_DEATH(record(true, "hdrTexture"),
               "pass 'tonemap', descriptor 'hdrTex': declared by the shaders but not bound");
}

}  // namespace
}  // namespace rayster
