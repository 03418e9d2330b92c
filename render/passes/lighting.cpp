// Pass 7: deferred lighting in compute.
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

graph::ImageHandle shadeLighting(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                                 const LightingInputs& inputs, const std::string& name) {
  const auto [visibility, specular, ao, indirect, direct, indirectSpecular] = inputs;
  // Without many-light direct light the binding still needs an image; the shader does not read it.
  const graph::ImageHandle directOrUnused = direct.valid() ? direct : specular;
  graph::ImageHandle hdr =
      graph.createImage(name == "lighting" ? "hdr" : name + "-hdr",
                        {kHdrFormat, in.size.width, in.size.height, 1,
                         VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
                        kRadianceImage);
  graph.addPass(
      name,
      [&](graph::PassBuilder& b) {
        b.pipeline(in.pipelines.compute("lighting.comp"));
        bindSurface(b, gb);
        b.bind("visibilityTex", visibility).bind("specularTex", specular).bind("aoTex", ao);
        b.bind("indirectTex", indirect).bind("directTex", directOrUnused).bind("outColor", hdr);
        b.bind("indirectSpecularTex", indirectSpecular.valid() ? indirectSpecular : indirect);
      },
      [size = in.size](graph::PassContext& pc) {
        vkCmdDispatch(pc.cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
      });
  return hdr;
}

}  // namespace rayster::render
