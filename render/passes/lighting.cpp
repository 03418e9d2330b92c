// Pass 7: deferred lighting in compute.
#include "render/gpu_scene.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

graph::ImageHandle shadeLighting(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                                 const LightingInputs& inputs, const std::string& name) {
  const auto [visibility, specular, ao, indirect, direct] = inputs;
  // Without many-light direct light the binding still needs an image; the shader does not read it.
  const graph::ImageHandle directOrUnused = direct.valid() ? direct : specular;
  graph::ImageHandle hdr = graph.createImage(
      name == "lighting" ? "hdr" : name + "-hdr", {kHdrFormat, in.size.width, in.size.height, 1,
              VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
      kRadianceImage);
  graph.addPass(
      name,
      [&](graph::PassBuilder& b) {
        for (auto h : {gb.depth, gb.normals, gb.albedo, gb.material, gb.emissive, visibility, specular, ao, indirect,
                       directOrUnused, gb.specular})
          b.read(h, graph::Use::SampledCompute);
        b.write(hdr, graph::Use::StorageWriteCompute);
      },
      [gb, visibility, specular, ao, indirect, directOrUnused, hdr, &in](graph::PassContext& pc) {
        const rhi::Pipeline& pipe = in.pipelines.lighting;
        VkSampler s = in.nearest.handle();
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.handle());
        rhi::DescriptorWriter()
            .uniformBuffer(0, in.constants)
            .sampledImage(1, pc.image(gb.depth).view(), s)
            .sampledImage(2, pc.image(gb.normals).view(), s)
            .sampledImage(3, pc.image(gb.albedo).view(), s)
            .sampledImage(4, pc.image(gb.material).view(), s)
            .sampledImage(5, pc.image(gb.emissive).view(), s)
            .sampledImage(6, pc.image(visibility).view(), s)
            .storageImage(7, pc.image(hdr).view())
            .sampledImage(8, pc.image(specular).view(), s)
            .sampledImage(9, pc.image(ao).view(), s)
            .sampledImage(10, pc.image(indirect).view(), s)
            .sampledImage(11, pc.image(directOrUnused).view(), s)
            .sampledImage(12, pc.image(gb.specular).view(), s)
            .push(pc.cmd, pipe);
        bindTextures(pc.cmd, in, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.layout());
        vkCmdDispatch(pc.cmd, (in.size.width + 7) / 8, (in.size.height + 7) / 8, 1);
      });
  return hdr;
}

} // namespace rayster::render
