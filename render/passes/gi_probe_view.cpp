// The probes' debug view (--probe-view on, off by default; docs/techniques.md §16b): every probe of
// the grid drawn into the lit image as a small sphere at its relocated position, shaded with its
// own irradiance in the direction of the sphere's normal (E/π: a white diffuse ball lit by the
// probe), and inactive probes (inside geometry, or no surface near) drawn dark red. Drawn before
// TAA and the tonemap, so the view looks like the frame; depth-tested against the G-buffer.
#include "render/passes/passes.h"
#include "render/pipelines.h"
#include "render/settings_table.h"

namespace rayster::render {
namespace {
const PassSetting kSwitch{passSwitch("probe-view", "Effects",
                                     "Draw the irradiance probes into the image (--gi probes): spheres lit by "
                                     "each probe's irradiance, inactive probes dark red",
                                     false)};
}  // namespace

graph::ImageHandle drawProbeView(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                                 graph::ImageHandle hdr, const ProbeLookup& probes) {
  const graph::ImageHandle out =
      graph.createImage("gi-probe-view",
                        {kHdrFormat, in.size.width, in.size.height, 1,
                         VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
                        kRadianceImage);
  graph.addPass(
      "gi-probe-view",
      [&](graph::PassBuilder& b) {
        b.pipeline(in.pipelines.compute("probe_view.comp")).bind("depthTex", gb.depth).bind("hdrTex", hdr);
        b.bind("probeIrradianceTex", probes.irradiance, in.linear.handle()).bind("probeDataTex", probes.data);
        b.bind("outColor", out);
        b.kind(graph::PassKind::Utility);  // a debug view: not part of the frame's cost
      },
      [grid = probes.grid, size = in.size](graph::PassContext& pc) {
        pc.push(grid);
        vkCmdDispatch(pc.cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
      });
  return out;
}

}  // namespace rayster::render
