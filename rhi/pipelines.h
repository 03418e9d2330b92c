#pragma once
// Pipelines: compute, graphics (dynamic rendering), ray tracing (with its shader binding table in
// rhi/sbt.h). Each pipeline has one push-descriptor set (set 0) and one push-constant range, which
// keeps passes free of descriptor pools: a pass pushes exactly what it reads and writes. Layouts come
// from the shaders' SPIR-V (rhi/spirv_reflect.h): set 0 is what the stages declare, set 1 the
// global (bindless texture) set when a stage uses it, the push range the largest block.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <volk.h>

#include "rhi/resources.h"
#include "rhi/spirv_reflect.h"

namespace rayster::rhi {

class Context;

class Pipeline {
 public:
  Pipeline() = default;
  virtual ~Pipeline() { reset(); }
  Pipeline(Pipeline&& o) noexcept { *this = std::move(o); }
  Pipeline& operator=(Pipeline&& o) noexcept;
  void reset();

  VkPipeline handle() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }
  VkPipelineBindPoint bindPoint() const { return bindPoint_; }
  VkShaderStageFlags stages() const { return stages_; }
  // What the stages declare (set 0 and set 1 bindings, push-constant size), from their SPIR-V.
  const ShaderInterface& interface() const { return interface_; }
  bool usesGlobalSet() const { return interface_.usesSet(1); }
  // Pushes `bytes` to the pipeline's push-constant range; their size must be the block's.
  void pushConstants(VkCommandBuffer cmd, const void* data, uint32_t bytes) const;
  template <class T>
  void push(VkCommandBuffer cmd, const T& value) const {
    pushConstants(cmd, &value, uint32_t(sizeof(T)));
  }
  explicit operator bool() const { return pipeline_ != VK_NULL_HANDLE; }

 protected:
  friend struct PipelineBuilder;
  friend Pipeline createComputePipeline(Context&, std::string_view, VkDescriptorSetLayout);
  friend Pipeline createGraphicsPipeline(Context&, const struct GraphicsPipelineDesc&);
  Context* ctx_ = nullptr;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineBindPoint bindPoint_ = VK_PIPELINE_BIND_POINT_COMPUTE;
  VkShaderStageFlags stages_ = 0;
  ShaderInterface interface_;
  std::string name_;
};

// Shader modules come from the SPIR-V embedded at build time (shaders/embedded.h).
VkShaderModule createShaderModule(Context& ctx, std::string_view name);

// The interface of an embedded shader (fatal for an unknown shader or words that are not SPIR-V).
ShaderInterface reflectShader(std::string_view name, VkShaderStageFlagBits stage);

// globalSet: the set 1 layout (the bindless textures), used when the shader declares set 1.
Pipeline createComputePipeline(Context& ctx, std::string_view shader, VkDescriptorSetLayout globalSet = VK_NULL_HANDLE);

struct GraphicsPipelineDesc {
  std::string_view vertex, fragment;
  std::vector<VkFormat> colorFormats;
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;
  VkCompareOp depthCompare = VK_COMPARE_OP_GREATER;  // Rayster uses reversed Z
  VkCullModeFlags cullMode = VK_CULL_MODE_NONE;
  bool dynamicCulling = false;  // cull mode and front face set per draw (vkCmdSetCullMode, vkCmdSetFrontFace)
  VkDescriptorSetLayout globalSet = VK_NULL_HANDLE;
};
Pipeline createGraphicsPipeline(Context& ctx, const GraphicsPipelineDesc& desc);

// Records vkCmdPushDescriptorSetKHR for set 0 of a pipeline.
class DescriptorWriter {
 public:
  DescriptorWriter& storageImage(uint32_t binding, VkImageView view);
  DescriptorWriter& sampledImage(uint32_t binding, VkImageView view, VkSampler sampler,
                                 VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  DescriptorWriter& uniformBuffer(uint32_t binding, const Buffer& buffer);
  DescriptorWriter& storageBuffer(uint32_t binding, const Buffer& buffer);
  DescriptorWriter& accelerationStructure(uint32_t binding, VkAccelerationStructureKHR as);
  void push(VkCommandBuffer cmd, const Pipeline& pipeline);

 private:
  struct Entry {
    VkWriteDescriptorSet write;
    VkDescriptorImageInfo image;
    VkDescriptorBufferInfo buffer;
    VkWriteDescriptorSetAccelerationStructureKHR as;
    VkAccelerationStructureKHR asHandle;
  };
  std::vector<Entry> entries_;
};

// Shared by the pipeline factories in rhi/.
struct PipelineBuilder {
  // Builds the layout from p.interface_ (set by the factory from its stages).
  static void makeLayout(Context& ctx, Pipeline& p, VkDescriptorSetLayout globalSet);
  static void addStage(Pipeline& p, std::string_view shader, VkShaderStageFlagBits stage);
  static void setHandle(Pipeline& p, VkPipeline handle, VkPipelineBindPoint bindPoint) {
    p.pipeline_ = handle;
    p.bindPoint_ = bindPoint;
  }
};

}  // namespace rayster::rhi
