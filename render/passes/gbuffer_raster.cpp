// Pass 1 (raster producer): the scene rasterised into the G-buffer with dynamic rendering.
#include "render/gpu_scene.h"
#include "render/passes/cull.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"
#include "shaders/shared/push.h"

namespace rayster::render {

namespace {
constexpr VkImageUsageFlags kTargetUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
                                           VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
}  // namespace

// Both producers create the shared targets with one description, so the transient pool hands the
// same images to either.
GBuffer createGBufferTargets(graph::RenderGraph& graph, const FrameInputs& in, bool traced,
                             graph::ImageHandle zeroLayers) {
  const VkExtent2D size = in.size;
  auto target = [&](const char* name, VkFormat format) {
    const bool light = std::string_view(name) == "gbuffer-emissive";  // emission is pre-exposed
    return graph.createImage(name, {format, size.width, size.height, 1, kTargetUsage}, light ? kRadianceImage : 0u);
  };
  GBuffer gb;
  gb.depth =
      traced ? graph.createImage("gbuffer-depth-traced", {kTracedDepthFormat, size.width, size.height, 1,
                                                          VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                                              VK_IMAGE_USAGE_TRANSFER_SRC_BIT})
             : graph.createImage("gbuffer-depth", {kDepthFormat, size.width, size.height, 1,
                                                   VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT |
                                                       VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
  gb.normals = target("gbuffer-normals", kNormalFormat);
  gb.albedo = target("gbuffer-albedo", kAlbedoFormat);
  gb.material = target("gbuffer-material", kMaterialFormat);
  gb.emissive = target("gbuffer-emissive", kEmissiveFormat);
  gb.id = target("gbuffer-id", kIdFormat);
  gb.motion = target("gbuffer-motion", kMotionFormat);
  gb.specular = target("gbuffer-specular", kSpecularFormat);
  gb.flatLayers = zeroLayers.valid() && !in.scene.layeredGBuffer;
  gb.layers = gb.flatLayers ? zeroLayers : target("gbuffer-layers", kLayersFormat);
  return gb;
}

void bindSurface(graph::PassBuilder& b, const GBuffer& gb) {
  b.bind("depthTex", gb.depth).bind("normalTex", gb.normals).bind("albedoTex", gb.albedo);
  b.bind("materialTex", gb.material).bind("emissiveTex", gb.emissive).bind("specularGbufTex", gb.specular);
  b.bind("layersTex", gb.layers);
}

namespace {

// Draws one phase's two lists (render/passes/cull.h) into the G-buffer: the early phase clears the
// targets, the late one loads them and adds what the early depth did not hide.
void drawGBuffer(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb, const CulledDraws& culled,
                 CullPhase phase) {
  const bool late = phase == CullPhase::Late;
  auto describe = [](bool spheres) {
    rhi::GraphicsPipelineDesc g;
    g.vertex = spheres ? "gbuffer_sphere.vert" : "gbuffer.vert";
    g.fragment = spheres ? "gbuffer_sphere.frag" : "gbuffer.frag";
    g.colorFormats = {kNormalFormat, kAlbedoFormat, kMaterialFormat, kEmissiveFormat,
                      kIdFormat,     kMotionFormat, kSpecularFormat, kLayersFormat};
    g.depthFormat = kDepthFormat;
    return g;
  };
  const rhi::Pipeline* triangles = &in.pipelines.graphics("gbuffer-raster", [&] { return describe(false); });
  const rhi::Pipeline* spheres = &in.pipelines.graphics("gbuffer-raster-spheres", [&] { return describe(true); });
  graph.addPass(
      late ? "gbuffer-raster-late" : "gbuffer-raster",
      [&](graph::PassBuilder& b) {
        b.write(gb.depth, graph::Use::DepthAttachment);
        for (auto h : {gb.normals, gb.albedo, gb.material, gb.emissive, gb.id, gb.motion, gb.specular})
          b.write(h, graph::Use::ColorAttachment);
        if (!gb.flatLayers) b.write(gb.layers, graph::Use::ColorAttachment);
        b.read(culled.commands, graph::Use::IndirectRead);
        b.read(culled.counts, graph::Use::IndirectRead);
        b.read(culled.drawIds, graph::Use::VertexShaderRead);
      },
      [gb, culled, late, triangles, spheres, &in](graph::PassContext& pc) {
        const VkAttachmentLoadOp load = late ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
        constexpr int kTargets = 8;  // in the order of the fragment outputs (lib/gbuffer_out.glsl)
        VkRenderingAttachmentInfo color[kTargets];
        graph::ImageHandle targets[kTargets] = {gb.normals, gb.albedo, gb.material, gb.emissive,
                                                gb.id,      gb.motion, gb.specular, gb.layers};
        for (int i = 0; i < kTargets; ++i) {
          color[i] = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
          // Flat layers: no attachment (a null view discards the fragment output, dynamic rendering).
          const bool unused = gb.flatLayers && i == kTargets - 1;
          color[i].imageView = unused ? VK_NULL_HANDLE : pc.image(targets[i]).view();
          color[i].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
          color[i].loadOp = load;
          color[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
          color[i].clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
        }
        color[4].clearValue.color.uint32[0] = gpu::kBackgroundId;
        VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        depth.imageView = pc.image(gb.depth).view();
        depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        depth.loadOp = load;
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
        // the phase's two lists, each as long as its count says.
        const uint32_t maxDraws = in.scene.cull->drawCount;
        for (uint32_t type : {0u, 1u}) {
          const uint32_t list = (late ? 2u : 0u) + type;
          const rhi::Pipeline& pipe = type == 1 ? *spheres : *triangles;
          pc.bindWithGlobals(pipe);
          pipe.push(pc.cmd,
                    gpu::GBufferDrawPush{in.scene.drawRecords.address(),
                                         pc.buffer(culled.drawIds).address() + list * maxDraws * sizeof(uint32_t)});
          vkCmdDrawIndirectCount(pc.cmd, pc.buffer(culled.commands).handle(),
                                 list * maxDraws * sizeof(VkDrawIndirectCommand), pc.buffer(culled.counts).handle(),
                                 list * sizeof(uint32_t), maxDraws, sizeof(VkDrawIndirectCommand));
        }
        vkCmdEndRendering(pc.cmd);
      });
}

}  // namespace

// Culling on: early cull, early draw (clear), depth pyramid, late cull, late draw (load). Off: one
// cull pass that keeps every draw and one draw pass, as before culling existed.
GBuffer rasterGBuffer(graph::RenderGraph& graph, const FrameInputs& in, graph::ImageHandle zeroLayers) {
  GBuffer gb = createGBufferTargets(graph, in, false, zeroLayers);
  const CulledDraws culled = cullDraws(graph, in);
  drawGBuffer(graph, in, gb, culled, CullPhase::Early);
  if (in.scene.cull->enabled) {
    buildDepthPyramid(graph, in, gb.depth, culled);
    cullLate(graph, in, culled);
    drawGBuffer(graph, in, gb, culled, CullPhase::Late);
  }
  readbackCullStats(graph, in, culled);
  return gb;
}

}  // namespace rayster::render
