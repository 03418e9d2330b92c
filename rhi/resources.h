#pragma once
// Move-only owners of buffers, images and samplers. Destruction is deferred through
// Context::retire, so an owner may die while the GPU still reads the object.
#include <cstdint>
#include <span>
#include <string>

#include <volk.h>

#include "rhi/memory.h"

namespace rayster::rhi {

class Context;

class Buffer {
 public:
  Buffer() = default;
  Buffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory, const char* name);
  ~Buffer() { reset(); }
  Buffer(Buffer&& o) noexcept { *this = std::move(o); }
  Buffer& operator=(Buffer&& o) noexcept;
  void reset();

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  VkDeviceAddress address() const { return address_; }
  void* mapped() const { return allocation_.mapped; }
  explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }

 private:
  Context* ctx_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  Allocation allocation_;
  VkDeviceSize size_ = 0;
  VkDeviceAddress address_ = 0;
};

struct ImageDesc {
  VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
  uint32_t width = 1, height = 1, layers = 1;
  VkImageUsageFlags usage = 0;
  bool array = false;  // view as an array even with one layer (shaders declaring image2DArray)
  uint32_t mips = 1;
  bool srgbView = false;  // RGBA8 UNORM image that also gets an sRGB view (colour textures)
  bool operator==(const ImageDesc&) const = default;
};

bool isDepthFormat(VkFormat format);

class Image {
 public:
  Image() = default;
  Image(Context& ctx, const ImageDesc& desc, const char* name);
  // An image without memory yet (aliased transients, graph/transient_pool.h): bindPlaced() gives it
  // memory owned elsewhere, at an offset, and creates its views.
  static Image unbound(Context& ctx, const ImageDesc& desc, const char* name);
  VkMemoryRequirements memoryRequirements() const;
  void bindPlaced(VkDeviceMemory memory, VkDeviceSize offset, const char* name);
  ~Image() { reset(); }
  Image(Image&& o) noexcept { *this = std::move(o); }
  Image& operator=(Image&& o) noexcept;
  void reset();

  VkImage handle() const { return image_; }
  VkImageView view() const { return view_; }
  VkImageView srgbView() const { return srgbView_; }
  const ImageDesc& desc() const { return desc_; }
  VkExtent2D extent() const { return {desc_.width, desc_.height}; }
  VkImageAspectFlags aspect() const;
  // The device memory the image needs (its memory requirements' size), owned or placed.
  VkDeviceSize bytes() const { return bytes_; }
  explicit operator bool() const { return image_ != VK_NULL_HANDLE; }

 private:
  void createViews(const char* name);
  Context* ctx_ = nullptr;
  VkImage image_ = VK_NULL_HANDLE;
  VkDeviceSize bytes_ = 0;
  VkImageView view_ = VK_NULL_HANDLE;
  VkImageView srgbView_ = VK_NULL_HANDLE;
  Allocation allocation_;
  ImageDesc desc_;
};

class Sampler {
 public:
  Sampler() = default;
  Sampler(Context& ctx, VkFilter filter, VkSamplerAddressMode address);
  Sampler(Context& ctx, VkFilter mag, VkFilter min, VkSamplerAddressMode u, VkSamplerAddressMode v, bool mipmaps);
  ~Sampler() { reset(); }
  Sampler(Sampler&& o) noexcept { *this = std::move(o); }
  Sampler& operator=(Sampler&& o) noexcept;
  void reset();
  VkSampler handle() const { return sampler_; }

 private:
  Context* ctx_ = nullptr;
  VkSampler sampler_ = VK_NULL_HANDLE;
};

// Creates a device-local buffer holding `bytes`, uploaded through a staging buffer (waits).
Buffer createBufferWithData(Context& ctx, std::span<const std::byte> bytes, VkBufferUsageFlags usage, const char* name);

template <class T>
std::span<const std::byte> asBytes(std::span<const T> s) {
  return std::as_bytes(s);
}

}  // namespace rayster::rhi
