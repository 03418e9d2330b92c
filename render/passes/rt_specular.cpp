// Pass 4: ray-traced reflections and refractions (the raygen bounce loop); denoised by SVGF
// (denoise_svgf.cpp). Rough glossy reflections trace half the pixels per frame in a checkerboard
// (lib/specular_weight.glsl); "rt-specular-fill" fills the other half from their neighbours, in place.
#include "render/gpu_scene.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

graph::ImageHandle traceSpecular(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb, uint32_t bounces,
                                 uint32_t lightsPerHit) {
  graph::ImageHandle out = graph.createImage(
      "specular-raw", {kRadianceFormat, in.size.width, in.size.height, 1,
                       VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
      kRadianceImage);
  graph.addPass(
      "rt-specular",
      [&](graph::PassBuilder& b) {
        for (auto h : {gb.depth, gb.normals, gb.albedo, gb.material, gb.emissive, gb.specular})
          b.read(h, graph::Use::SampledRayTracing);
        b.write(out, graph::Use::StorageWriteRayTracing);
        // Per pixel and bounce a ray and a shadow ray per light shaded at its hit: a bound, since
        // most pixels are not specular and most paths end after a bounce.
        b.rays(uint64_t(in.size.width) * in.size.height * bounces * (1u + lightsPerHit));
      },
      [gb, out, &in](graph::PassContext& pc) {
        const rhi::RayTracingPipeline& pipe = in.pipelines.specular;
        VkSampler s = in.nearest.handle();
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.handle());
        rhi::DescriptorWriter()
            .uniformBuffer(0, in.constants)
            .accelerationStructure(1, in.scene.tlas.handle())
            .sampledImage(2, pc.image(gb.depth).view(), s)
            .sampledImage(3, pc.image(gb.normals).view(), s)
            .sampledImage(4, pc.image(gb.albedo).view(), s)
            .sampledImage(5, pc.image(gb.material).view(), s)
            .storageImage(6, pc.image(out).view())
            .sampledImage(7, pc.image(gb.emissive).view(), s)
            .sampledImage(8, pc.image(gb.specular).view(), s)
            .push(pc.cmd, pipe);
        bindTextures(pc.cmd, in, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.layout());
        pipe.trace(pc.cmd, in.size.width, in.size.height);
      });
  graph.addPass(
      "rt-specular-fill",
      [&](graph::PassBuilder& b) {
        b.read(gb.depth, graph::Use::SampledCompute);
        b.read(gb.material, graph::Use::SampledCompute);
        b.write(out, graph::Use::StorageReadWriteCompute);
      },
      [gb, out, &in](graph::PassContext& pc) {
        const rhi::Pipeline& pipe = in.pipelines.specularFill;
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.handle());
        rhi::DescriptorWriter()
            .uniformBuffer(0, in.constants)
            .storageImage(1, pc.image(out).view())
            .sampledImage(2, pc.image(gb.depth).view(), in.nearest.handle())
            .sampledImage(3, pc.image(gb.material).view(), in.nearest.handle())
            .push(pc.cmd, pipe);
        vkCmdDispatch(pc.cmd, (in.size.width + 7) / 8, (in.size.height + 7) / 8, 1);
      });
  return out;
}

} // namespace rayster::render
