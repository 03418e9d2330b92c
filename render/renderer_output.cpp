// What leaves a run (render/renderer_impl.h): readback of the final images and the AOV stages,
// and the per-pass statistics of the measured frames.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>

#include "core/half.h"
#include "core/log.h"
#include "render/renderer_impl.h"

namespace rayster::render {

namespace {

// Texel formats the AOVs come in, converted to RGBA float on the CPU.
float texel(const uint8_t* data, VkFormat format, size_t index, int channel) {
  switch (format) {
    case VK_FORMAT_R32_SFLOAT:
      return channel == 0 ? reinterpret_cast<const float*>(data)[index] : channel == 3 ? 1.0f : 0.0f;
    case VK_FORMAT_D32_SFLOAT: return channel == 3 ? 1.0f : reinterpret_cast<const float*>(data)[index];
    case VK_FORMAT_R16_SFLOAT:
      return channel == 3 ? 1.0f : halfToFloat(reinterpret_cast<const uint16_t*>(data)[index]);
    case VK_FORMAT_R16G16_SFLOAT:
      return channel < 2 ? halfToFloat(reinterpret_cast<const uint16_t*>(data)[index * 2 + channel]) : channel == 3 ? 1.0f : 0.0f;
    case VK_FORMAT_R16G16B16A16_SFLOAT: return halfToFloat(reinterpret_cast<const uint16_t*>(data)[index * 4 + channel]);
    case VK_FORMAT_R32G32B32A32_SFLOAT: return reinterpret_cast<const float*>(data)[index * 4 + channel];
    case VK_FORMAT_R16G16B16A16_SNORM:
      return std::max(-1.0f, reinterpret_cast<const int16_t*>(data)[index * 4 + channel] / 32767.0f);
    case VK_FORMAT_R8G8B8A8_UNORM: return data[index * 4 + channel] / 255.0f;
    default: return 0.0f;
  }
}

uint32_t texelBytes(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R16_SFLOAT: return 2;
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_R8G8B8A8_UNORM: return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R16G16B16A16_SNORM: return 8;
    default: return 16;
  }
}

// Stages that hold light (pre-exposed on the GPU; written out in the scene's own units).
const std::set<std::string> kRadianceStages = {"emissive",      "reflection-raw", "reflection-denoised", "indirect-raw",
                                               "indirect-denoised", "raw-direct", "raw-indirect", "raw-specular"};

} // namespace

void unexpose(ImageF& image, float exposure) {
  for (size_t i = 0; i < image.rgba.size(); ++i)
    if (i % 4 != 3) image.rgba[i] /= exposure;  // alpha is coverage (or, for emissive, the ior)
}

void summarisePasses(const std::vector<std::string>& order, const std::map<std::string, std::vector<double>>& times,
                     const std::map<std::string, graph::PassInfo>& infos, RenderOutput& out) {
  for (const std::string& name : order) {
    const std::vector<double>& samples = times.at(name);
    std::vector<double> v = samples;
    std::sort(v.begin(), v.end());
    PassStats ps{name, v[v.size() / 2], v.front(), v[std::min(v.size() - 1, size_t(std::ceil(0.95 * v.size())) - 1)],
                 uint32_t(v.size())};
    ps.samplesMs = samples;
    ps.info = infos.at(name);
    if (ps.info.kind == graph::PassKind::Frame) out.frameMedianMs += ps.medianMs;  // twins are not the frame's
    out.passes.push_back(ps);
  }
}

void Renderer::Impl::addReadbacks(graph::RenderGraph& graph, const GBuffer& gb, const FrameImages& images,
                                  graph::ImageHandle ldr) {
  Run& r = *run;
  const RenderSettings& s = r.settings;
  r.aovReadback.clear();  // only the latest readback frame's AOVs are kept
  r.aovStates.clear();
  readback(graph, ldr, graph.importBuffer("ldr-readback", &r.ldrReadback, &r.ldrState));
  readback(graph, images.hdr, graph.importBuffer("hdr-readback", &r.hdrReadback, &r.hdrState));
  // Stage → (image, layer); the visibility arrays hold one layer per shadowed light.
  std::map<std::string, std::pair<graph::ImageHandle, uint32_t>> stages = {
      {"depth", {gb.depth, 0}},
      {"normal", {gb.normals, 0}},
      {"albedo", {gb.albedo, 0}},
      {"material", {gb.material, 0}},
      {"emissive", {gb.emissive, 0}},
      {"specular", {gb.specular, 0}},  // encoded (lib/common.glsl encodeSpecular)
      {"motion", {gb.motion, 0}},
      {"shadow-raw", {images.shadowRaw, 0}},
      {"shadow-denoised", {images.shadow, 0}},
      {"reflection-raw", {images.specularRaw, 0}},
      {"reflection-denoised", {images.specular, 0}},
      {"ao-raw", {images.aoRaw, images.aoLayer}},
      {"ao-denoised", {images.ao, images.aoLayer}},
      {"indirect-raw", {images.indirectRaw, 0}},
      {"indirect-denoised", {images.indirect, 0}}};
  for (auto [name, h] : {std::pair{"raw-ao", images.rawTwins.ao}, {"raw-direct", images.rawTwins.direct},
                         {"raw-indirect", images.rawTwins.indirect}, {"raw-specular", images.rawTwins.specular}})
    if (h.valid()) stages[name] = {h, 0};
  for (uint32_t i = 0; i < shadowLights(); ++i) {
    stages["shadow" + std::to_string(i) + "-raw"] = {images.shadowRaw, i};
    stages["shadow" + std::to_string(i) + "-denoised"] = {images.shadow, i};
  }
  for (const std::string& name : s.aovs) {
    auto it = stages.find(name);
    if (name == "variance") {
      log::info("AOV 'variance' skipped: only --mode pathtrace has it");
      continue;
    }
    if (it == stages.end() && name.rfind("raw-", 0) == 0) {
      log::info("AOV '{}' skipped: only --raw-rays traces it (raw-direct: with many lights)", name);
      continue;
    }
    if (it == stages.end()) {  // a light the scene does not have
      log::info("AOV '{}' skipped: the scene has {} shadowed light(s)", name, shadowLights());
      continue;
    }
    const rhi::ImageDesc& d = graph.imageDesc(it->second.first);
    r.aovReadback.push_back(Run::AovReadback{name, d.format, it->second.second,
                                             rhi::Buffer(ctx, size_t(d.width) * d.height * texelBytes(d.format) * d.layers,
                                                         VK_BUFFER_USAGE_TRANSFER_DST_BIT, rhi::MemoryUsage::Readback,
                                                         "aov-readback"),
                                             kRadianceStages.count(name) > 0});
    r.aovStates.emplace_back();
  }
  for (size_t i = 0; i < r.aovReadback.size(); ++i)
    readback(graph, stages.at(r.aovReadback[i].name).first,
             graph.importBuffer("aov-readback", &r.aovReadback[i].buffer, &r.aovStates[i]));
}

RenderOutput Renderer::Impl::endRun() {
  Run& r = *run;
  RenderOutput out = std::move(r.out);
  readImages(out);
  summarisePasses(r.passOrder, r.passTimes, r.passInfo, out);
  run.reset();
  return out;
}


void Renderer::Impl::readImages(RenderOutput& out) {
  Run& r = *run;
  const RenderSettings& s = r.settings;
  const size_t pixels = size_t(s.width) * s.height;
  auto [ldrReadback, hdrReadback, aovReadback] = std::tie(r.ldrReadback, r.hdrReadback, r.aovReadback);
  out.scene = sceneStats();
  out.shadowLayers = shadowLights();
  out.ldr = Image8::make(int(s.width), int(s.height));
  std::memcpy(out.ldr.rgba.data(), ldrReadback.mapped(), pixels * 4);
  out.hdr = ImageF::make(int(s.width), int(s.height));
  const uint16_t* halves = static_cast<const uint16_t*>(hdrReadback.mapped());
  for (size_t i = 0; i < pixels * 4; ++i) out.hdr.rgba[i] = halfToFloat(halves[i]);
  const float exposure = std::exp2(s.exposureEv);
  unexpose(out.hdr, exposure);
  for (auto& [name, format, layer, buffer, radiance] : aovReadback) {
    ImageF img = ImageF::make(int(s.width), int(s.height));
    const uint8_t* data = static_cast<const uint8_t*>(buffer.mapped()) + size_t(layer) * pixels * texelBytes(format);
    for (size_t i = 0; i < pixels; ++i)
      for (int c = 0; c < 4; ++c) img.rgba[i * 4 + c] = texel(data, format, i, c);
    if (radiance) unexpose(img, exposure);
    out.aovs.emplace_back(name, std::move(img));
  }
}

void Renderer::Impl::copyToOutput(graph::RenderGraph& graph, graph::ImageHandle ldr) {
  const rhi::ImageDesc& d = graph.imageDesc(ldr);
  const rhi::ImageDesc desc{d.format, d.width, d.height, 1,
                            VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT};
  if (!output || !(output.desc() == desc)) {
    output = rhi::Image(ctx, desc, "output");
    outputState = {};
  }
  graph::ImageHandle dst = graph.importImage("output", &output, &outputState);
  graph.addPass(
      "output-copy",
      [&](graph::PassBuilder& b) {
        b.read(ldr, graph::Use::TransferSrc);
        b.write(dst, graph::Use::TransferDst);
        b.kind(graph::PassKind::Utility);
      },
      [ldr, dst](graph::PassContext& pc) {
        const rhi::Image& src = pc.image(ldr);
        VkImageCopy region{};
        region.srcSubresource = region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.extent = {src.desc().width, src.desc().height, 1};
        vkCmdCopyImage(pc.cmd, src.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, pc.image(dst).handle(),
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
      });
  graph.addPass(
      "output-ready",
      [&](graph::PassBuilder& b) {
        b.read(dst, graph::Use::TransferSrc);
        b.sideEffect();
        b.kind(graph::PassKind::Utility);
      },
      [](graph::PassContext&) {});
}

} // namespace rayster::render
