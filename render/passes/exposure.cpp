// Auto exposure's meter: the frame's luminance histogram, for the host (render/exposure.h).
#include "shaders/shared/exposure.h"
#include "render/passes/passes.h"
#include "rhi/pipeline_library.h"

namespace rayster::render {

void meterExposure(graph::RenderGraph& graph, const FrameInputs& in, graph::ImageHandle hdr, const GBuffer& gb,
                   float exposure, graph::BufferHandle histogram, graph::BufferHandle readback) {
  graph.addPass(
      "exposure-clear",
      [&](graph::PassBuilder& b) {
        b.write(histogram, graph::Use::TransferDst);
        b.kind(graph::PassKind::Utility);
      },
      [histogram](graph::PassContext& pc) {
        vkCmdFillBuffer(pc.cmd, pc.buffer(histogram).handle(), 0, VK_WHOLE_SIZE, 0u);
      });
  graph.addPass(
      "exposure-histogram",
      [&](graph::PassBuilder& b) {
        b.pipeline(in.pipelines.compute("exposure_histogram.comp")).bind("hdrTex", hdr);
        b.bind("depthTex", gb.depth).bind("albedoTex", gb.albedo).bind("Histogram", histogram);
      },
      [size = in.size, exposure](graph::PassContext& pc) {
        pc.push(gpu::ExposurePush{{size.width, size.height}, 1.0f / exposure, 0u});
        vkCmdDispatch(pc.cmd, (size.width + 15) / 16, (size.height + 15) / 16, 1);
      });
  graph.addPass(
      "exposure-readback",
      [&](graph::PassBuilder& b) {
        b.read(histogram, graph::Use::TransferSrc);
        b.write(readback, graph::Use::TransferDst);
        b.kind(graph::PassKind::Readback);
      },
      [histogram, readback](graph::PassContext& pc) {
        const VkBufferCopy all{0, 0, gpu::kExposureHistograms * gpu::kExposureBins * sizeof(uint32_t)};
        vkCmdCopyBuffer(pc.cmd, pc.buffer(histogram).handle(), pc.buffer(readback).handle(), 1, &all);
      });
  makeHostVisible(graph, "host-visible-exposure", readback);
}

}  // namespace rayster::render
