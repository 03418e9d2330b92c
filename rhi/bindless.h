#pragma once
// One global descriptor set (set 1 in every pipeline that samples scene textures) holding an array
// of combined image samplers indexed by a material's slot (docs/techniques.md §24). Slots are written
// before any command buffer that uses them is recorded, so no update-after-bind is needed.
#include <cstdint>

#include <volk.h>

namespace rayster::rhi {

class Context;

class BindlessTextures {
 public:
  static constexpr uint32_t kCapacity = 1024;  // well under every device's per-stage sampler limit

  explicit BindlessTextures(Context& ctx);
  ~BindlessTextures();
  BindlessTextures(const BindlessTextures&) = delete;
  BindlessTextures& operator=(const BindlessTextures&) = delete;

  // Writes `view` + `sampler` into the next free slot and returns it.
  uint32_t add(VkImageView view, VkSampler sampler);
  VkDescriptorSetLayout layout() const { return layout_; }
  VkDescriptorSet set() const { return set_; }
  uint32_t count() const { return count_; }

 private:
  Context& ctx_;
  VkDescriptorSetLayout layout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  uint32_t count_ = 0;
};

}  // namespace rayster::rhi
