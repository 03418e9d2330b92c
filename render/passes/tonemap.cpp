// Pass 8: tonemap and output, and the copy of results back to the host.
#include "render/passes/passes.h"
#include "render/pipelines.h"
#include "shaders/shared/push.h"

namespace rayster::render {

graph::ImageHandle tonemap(graph::RenderGraph& graph, const FrameInputs& in, graph::ImageHandle hdr,
                           const ToneSettings& tone) {
  graph::ImageHandle ldr = graph.createImage("ldr", {kLdrFormat, in.size.width, in.size.height, 1,
                                                     VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
  graph.addPass(
      "tonemap",
      [&](graph::PassBuilder& b) {
        b.pipeline(in.pipelines.compute("tonemap.comp")).bind("hdrTex", hdr).bind("outLdr", ldr);
      },
      [tone, size = in.size](graph::PassContext& pc) {
        pc.push(gpu::TonemapPush{{size.width, size.height}, tone.seed, uint32_t(tone.op), tone.dither ? 1.0f : 0.0f});
        vkCmdDispatch(pc.cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
      });
  return ldr;
}

void readback(graph::RenderGraph& graph, graph::ImageHandle image, graph::BufferHandle buffer) {
  graph.addPass(
      "readback",
      [&](graph::PassBuilder& b) {
        b.read(image, graph::Use::TransferSrc);
        b.write(buffer, graph::Use::TransferDst);
        b.kind(graph::PassKind::Readback);
      },
      [image, buffer](graph::PassContext& pc) {
        const rhi::Image& img = pc.image(image);
        VkBufferImageCopy region{};
        region.imageSubresource = {img.aspect(), 0, 0, img.desc().layers};
        region.imageExtent = {img.desc().width, img.desc().height, 1};
        vkCmdCopyImageToBuffer(pc.cmd, img.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, pc.buffer(buffer).handle(),
                               1, &region);
      });
  makeHostVisible(graph, "host-visible", buffer);
}

void makeHostVisible(graph::RenderGraph& graph, const char* name, graph::BufferHandle buffer) {
  graph.addPass(
      name,
      [&](graph::PassBuilder& b) {
        b.read(buffer, graph::Use::HostRead);
        b.sideEffect();
        b.kind(graph::PassKind::Readback);
      },
      [](graph::PassContext&) {});
}

}  // namespace rayster::render
