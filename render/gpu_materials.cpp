// Materials, samplers and textures: every image gets a full mip chain and, for colour data, an sRGB
// view; each (texture, colour-or-linear) use gets one bindless slot.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "render/gpu_scene.h"
#include "rhi/commands.h"
#include "rhi/context.h"
#include "shaders/shared/types.h"

namespace rayster::render {
namespace {

void imageBarrier(VkCommandBuffer cmd, VkImage image, uint32_t mip, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                  VkAccessFlags2 dstAccess) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, mip, 1, 0, 1};
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

VkSamplerAddressMode toVk(scene::Wrap w) {
  switch (w) {
    case scene::Wrap::ClampToEdge: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    case scene::Wrap::MirroredRepeat: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    default: return VK_SAMPLER_ADDRESS_MODE_REPEAT;
  }
}
VkFilter toVk(scene::Filter f) { return f == scene::Filter::Nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR; }

} // namespace

rhi::Image uploadTexture(rhi::Context& ctx, const scene::ImageData& img) {
  const uint32_t w = uint32_t(img.width), h = uint32_t(img.height);
  const uint32_t mips = uint32_t(std::floor(std::log2(double(std::max(w, h))))) + 1;
  rhi::ImageDesc desc{VK_FORMAT_R8G8B8A8_UNORM, w, h, 1,
                      VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                      false, mips, true};
  rhi::Image image(ctx, desc, img.name.empty() ? "texture" : img.name.c_str());
  rhi::Buffer staging(ctx, img.rgba.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, rhi::MemoryUsage::Upload, "staging");
  std::memcpy(staging.mapped(), img.rgba.data(), img.rgba.size());

  rhi::OneShot cmd(ctx);
  imageBarrier(cmd, image.handle(), 0, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {w, h, 1};
  vkCmdCopyBufferToImage(cmd, staging.handle(), image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  // Each level is a linear downsample of the previous one (UNORM view: averaging happens on the
  // stored values, as every glTF viewer does).
  for (uint32_t m = 1; m < mips; ++m) {
    imageBarrier(cmd, image.handle(), m - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    imageBarrier(cmd, image.handle(), m, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m - 1, 0, 1};
    blit.srcOffsets[1] = {int32_t(std::max(w >> (m - 1), 1u)), int32_t(std::max(h >> (m - 1), 1u)), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, 0, 1};
    blit.dstOffsets[1] = {int32_t(std::max(w >> m, 1u)), int32_t(std::max(h >> m, 1u)), 1};
    vkCmdBlitImage(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image.handle(),
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
    imageBarrier(cmd, image.handle(), m - 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, 0,
                 VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  }
  imageBarrier(cmd, image.handle(), mips - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
               VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
               VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  cmd.submitAndWait();
  return image;
}

void uploadMaterials(rhi::Context& ctx, const scene::Scene& scene, GpuScene& gs) {
  gs.bindless = std::make_unique<rhi::BindlessTextures>(ctx);
  for (const scene::Sampler& s : scene.samplers)
    gs.samplers.emplace_back(ctx, toVk(s.magFilter), toVk(s.minFilter), toVk(s.wrapS), toVk(s.wrapT), s.mipmaps);
  for (const scene::ImageData& img : scene.images) gs.textures.push_back(uploadTexture(ctx, img));

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
    return t;
  };

  std::vector<gpu::MaterialRecord> rows;
  for (const scene::Material& m : scene.materials) {
    gpu::MaterialRecord r{};
    r.baseColor = m.baseColor;
    r.emissive = m.emissive;
    r.metallic = m.metallic;
    r.roughness = m.roughness;
    r.flags = (m.doubleSided ? gpu::kMaterialDoubleSided : 0u) |
              (m.alphaMode == scene::AlphaMode::Mask ? gpu::kMaterialAlphaMask : 0u) |
              (m.alphaMode == scene::AlphaMode::Blend ? gpu::kMaterialAlphaBlend : 0u);
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
    if (m.alphaMode != scene::AlphaMode::Opaque) gs.anyAlphaTested = true;
    rows.push_back(r);
  }
  if (rows.empty()) {
    gpu::MaterialRecord r{};
    r.baseColor = glm::vec4(0.8f);
    r.roughness = 1.0f;
    for (gpu::TextureSlot* t : {&r.baseColorTexture, &r.metallicRoughnessTexture, &r.normalTexture,
                                &r.occlusionTexture, &r.emissiveTexture})
      *t = {gpu::kNoTexture, 0, 0, 0, glm::vec2(0), glm::vec2(1)};
    rows.push_back(r);
  }
  gs.materials = rhi::createBufferWithData(ctx, std::as_bytes(std::span(rows)), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                           "materials");
}

} // namespace rayster::render
