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
    case VK_FORMAT_D32_SFLOAT:
      return channel == 3 ? 1.0f : reinterpret_cast<const float*>(data)[index];
    case VK_FORMAT_R16_SFLOAT:
      return channel == 3 ? 1.0f : halfToFloat(reinterpret_cast<const uint16_t*>(data)[index]);
    case VK_FORMAT_R16G16_SFLOAT:
      return channel < 2    ? halfToFloat(reinterpret_cast<const uint16_t*>(data)[index * 2 + channel])
             : channel == 3 ? 1.0f
                            : 0.0f;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
      return halfToFloat(reinterpret_cast<const uint16_t*>(data)[index * 4 + channel]);
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      return reinterpret_cast<const float*>(data)[index * 4 + channel];
    case VK_FORMAT_R32G32_SFLOAT:
      return channel < 2 ? reinterpret_cast<const float*>(data)[index * 2 + channel] : channel == 3 ? 1.0f : 0.0f;
    case VK_FORMAT_R32_UINT:  // ids: the value as a float (exact below 2^24)
      return channel == 0 ? float(reinterpret_cast<const uint32_t*>(data)[index]) : channel == 3 ? 1.0f : 0.0f;
    case VK_FORMAT_R32G32_UINT:  // packed words (the denoisers' surface): each as a float
      return channel < 2    ? float(reinterpret_cast<const uint32_t*>(data)[index * 2 + channel])
             : channel == 3 ? 1.0f
                            : 0.0f;
    case VK_FORMAT_R16G16B16A16_SNORM:
      return std::max(-1.0f, reinterpret_cast<const int16_t*>(data)[index * 4 + channel] / 32767.0f);
    case VK_FORMAT_R8G8B8A8_UNORM:
      return data[index * 4 + channel] / 255.0f;
    default:
      return 0.0f;
  }
}

// 0: a format the AOVs do not read.
uint32_t texelBytes(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R16_SFLOAT:
      return 2;
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_R8G8B8A8_UNORM:
      return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R32G32_SFLOAT:
    case VK_FORMAT_R32G32_UINT:
    case VK_FORMAT_R16G16B16A16_SNORM:
      return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      return 16;
    default:
      return 0;
  }
}

}  // namespace

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

std::optional<Renderer::Impl::AovSource> Renderer::Impl::resolveAov(const graph::RenderGraph& graph, const GBuffer& gb,
                                                                    const FrameImages& images,
                                                                    const std::string& name) const {
  // The names of earlier releases (aovNames()) are aliases of the images they always meant; the
  // visibility arrays hold one layer per shadowed light.
  const std::map<std::string, std::pair<graph::ImageHandle, uint32_t>> aliases = {
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
  if (auto it = aliases.find(name); it != aliases.end() && it->second.first.valid())
    return AovSource{it->second.first, it->second.second};
  for (uint32_t i = 0; i < shadowLights(); ++i) {
    if (name == "shadow" + std::to_string(i) + "-raw") return AovSource{images.shadowRaw, i};
    if (name == "shadow" + std::to_string(i) + "-denoised") return AovSource{images.shadow, i};
  }
  // Any image of the frame by its graph name (--memory-report lists them), "NAME" or "NAME:LAYER".
  std::string image = name;
  uint32_t layer = 0;
  if (const size_t colon = name.rfind(':'); colon != std::string::npos) {
    image = name.substr(0, colon);
    char* end = nullptr;
    const unsigned long l = std::strtoul(name.c_str() + colon + 1, &end, 10);
    if (colon + 1 == name.size() || *end != '\0') return std::nullopt;
    layer = uint32_t(l);
  }
  const graph::ImageHandle h = graph.findImage(image);
  if (!h.valid() || layer >= graph.imageDesc(h).layers) return std::nullopt;
  return AovSource{h, layer};
}

std::optional<Error> Renderer::Impl::checkAovs(const graph::RenderGraph& graph, const GBuffer& gb,
                                               const FrameImages& images) const {
  for (const std::string& name : run->settings.aovs) {
    if (name == "variance" || resolveAov(graph, gb, images, name)) continue;
    const bool known = std::find(aovNames().begin(), aovNames().end(), name) != aovNames().end();
    if (known) continue;  // a name of the list this scene or these settings do not have: skipped later
    if (const std::optional<AovSource> a = resolveAov(graph, gb, images, name.substr(0, name.rfind(':'))))
      return makeError(ExitCode::BadArguments, "unknown AOV '{}': image '{}' has {} layer(s)", name,
                       name.substr(0, name.rfind(':')), graph.imageDesc(a->image).layers);
    std::string list;
    for (const std::string& n : graph.imageNames()) list += (list.empty() ? "" : ", ") + n;
    return makeError(ExitCode::BadArguments, "unknown AOV '{}': no such name or image this frame (images: {})", name,
                     list);
  }
  return std::nullopt;
}

void Renderer::Impl::addReadbacks(graph::RenderGraph& graph, const GBuffer& gb, const FrameImages& images,
                                  graph::ImageHandle ldr) {
  Run& r = *run;
  const RenderSettings& s = r.settings;
  r.aovReadback.clear();  // only the latest readback frame's AOVs are kept
  r.aovStates.clear();
  readback(graph, ldr, graph.importBuffer("ldr-readback", &r.ldrReadback, &r.ldrState));
  readback(graph, images.hdr, graph.importBuffer("hdr-readback", &r.hdrReadback, &r.hdrState));
  std::vector<graph::ImageHandle> sources;
  for (const std::string& name : s.aovs) {
    if (name == "variance") {
      log::info("AOV 'variance' skipped: only --mode pathtrace has it");
      continue;
    }
    const std::optional<AovSource> a = resolveAov(graph, gb, images, name);
    if (!a && name.rfind("raw-", 0) == 0) {
      log::info("AOV '{}' skipped: only --raw-rays traces it, for an effect that is on (raw-direct: with many lights)",
                name);
      continue;
    }
    if (!a) {  // a light the scene does not have
      log::info("AOV '{}' skipped: the scene has {} shadowed light(s)", name, shadowLights());
      continue;
    }
    const rhi::ImageDesc& d = graph.imageDesc(a->image);
    if (texelBytes(d.format) == 0) {
      log::warn("AOV '{}' skipped: its format ({}) is not one Rayster reads back", name, int(d.format));
      continue;
    }
    const rhi::Image* imported = graph.importedImage(a->image);
    if (imported && neutral.holds(*imported))
      log::info("AOV '{}': its effect records no pass this frame; the image is the constant lighting reads", name);
    r.aovReadback.push_back(
        Run::AovReadback{name, d.format, d.width, d.height, a->layer,
                         rhi::Buffer(ctx, size_t(d.width) * d.height * texelBytes(d.format) * d.layers,
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT, rhi::MemoryUsage::Readback, "aov-readback"),
                         (graph.imageTags(a->image) & kRadianceImage) != 0});
    r.aovStates.emplace_back();
    sources.push_back(a->image);
  }
  for (size_t i = 0; i < r.aovReadback.size(); ++i)
    readback(graph, sources[i], graph.importBuffer("aov-readback", &r.aovReadback[i].buffer, &r.aovStates[i]));
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
  const float exposure = this->exposure.exposure();  // of the frame read back
  out.exposure = exposure;
  out.ev100 = ev100FromExposure(exposure);
  unexpose(out.hdr, exposure);
  for (auto& [name, format, width, height, layer, buffer, radiance] : aovReadback) {
    // One texel (a neutral image) is the same everywhere: broadcast to the frame. Other images come
    // at their own size (a shadow map, a half-resolution target).
    const size_t texels = size_t(width) * height;
    const bool broadcast = texels == 1;
    ImageF img = broadcast ? ImageF::make(int(s.width), int(s.height)) : ImageF::make(int(width), int(height));
    const uint8_t* data = static_cast<const uint8_t*>(buffer.mapped()) + size_t(layer) * texels * texelBytes(format);
    for (size_t i = 0; i < img.rgba.size() / 4; ++i)
      for (int c = 0; c < 4; ++c) img.rgba[i * 4 + c] = texel(data, format, broadcast ? 0 : i, c);
    if (radiance) unexpose(img, exposure);
    out.aovs.emplace_back(name, std::move(img));
  }
}

void Renderer::Impl::copyToOutput(graph::RenderGraph& graph, graph::ImageHandle ldr) {
  const rhi::ImageDesc& d = graph.imageDesc(ldr);
  const rhi::ImageDesc desc{
      d.format, d.width, d.height, 1,
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

}  // namespace rayster::render
