#include "rhi/resources.h"

#include <cstring>
#include <utility>

#include "rhi/commands.h"
#include "rhi/context.h"
#include "rhi/vk_check.h"

namespace rayster::rhi {

Buffer::Buffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory, const char* name)
    : ctx_(&ctx), size_(size) {
  VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  ci.size = size;
  ci.usage = usage | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
  VK_CHECK(vkCreateBuffer(ctx.device(), &ci, nullptr, &buffer_));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device(), buffer_, &req);
  const MemoryCategory category = memory != MemoryUsage::GpuOnly ? MemoryCategory::Host
                                  : (usage & VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR)
                                      ? MemoryCategory::Accel
                                      : MemoryCategory::Buffer;
  allocation_ = ctx.memory().allocate(req, memory, true, category);
  VK_CHECK(vkBindBufferMemory(ctx.device(), buffer_, allocation_.memory, allocation_.offset));
  VkBufferDeviceAddressInfo ai{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
  ai.buffer = buffer_;
  address_ = vkGetBufferDeviceAddress(ctx.device(), &ai);
  ctx.setName(VK_OBJECT_TYPE_BUFFER, uint64_t(buffer_), name);
}

Buffer& Buffer::operator=(Buffer&& o) noexcept {
  if (this != &o) {
    reset();
    ctx_ = std::exchange(o.ctx_, nullptr);
    buffer_ = std::exchange(o.buffer_, VK_NULL_HANDLE);
    allocation_ = std::exchange(o.allocation_, {});
    size_ = std::exchange(o.size_, 0);
    address_ = std::exchange(o.address_, 0);
  }
  return *this;
}

void Buffer::reset() {
  if (!buffer_) return;
  ctx_->retire([ctx = ctx_, b = buffer_, a = allocation_] {
    vkDestroyBuffer(ctx->device(), b, nullptr);
    ctx->memory().free(a);
  });
  buffer_ = VK_NULL_HANDLE;
  allocation_ = {};
  size_ = 0;
  address_ = 0;
}

bool isDepthFormat(VkFormat f) {
  return f == VK_FORMAT_D32_SFLOAT || f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_D24_UNORM_S8_UINT ||
         f == VK_FORMAT_D32_SFLOAT_S8_UINT;
}

VkImageAspectFlags Image::aspect() const {
  return isDepthFormat(desc_.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}

Image Image::unbound(Context& ctx, const ImageDesc& desc, const char* name) {
  Image img;
  img.ctx_ = &ctx;
  img.desc_ = desc;
  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  const VkFormat viewFormats[2] = {desc.format, VK_FORMAT_R8G8B8A8_SRGB};
  VkImageFormatListCreateInfo formatList{VK_STRUCTURE_TYPE_IMAGE_FORMAT_LIST_CREATE_INFO};
  formatList.viewFormatCount = 2;
  formatList.pViewFormats = viewFormats;
  if (desc.srgbView) {
    RAYSTER_ASSERT(desc.format == VK_FORMAT_R8G8B8A8_UNORM, "sRGB views are for RGBA8 images");
    ci.flags = VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT;
    ci.pNext = &formatList;
  }
  ci.imageType = VK_IMAGE_TYPE_2D;
  ci.format = desc.format;
  ci.extent = {desc.width, desc.height, 1};
  ci.mipLevels = desc.mips;
  ci.arrayLayers = desc.layers;
  ci.samples = VK_SAMPLE_COUNT_1_BIT;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = desc.usage;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VK_CHECK(vkCreateImage(ctx.device(), &ci, nullptr, &img.image_));
  ctx.setName(VK_OBJECT_TYPE_IMAGE, uint64_t(img.image_), name);
  img.bytes_ = img.memoryRequirements().size;
  return img;
}

VkMemoryRequirements Image::memoryRequirements() const {
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(ctx_->device(), image_, &req);
  return req;
}

void Image::bindPlaced(VkDeviceMemory memory, VkDeviceSize offset, const char* name) {
  RAYSTER_ASSERT(image_ && !view_, "bindPlaced() is for an unbound image");
  VK_CHECK(vkBindImageMemory(ctx_->device(), image_, memory, offset));
  createViews(name);
}

Image::Image(Context& ctx, const ImageDesc& desc, const char* name) {
  *this = unbound(ctx, desc, name);
  allocation_ = ctx.memory().allocate(memoryRequirements(), MemoryUsage::GpuOnly, false, MemoryCategory::Image);
  VK_CHECK(vkBindImageMemory(ctx.device(), image_, allocation_.memory, allocation_.offset));
  createViews(name);
}

void Image::createViews(const char* name) {
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = image_;
  vi.viewType = desc_.layers > 1 || desc_.array ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
  vi.format = desc_.format;
  vi.subresourceRange = {aspect(), 0, desc_.mips, 0, desc_.layers};
  VK_CHECK(vkCreateImageView(ctx_->device(), &vi, nullptr, &view_));
  if (desc_.srgbView) {
    vi.format = VK_FORMAT_R8G8B8A8_SRGB;
    VK_CHECK(vkCreateImageView(ctx_->device(), &vi, nullptr, &srgbView_));
  }
  if (name) ctx_->setName(VK_OBJECT_TYPE_IMAGE_VIEW, uint64_t(view_), name);
}

Image& Image::operator=(Image&& o) noexcept {
  if (this != &o) {
    reset();
    ctx_ = std::exchange(o.ctx_, nullptr);
    image_ = std::exchange(o.image_, VK_NULL_HANDLE);
    view_ = std::exchange(o.view_, VK_NULL_HANDLE);
    srgbView_ = std::exchange(o.srgbView_, VK_NULL_HANDLE);
    allocation_ = std::exchange(o.allocation_, {});
    bytes_ = std::exchange(o.bytes_, 0);
    desc_ = o.desc_;
  }
  return *this;
}

void Image::reset() {
  if (!image_) return;
  ctx_->retire([ctx = ctx_, i = image_, v = view_, sv = srgbView_, a = allocation_] {
    vkDestroyImageView(ctx->device(), v, nullptr);
    if (sv) vkDestroyImageView(ctx->device(), sv, nullptr);
    vkDestroyImage(ctx->device(), i, nullptr);
    ctx->memory().free(a);
  });
  image_ = VK_NULL_HANDLE;
  view_ = VK_NULL_HANDLE;
  srgbView_ = VK_NULL_HANDLE;
  allocation_ = {};
  bytes_ = 0;
}

Sampler::Sampler(Context& ctx, VkFilter filter, VkSamplerAddressMode address)
    : Sampler(ctx, filter, filter, address, address, false) {}

Sampler::Sampler(Context& ctx, VkFilter mag, VkFilter min, VkSamplerAddressMode u, VkSamplerAddressMode v, bool mips)
    : ctx_(&ctx) {
  VkSamplerCreateInfo ci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  ci.magFilter = mag;
  ci.minFilter = min;
  // Without mips only level 0 exists: NEAREST then changes nothing, and lets the sampler read
  // integer formats (ids, the denoisers' surface), which support no linear filtering of any kind.
  ci.mipmapMode = mips ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
  ci.addressModeU = u;
  ci.addressModeV = v;
  ci.addressModeW = u;
  ci.maxLod = mips ? VK_LOD_CLAMP_NONE : 0.0f;
  VK_CHECK(vkCreateSampler(ctx.device(), &ci, nullptr, &sampler_));
}

Sampler& Sampler::operator=(Sampler&& o) noexcept {
  if (this != &o) {
    reset();
    ctx_ = std::exchange(o.ctx_, nullptr);
    sampler_ = std::exchange(o.sampler_, VK_NULL_HANDLE);
  }
  return *this;
}

void Sampler::reset() {
  if (!sampler_) return;
  ctx_->retire([ctx = ctx_, s = sampler_] { vkDestroySampler(ctx->device(), s, nullptr); });
  sampler_ = VK_NULL_HANDLE;
}

Buffer createBufferWithData(Context& ctx, std::span<const std::byte> bytes, VkBufferUsageFlags usage,
                            const char* name) {
  VkDeviceSize size = std::max<VkDeviceSize>(bytes.size(), 16);
  Buffer staging(ctx, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "staging");
  std::memcpy(staging.mapped(), bytes.data(), bytes.size());
  Buffer buffer(ctx, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::GpuOnly, name);
  OneShot cmd(ctx);
  VkBufferCopy region{0, 0, size};
  vkCmdCopyBuffer(cmd, staging.handle(), buffer.handle(), 1, &region);
  cmd.submitAndWait();
  return buffer;
}

}  // namespace rayster::rhi
