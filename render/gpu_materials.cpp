// Materials, samplers and textures: every image gets a full mip chain and, for colour data, an sRGB
// view; each (texture, colour-or-linear) use gets one bindless slot.
//
// KHR_materials_unlit (gpu::kMaterialUnlit) means one thing in every mode and for every ray: the
// surface emits its base colour (× base colour texture × vertex colour) as radiance and reflects
// nothing. Surface evaluation writes that colour as emission and zero albedo and specular, so the
// hybrid's lighting, shadows, reflections, AO and indirect passes, the raster mode and SSR need no
// special case: camera rays see the colour unlit and unshadowed (then exposed and tonemapped like
// everything else), and reflection, refraction and indirect rays see the same colour. In the path
// tracer it is an emitter like any emissive surface (render/gpu_emissive.cpp): it lights what is
// around it, as its colour seen in a mirror implies it must for the image to be consistent, and as
// the hybrid's indirect rays already count it. (A surface visible to camera and mirror rays but not
// to diffuse ones would need a per-path flag and would break the reference's consistency; the spec
// leaves rays other than the camera's to the renderer, since it means unlit for baked or stylised
// colour.)
#include <algorithm>
#include <cmath>
#include <map>

#include "core/load_progress.h"
#include "render/gpu_scene.h"
#include "render/gpu_upload.h"
#include "rhi/context.h"
#include "rhi/upload.h"
#include "shaders/shared/types.h"

namespace rayster::render {
namespace {

VkSamplerAddressMode toVk(scene::Wrap w) {
  switch (w) {
    case scene::Wrap::ClampToEdge:
      return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    case scene::Wrap::MirroredRepeat:
      return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    default:
      return VK_SAMPLER_ADDRESS_MODE_REPEAT;
  }
}
VkFilter toVk(scene::Filter f) { return f == scene::Filter::Nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR; }

}  // namespace

rhi::Image uploadTexture(rhi::Context& ctx, const scene::ImageData& img) {
  rhi::UploadBatch batch(ctx);
  return uploadTexture(batch, img);
}

void uploadMaterials(rhi::Context& ctx, const scene::Scene& scene, GpuScene& gs) {
  rhi::UploadBatch batch(ctx);
  uploadMaterials(ctx, scene, gs, batch);
}

rhi::Image uploadTexture(rhi::UploadBatch& batch, const scene::ImageData& img) {
  // UNORM storage with an sRGB view: colour textures sample through the view, data textures not.
  rhi::ImageDesc desc{VK_FORMAT_R8G8B8A8_UNORM, uint32_t(img.width), uint32_t(img.height), 1, 0, false, 1, true};
  return batch.image(desc, std::as_bytes(std::span(img.rgba)), true, img.name.empty() ? "texture" : img.name.c_str());
}

SpecularSurfaces specularSurfaces(const scene::Scene& scene) {
  SpecularSurfaces out;
  // By texture: the lowest and highest G of its image's texels.
  std::map<int32_t, std::pair<float, float>> rangeG;
  for (const scene::Material& m : scene.materials) {
    if (m.unlit) {  // scatters nothing (see above); its G-buffer says roughness 1 (lib/surface.glsl)
      out.opaqueRoughness.emplace_back(1.0f, 1.0f);
      continue;
    }
    out.transmission = out.transmission || m.transmission > 0.0f;
    std::pair<float, float> texture{1.0f, 1.0f};
    if (const int32_t t = m.metallicRoughnessTexture.texture; t >= 0) {
      auto [it, fresh] = rangeG.try_emplace(t, 0.0f, 1.0f);  // an image not decoded: assume the worst
      if (fresh && size_t(t) < scene.textures.size() && scene.textures[size_t(t)].image < scene.images.size()) {
        const scene::ImageData& img = scene.images[scene.textures[size_t(t)].image];
        uint8_t lo = img.rgba.empty() ? 0 : 255, hi = img.rgba.empty() ? 255 : 0;
        for (size_t i = 1; i < img.rgba.size(); i += 4) {
          lo = std::min(lo, img.rgba[i]);
          hi = std::max(hi, img.rgba[i]);
        }
        it->second = {lo / 255.0f, hi / 255.0f};
      }
      texture = it->second;
    }
    out.minRoughness = std::min(out.minRoughness, std::clamp(m.roughness * texture.first, 0.0f, 1.0f));
    if (m.transmission <= 0.0f || m.transmissionTexture.texture >= 0)  // a texture may make it opaque
      out.opaqueRoughness.emplace_back(std::clamp(m.roughness * texture.first, 0.0f, 1.0f),
                                       std::clamp(m.roughness * texture.second, 0.0f, 1.0f));
  }
  return out;
}

std::string layersApproximated(const scene::Scene& scene) {
  bool coat = false, film = false, aniso = false, dispersion = false;
  for (const scene::Material& m : scene.materials) {
    if (m.unlit) continue;
    coat = coat || m.hasClearcoat();
    film = film || m.hasIridescence();
    aniso = aniso || m.hasAnisotropy();
    dispersion = dispersion || (m.dispersion > 0.0f && m.transmission > 0.0f);
  }
  // Clear coat and sheen are shaded (lib/shading.glsl); only the coat's reflection is approximated.
  std::string names;
  auto add = [&](bool on, const char* name) {
    if (on) names += (names.empty() ? "" : ", ") + std::string(name);
  };
  add(film, "iridescence");
  add(aniso, "anisotropy");
  add(dispersion, "dispersion");
  std::string said;
  if (!names.empty()) said = "render its materials' " + names + " as the base layer alone (no film, isotropic, one η)";
  if (coat)
    said += std::string(said.empty() ? "" : " and ") +
            "reflect only the environment (or the GI probes) in its clear coats, no traced rays";
  if (said.empty()) return {};
  return "scene '" + scene.name + "': the hybrid and raster modes " + said + "; --mode pathtrace renders them exactly";
}

void uploadMaterials(rhi::Context& ctx, const scene::Scene& scene, GpuScene& gs, rhi::UploadBatch& batch) {
  gs.bindless = std::make_unique<rhi::BindlessTextures>(ctx);
  for (const scene::Sampler& s : scene.samplers)
    gs.samplers.emplace_back(ctx, toVk(s.magFilter), toVk(s.minFilter), toVk(s.wrapS), toVk(s.wrapT), s.mipmaps);
  {
    LoadProgress progress("loading " + scene.name, "textures uploaded", scene.images.size());
    for (const scene::ImageData& img : scene.images) {
      gs.textures.push_back(uploadTexture(batch, img));
      progress.advance();
    }
  }

  std::map<std::pair<int32_t, bool>, uint32_t> slots;  // (texture, sRGB) -> bindless slot
  auto slotFor = [&](const scene::TextureRef& ref, bool srgb) -> gpu::TextureSlot {
    gpu::TextureSlot t{gpu::kNoTexture, ref.texCoord, ref.rotation, 0.0f, ref.offset, ref.scale};
    if (!ref.valid()) return t;
    auto key = std::make_pair(ref.texture, srgb);
    auto it = slots.find(key);
    if (it == slots.end()) {
      const scene::Texture& tex = scene.textures[size_t(ref.texture)];
      const rhi::Image& img = gs.textures[tex.image];
      uint32_t slot = gs.bindless->add(srgb ? img.srgbView() : img.view(), gs.samplers[tex.sampler].handle());
      it = slots.emplace(key, slot).first;
    }
    t.slot = it->second;
    // Ray cones' texel density of this texture (lib/textures.glsl coneLod), once here rather than a
    // textureSize and a log2 per sample.
    const rhi::Image& img = gs.textures[scene.textures[size_t(ref.texture)].image];
    const double texels = double(img.desc().width) * double(img.desc().height);
    t.lodBias = float(0.5 * std::log2(texels * std::max(std::abs(double(ref.scale.x) * ref.scale.y), 1e-20)));
    return t;
  };

  // The layer rows first: each layered material's record points at its row.
  std::vector<gpu::MaterialLayers> layerRows;
  std::vector<int32_t> layerOf;
  gs.layeredGBuffer = false;
  for (const scene::Material& m : scene.materials) {
    gs.layeredGBuffer =
        gs.layeredGBuffer || m.clearcoat > 0.0f || std::max({m.sheenColor.r, m.sheenColor.g, m.sheenColor.b}) > 0.0f;
    layerOf.push_back(m.layered() ? int32_t(layerRows.size()) : -1);
    if (!m.layered()) continue;
    gpu::MaterialLayers l{};
    l.clearcoat = m.clearcoat;
    l.clearcoatRoughness = m.clearcoatRoughness;
    l.clearcoatNormalScale = m.clearcoatNormalScale;
    l.sheenRoughness = m.sheenRoughness;
    l.sheenColor = m.sheenColor;
    l.iridescence = m.iridescence;
    l.iridescenceIor = m.iridescenceIor;
    l.iridescenceThicknessMin = m.iridescenceThicknessMin;
    l.iridescenceThicknessMax = m.iridescenceThicknessMax;
    l.anisotropyStrength = m.anisotropyStrength;
    l.anisotropyRotation = m.anisotropyRotation;
    l.dispersion = m.dispersion;
    l.clearcoatTexture = slotFor(m.clearcoatTexture, false);
    l.clearcoatRoughnessTexture = slotFor(m.clearcoatRoughnessTexture, false);
    l.clearcoatNormalTexture = slotFor(m.clearcoatNormalTexture, false);
    l.sheenColorTexture = slotFor(m.sheenColorTexture, true);
    l.sheenRoughnessTexture = slotFor(m.sheenRoughnessTexture, false);
    l.iridescenceTexture = slotFor(m.iridescenceTexture, false);
    l.iridescenceThicknessTexture = slotFor(m.iridescenceThicknessTexture, false);
    l.anisotropyTexture = slotFor(m.anisotropyTexture, false);
    layerRows.push_back(l);
  }
  uint64_t layersAddress = 0;
  if (!layerRows.empty()) {
    gs.materialLayers = rhi::createBufferWithData(ctx, std::as_bytes(std::span(layerRows)),
                                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "material layers");
    layersAddress = gs.materialLayers.address();
  }

  std::vector<gpu::MaterialRecord> rows;
  for (const scene::Material& m : scene.materials) {
    gpu::MaterialRecord r{};
    r.baseColor = m.baseColor;
    r.emissive = m.emissive;
    r.metallic = m.metallic;
    r.roughness = m.roughness;
    r.flags =
        (m.doubleSided ? gpu::kMaterialDoubleSided : 0u) | (m.cullsBackFaces() ? gpu::kMaterialCullsBackFaces : 0u) |
        (m.alphaMode == scene::AlphaMode::Mask ? gpu::kMaterialAlphaMask : 0u) |
        (m.alphaMode == scene::AlphaMode::Blend ? gpu::kMaterialAlphaBlend : 0u) | (m.unlit ? gpu::kMaterialUnlit : 0u);
    r.alphaCutoff = m.alphaCutoff;
    r.normalScale = m.normalScale;
    r.occlusionStrength = m.occlusionStrength;
    r.transmission = m.transmission;
    r.ior = m.ior;
    r.thickness = m.thickness;
    r.attenuationColor = m.attenuationColor;
    r.attenuationDistance = m.attenuationDistance;
    r.specularColor = m.specularColor;
    r.specular = m.specular;
    r.baseColorTexture = slotFor(m.baseColorTexture, true);
    r.metallicRoughnessTexture = slotFor(m.metallicRoughnessTexture, false);
    r.normalTexture = slotFor(m.normalTexture, false);
    r.occlusionTexture = slotFor(m.occlusionTexture, false);
    r.emissiveTexture = slotFor(m.emissiveTexture, true);
    r.specularTexture = slotFor(m.specularTexture, false);  // A only: no sRGB (alpha is linear in both views)
    r.specularColorTexture = slotFor(m.specularColorTexture, true);
    r.transmissionTexture = slotFor(m.transmissionTexture, false);
    if (const int32_t l = layerOf[rows.size()]; l >= 0)
      r.layers = layersAddress + uint64_t(l) * sizeof(gpu::MaterialLayers);
    rows.push_back(r);
  }
  if (rows.empty()) {
    gpu::MaterialRecord r{};
    r.baseColor = glm::vec4(0.8f);
    r.roughness = 1.0f;
    r.ior = 1.5f;
    r.specular = 1.0f;
    r.specularColor = glm::vec3(1.0f);
    for (gpu::TextureSlot* t :
         {&r.baseColorTexture, &r.metallicRoughnessTexture, &r.normalTexture, &r.occlusionTexture, &r.emissiveTexture,
          &r.specularTexture, &r.specularColorTexture, &r.transmissionTexture})
      *t = {gpu::kNoTexture, 0, 0, 0, glm::vec2(0), glm::vec2(1)};
    rows.push_back(r);
  }
  gs.materials =
      rhi::createBufferWithData(ctx, std::as_bytes(std::span(rows)), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "materials");
}

}  // namespace rayster::render
