// Raster mode: shadow maps (one depth atlas, a tile per view) and their PCF resolve.
#include <algorithm>

#include "render/gpu_scene.h"
#include "render/passes/raster_passes.h"
#include "render/pipelines.h"
#include "render/shadow_setup.h"
#include "shaders/shared/push.h"

namespace rayster::render {

namespace {

// A shadow ray from a receiver meets the faces of an occluder that face the receiver, which the light
// sees from behind: a single-sided material's shadow-map draw keeps its back faces and culls its
// front (the ray-traced shadows ignore back faces: lib/ray_flags.glsl). The light views have no
// y flip, unlike the camera (renderer.cpp), so glTF's counter-clockwise fronts land clockwise on the
// atlas; a mirroring instance turns them once more.
void setShadowCulling(VkCommandBuffer cmd, const GpuScene::Draw& d, const gpu::InstanceRecord& instance) {
  const bool mirrored = glm::determinant(glm::mat3(instance.worldFromObject)) < 0.0f;
  vkCmdSetCullMode(cmd, d.cullsBackFaces ? VK_CULL_MODE_FRONT_BIT : VK_CULL_MODE_NONE);
  vkCmdSetFrontFace(cmd, mirrored ? VK_FRONT_FACE_COUNTER_CLOCKWISE : VK_FRONT_FACE_CLOCKWISE);
}

}  // namespace

graph::ImageHandle renderShadowAtlas(graph::RenderGraph& graph, const FrameInputs& in, const ShadowAtlas& atlas) {
  const VkExtent2D size{atlas.columns * atlas.tileSize, atlas.rows * atlas.tileSize};
  graph::ImageHandle depth =
      graph.createImage("shadow-atlas", {kDepthFormat, size.width, size.height, 1,
                                         VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
  auto describe = [](bool spheres) {
    rhi::GraphicsPipelineDesc d;
    d.vertex = spheres ? "shadow_sphere.vert" : "shadow_map.vert";
    d.fragment = spheres ? "shadow_sphere.frag" : "shadow_map.frag";
    d.depthFormat = kDepthFormat;
    d.dynamicCulling = !spheres;  // per draw: the material's sidedness, the instance's mirroring
    return d;
  };
  const rhi::Pipeline* triangleMaps = &in.pipelines.graphics("shadow-map", [&] { return describe(false); });
  const rhi::Pipeline* sphereMaps = &in.pipelines.graphics("shadow-map-spheres", [&] { return describe(true); });
  graph.addPass(
      "shadow-maps", [&](graph::PassBuilder& b) { b.write(depth, graph::Use::DepthAttachment); },
      [depth, size, triangleMaps, sphereMaps, &atlas, &in](graph::PassContext& pc) {
        VkRenderingAttachmentInfo da{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        da.imageView = pc.image(depth).view();
        da.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        da.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        da.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        da.clearValue.depthStencil = {0.0f, 0};  // reversed Z: nothing in the way
        VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
        ri.renderArea = {{0, 0}, size};
        ri.layerCount = 1;
        ri.pDepthAttachment = &da;
        vkCmdBeginRendering(pc.cmd, &ri);
        // Triangles, then analytic spheres (bounding cubes intersected exactly along the light's rays).
        for (bool spheres : {false, true}) {
          const rhi::Pipeline& pipe = spheres ? *sphereMaps : *triangleMaps;
          pc.bindWithGlobals(pipe);
          for (uint32_t v = 0; v < atlas.setup.viewCount; ++v) {
            const ShadowAtlas::Tile& t = atlas.tiles[v];
            VkViewport vp{float(t.x), float(t.y), float(atlas.tileSize), float(atlas.tileSize), 0, 1};
            VkRect2D scissor{{int32_t(t.x), int32_t(t.y)}, {atlas.tileSize, atlas.tileSize}};
            vkCmdSetViewport(pc.cmd, 0, 1, &vp);
            vkCmdSetScissor(pc.cmd, 0, 1, &scissor);
            gpu::ShadowSpherePush push{atlas.setup.views[v].clipFromWorld, 0, 0, atlas.lightRays[v]};
            for (const GpuScene::Draw& d : in.scene.draws) {
              if (d.spheres != spheres || !d.castsShadows) continue;  // lights' visible shapes cast nothing
              if (!spheres) setShadowCulling(pc.cmd, d, in.scene.instanceRecords[d.instance]);
              push.instance = d.instance;
              push.geometry = d.geometry;
              if (spheres)
                pipe.push(pc.cmd, push);
              else
                pipe.push(pc.cmd, gpu::ShadowMapPush{push.clipFromWorld, push.instance, push.geometry});
              vkCmdDraw(pc.cmd, spheres ? 36 : d.count, spheres ? d.count : 1, 0, 0);
            }
          }
        }
        vkCmdEndRendering(pc.cmd);
      });
  return depth;
}

graph::ImageHandle resolveShadows(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                                  graph::ImageHandle atlas, const rhi::Buffer& setup, uint32_t lights) {
  graph::ImageHandle visibility = graph.createImage(
      "shadow-visibility",
      {kVisibilityFormat, in.size.width, in.size.height, std::max(lights, 1u),
       VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, true});
  graph.addPass(
      "shadow-resolve",
      [&](graph::PassBuilder& b) {
        b.pipeline(in.pipelines.compute("shadow_resolve.comp"));
        b.bind("depthTex", gb.depth).bind("normalTex", gb.normals).bind("atlasTex", atlas);
        b.bind("ShadowBlock", setup).bind("outVisibility", visibility);
      },
      [size = in.size](graph::PassContext& pc) {
        vkCmdDispatch(pc.cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
      });
  return visibility;
}

}  // namespace rayster::render
