#include "rhi/bindless.h"

#include "core/error.h"
#include "rhi/context.h"
#include "rhi/vk_check.h"

namespace rayster::rhi {

BindlessTextures::BindlessTextures(Context& ctx) : ctx_(ctx) {
  VkDescriptorSetLayoutBinding binding{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kCapacity, VK_SHADER_STAGE_ALL,
                                       nullptr};
  // Partially bound: only the slots a material names are ever read.
  VkDescriptorBindingFlags flags = VK_DESCRIPTOR_BINDING_PARTIALLY_BOUND_BIT;
  VkDescriptorSetLayoutBindingFlagsCreateInfo fci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_BINDING_FLAGS_CREATE_INFO};
  fci.bindingCount = 1;
  fci.pBindingFlags = &flags;
  VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  lci.pNext = &fci;
  lci.bindingCount = 1;
  lci.pBindings = &binding;
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device(), &lci, nullptr, &layout_));
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kCapacity};
  VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pci.maxSets = 1;
  pci.poolSizeCount = 1;
  pci.pPoolSizes = &size;
  VK_CHECK(vkCreateDescriptorPool(ctx.device(), &pci, nullptr, &pool_));
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &layout_;
  VK_CHECK(vkAllocateDescriptorSets(ctx.device(), &ai, &set_));
}

BindlessTextures::~BindlessTextures() {
  ctx_.retire([dev = ctx_.device(), pool = pool_, layout = layout_] {
    vkDestroyDescriptorPool(dev, pool, nullptr);
    vkDestroyDescriptorSetLayout(dev, layout, nullptr);
  });
}

uint32_t BindlessTextures::add(VkImageView view, VkSampler sampler) {
  RAYSTER_ASSERT(count_ < kCapacity, "bindless texture array is full");
  VkDescriptorImageInfo info{sampler, view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set_;
  w.dstBinding = 0;
  w.dstArrayElement = count_;
  w.descriptorCount = 1;
  w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  w.pImageInfo = &info;
  vkUpdateDescriptorSets(ctx_.device(), 1, &w, 0, nullptr);
  return count_++;
}

}  // namespace rayster::rhi
