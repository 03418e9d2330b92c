// Pass 6a: ray-traced ambient occlusion from the G-buffer (one layer of R16F, 1 sample per pixel, or
// at --ao-rate half one per checkerboard pair and frame, "rt-ao-fill" filling the other).
#include "render/passes/passes.h"
#include "render/pipelines.h"
#include "render/settings_table.h"

namespace rayster::render {
namespace {
const PassSetting kRate{
    passChoice("ao-rate", "Effects",
               "Pixels AO traces per frame: half (a checkerboard alternating with the frame, the other half the mean "
               "of its traced neighbours on the same surface) or full",
               {"full", "half"}, "half")};
}  // namespace

bool aoHalfRate(const RenderSettings& settings) { return passSettingText(settings, "ao-rate") == "half"; }

VkExtent2D aoLaunchSize(VkExtent2D size, bool half) { return {half ? (size.width + 1) / 2 : size.width, size.height}; }

// AO rays are shadow rays of another length: the shadow pass's miss and hit groups.
const rhi::RayTracingPipeline& aoPipeline(rhi::PipelineLibrary& lib) {
  return lib.rayTracing("ao.rgen", [] {
    rhi::RayTracingPipelineDesc d;
    d.raygen = "ao.rgen";
    d.miss = {"shadow.rmiss"};
    d.hitGroups = shadowHitGroups();
    return d;
  });
}

graph::ImageHandle traceAo(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb, graph::ImageHandle into,
                           bool half) {
  // A layer of an array image, so the shadow denoiser takes it unchanged: the shadow image's AO
  // layer (one denoiser run for lights and AO), or an image of its own.
  graph::ImageHandle ao = into.valid()
                              ? into
                              : graph.createImage("ao-raw", {kVisibilityFormat, in.size.width, in.size.height, 1,
                                                             VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                                                 VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                                             true});
  const rhi::RayTracingPipeline& pipe = aoPipeline(in.pipelines);
  const VkExtent2D launch = aoLaunchSize(in.size, half);
  graph.addPass(
      "rt-ao",
      [&](graph::PassBuilder& b) {
        b.pipeline(pipe)
            .bind("tlas", in.tlas)
            .bind("depthTex", gb.depth)
            .bind("normalTex", gb.normals)
            .bind("outAo", ao);
        b.rays(uint64_t(launch.width) * launch.height);  // one occlusion ray per invocation; none on the sky
      },
      [&pipe, launch](graph::PassContext& pc) { pipe.trace(pc.cmd, launch.width, launch.height); });
  if (half) {
    graph.addPass(
        "rt-ao-fill",
        [&](graph::PassBuilder& b) {
          b.pipeline(in.pipelines.compute("ao_fill.comp"))
              .bind("ao", ao)
              .bind("depthTex", gb.depth)
              .bind("normalTex", gb.normals);
        },
        [size = in.size](graph::PassContext& pc) {
          vkCmdDispatch(pc.cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
        });
  }
  return ao;
}

}  // namespace rayster::render
