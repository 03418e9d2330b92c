// Pass 1 (raster producer): the scene rasterised into the G-buffer with dynamic rendering.
#include "render/gpu_scene.h"
#include "render/passes/cull.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"
#include "shaders/shared/types.h"

namespace rayster::render {

namespace {
constexpr VkImageUsageFlags kTargetUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
                                           VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
} // namespace

// Both producers create the shared targets with one description, so the transient pool hands the
// same images to either.
GBuffer createGBufferTargets(graph::RenderGraph& graph, VkExtent2D size, bool traced) {
  auto target = [&](const char* name, VkFormat format) {
    return graph.createImage(name, {format, size.width, size.height, 1, kTargetUsage});
  };
  GBuffer gb;
  gb.depth = traced ? graph.createImage("gbuffer-depth-traced",
                                        {kTracedDepthFormat, size.width, size.height, 1,
                                         VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                             VK_IMAGE_USAGE_TRANSFER_SRC_BIT})
                    : graph.createImage("gbuffer-depth",
                                        {kDepthFormat, size.width, size.height, 1,
                                         VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                             VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
  gb.normals = target("gbuffer-normals", kNormalFormat);
  gb.albedo = target("gbuffer-albedo", kAlbedoFormat);
  gb.material = target("gbuffer-material", kMaterialFormat);
  gb.emissive = target("gbuffer-emissive", kEmissiveFormat);
  gb.id = target("gbuffer-id", kIdFormat);
  gb.motion = target("gbuffer-motion", kMotionFormat);
  return gb;
}

void bindTextures(VkCommandBuffer cmd, const FrameInputs& in, VkPipelineBindPoint bindPoint, VkPipelineLayout layout) {
  vkCmdBindDescriptorSets(cmd, bindPoint, layout, 1, 1, &in.textures, 0, nullptr);
}

GBuffer rasterGBuffer(graph::RenderGraph& graph, const FrameInputs& in) {
  GBuffer gb = createGBufferTargets(graph, in.size, false);
  const CulledDraws culled = cullDraws(graph, in);
  graph.addPass(
      "gbuffer-raster",
      [&](graph::PassBuilder& b) {
        b.write(gb.depth, graph::Use::DepthAttachment);
        for (auto h : {gb.normals, gb.albedo, gb.material, gb.emissive, gb.id, gb.motion})
          b.write(h, graph::Use::ColorAttachment);
        b.read(culled.commands, graph::Use::IndirectRead);
        b.read(culled.counts, graph::Use::IndirectRead);
        b.read(culled.drawIds, graph::Use::VertexShaderRead);
      },
      [gb, culled, &in](graph::PassContext& pc) {
        constexpr int kTargets = 6;
        VkRenderingAttachmentInfo color[kTargets];
        graph::ImageHandle targets[kTargets] = {gb.normals, gb.albedo, gb.material, gb.emissive, gb.id, gb.motion};
        for (int i = 0; i < kTargets; ++i) {
          color[i] = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
          color[i].imageView = pc.image(targets[i]).view();
          color[i].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
          color[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
          color[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
          color[i].clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
        }
        color[4].clearValue.color.uint32[0] = gpu::kBackgroundId;
        VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        depth.imageView = pc.image(gb.depth).view();
        depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        depth.clearValue.depthStencil = {0.0f, 0};  // reversed Z: the far plane is 0
        VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
        ri.renderArea = {{0, 0}, in.size};
        ri.layerCount = 1;
        ri.colorAttachmentCount = kTargets;
        ri.pColorAttachments = color;
        ri.pDepthAttachment = &depth;
        vkCmdBeginRendering(pc.cmd, &ri);
        VkViewport vp{0, 0, float(in.size.width), float(in.size.height), 0, 1};
        VkRect2D scissor{{0, 0}, in.size};
        vkCmdSetViewport(pc.cmd, 0, 1, &vp);
        vkCmdSetScissor(pc.cmd, 0, 1, &scissor);
        // Triangles first, then sphere impostors (their bounding cubes, one instance per sphere):
        // the two lists cullDraws() compacted, each as long as its count says.
        const uint32_t maxDraws = in.scene.cull->drawCount;
        for (uint32_t list : {0u, 1u}) {
          const rhi::Pipeline& pipe = list == 1 ? in.pipelines.gbufferSpheres : in.pipelines.gbufferRaster;
          vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe.handle());
          rhi::DescriptorWriter().uniformBuffer(0, in.constants).push(pc.cmd, pipe);
          bindTextures(pc.cmd, in, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe.layout());
          const uint64_t push[2] = {in.scene.drawRecords.address(),
                                    pc.buffer(culled.drawIds).address() + list * maxDraws * sizeof(uint32_t)};
          vkCmdPushConstants(pc.cmd, pipe.layout(), pipe.stages(), 0, sizeof(push), push);
          vkCmdDrawIndirectCount(pc.cmd, pc.buffer(culled.commands).handle(),
                                 list * maxDraws * sizeof(VkDrawIndirectCommand), pc.buffer(culled.counts).handle(),
                                 list * sizeof(uint32_t), maxDraws, sizeof(VkDrawIndirectCommand));
        }
        vkCmdEndRendering(pc.cmd);
      });
  buildDepthPyramid(graph, in, gb.depth, culled);
  readbackCullStats(graph, in, culled);
  return gb;
}

} // namespace rayster::render
