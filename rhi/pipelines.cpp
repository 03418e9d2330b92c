#include "rhi/pipelines.h"

#include <utility>

#include "rhi/context.h"
#include "rhi/vk_check.h"
#include "shaders/embedded.h"

namespace rayster::rhi {

Pipeline& Pipeline::operator=(Pipeline&& o) noexcept {
  if (this != &o) {
    reset();
    ctx_ = std::exchange(o.ctx_, nullptr);
    pipeline_ = std::exchange(o.pipeline_, VK_NULL_HANDLE);
    layout_ = std::exchange(o.layout_, VK_NULL_HANDLE);
    setLayout_ = std::exchange(o.setLayout_, VK_NULL_HANDLE);
    bindPoint_ = o.bindPoint_;
    stages_ = o.stages_;
    interface_ = std::move(o.interface_);
    name_ = std::move(o.name_);
  }
  return *this;
}

void Pipeline::reset() {
  if (!ctx_) return;
  ctx_->retire([dev = ctx_->device(), p = pipeline_, l = layout_, s = setLayout_] {
    vkDestroyPipeline(dev, p, nullptr);
    vkDestroyPipelineLayout(dev, l, nullptr);
    vkDestroyDescriptorSetLayout(dev, s, nullptr);
  });
  ctx_ = nullptr;
  pipeline_ = VK_NULL_HANDLE;
}

VkShaderModule createShaderModule(Context& ctx, std::string_view name) {
  auto words = shaders::get(name);
  if (words.empty()) fatal(("unknown embedded shader: " + std::string(name)).c_str(), __FILE__, __LINE__);
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = words.size_bytes();
  ci.pCode = words.data();
  VkShaderModule module = VK_NULL_HANDLE;
  VK_CHECK(vkCreateShaderModule(ctx.device(), &ci, nullptr, &module));
  return module;
}

ShaderInterface reflectShader(std::string_view name, VkShaderStageFlagBits stage) {
  auto words = shaders::get(name);
  if (words.empty()) fatal(("unknown embedded shader: " + std::string(name)).c_str(), __FILE__, __LINE__);
  std::string error;
  auto iface = reflectSpirv(words, stage, &error);
  if (!iface) fatal((std::string(name) + ": " + error).c_str(), __FILE__, __LINE__);
  return *iface;
}

void PipelineBuilder::addStage(Pipeline& p, std::string_view shader, VkShaderStageFlagBits stage) {
  std::string error;
  if (!mergeInterface(p.interface_, reflectShader(shader, stage), &error))
    fatal((std::string(shader) + ": " + error).c_str(), __FILE__, __LINE__);
  if (p.name_.empty()) p.name_ = shader;
}

void PipelineBuilder::makeLayout(Context& ctx, Pipeline& p, VkDescriptorSetLayout globalSet) {
  p.ctx_ = &ctx;
  std::vector<VkDescriptorSetLayoutBinding> b;
  for (const ShaderBinding& x : p.interface_.bindings) {
    if (x.set > 1)
      fatal((p.name_ + ": descriptor '" + x.name + "' is in set " + std::to_string(x.set) +
             "; pipelines have set 0 (the pass's) and set 1 (global)")
                .c_str(),
            __FILE__, __LINE__);
    if (x.set == 0) {
      if (x.count == 0)
        fatal((p.name_ + ": '" + x.name + "' is a runtime array in set 0 (push descriptors need a size)").c_str(),
              __FILE__, __LINE__);
      b.push_back({x.binding, x.type, x.count, p.stages_, nullptr});
    }
  }
  const bool global = p.interface_.usesSet(1);
  if (global && !globalSet)
    fatal((p.name_ + ": uses set 1 but the pipeline was created without the global set").c_str(), __FILE__, __LINE__);
  VkDescriptorSetLayoutCreateInfo sci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  sci.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  sci.bindingCount = uint32_t(b.size());
  sci.pBindings = b.data();
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device(), &sci, nullptr, &p.setLayout_));
  const uint32_t pushBytes = p.interface_.pushConstantBytes;
  VkPushConstantRange range{p.stages_, 0, pushBytes};
  VkPipelineLayoutCreateInfo lci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  const VkDescriptorSetLayout sets[2] = {p.setLayout_, globalSet};
  lci.setLayoutCount = global ? 2 : 1;
  lci.pSetLayouts = sets;
  lci.pushConstantRangeCount = pushBytes ? 1 : 0;
  lci.pPushConstantRanges = &range;
  VK_CHECK(vkCreatePipelineLayout(ctx.device(), &lci, nullptr, &p.layout_));
}

void Pipeline::pushConstants(VkCommandBuffer cmd, const void* data, uint32_t bytes) const {
  RAYSTER_ASSERT(bytes == interface_.pushConstantBytes,
                 "push-constant struct size differs from the shader's block (shaders/shared/push.h)");
  vkCmdPushConstants(cmd, layout_, stages_, 0, bytes, data);
}

Pipeline createComputePipeline(Context& ctx, std::string_view shader, VkDescriptorSetLayout globalSet) {
  Pipeline p;
  p.stages_ = VK_SHADER_STAGE_COMPUTE_BIT;
  PipelineBuilder::addStage(p, shader, VK_SHADER_STAGE_COMPUTE_BIT);
  PipelineBuilder::makeLayout(ctx, p, globalSet);
  VkShaderModule module = createShaderModule(ctx, shader);
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  ci.stage.module = module;
  ci.stage.pName = "main";
  ci.layout = p.layout_;
  VkPipeline handle = VK_NULL_HANDLE;
  VK_CHECK(vkCreateComputePipelines(ctx.device(), ctx.pipelineCache(), 1, &ci, nullptr, &handle));
  vkDestroyShaderModule(ctx.device(), module, nullptr);
  PipelineBuilder::setHandle(p, handle, VK_PIPELINE_BIND_POINT_COMPUTE);
  ctx.setName(VK_OBJECT_TYPE_PIPELINE, uint64_t(handle), std::string(shader).c_str());
  return p;
}

Pipeline createGraphicsPipeline(Context& ctx, const GraphicsPipelineDesc& d) {
  Pipeline p;
  p.stages_ = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  PipelineBuilder::addStage(p, d.vertex, VK_SHADER_STAGE_VERTEX_BIT);
  PipelineBuilder::addStage(p, d.fragment, VK_SHADER_STAGE_FRAGMENT_BIT);
  PipelineBuilder::makeLayout(ctx, p, d.globalSet);
  VkShaderModule vs = createShaderModule(ctx, d.vertex);
  VkShaderModule fs = createShaderModule(ctx, d.fragment);
  VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                               {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vs;
  stages[0].pName = "main";
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fs;
  stages[1].pName = "main";

  // Vertices are pulled from buffers by device address: no vertex input state.
  VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = 1;
  vp.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.cullMode = d.cullMode;
  rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  rs.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = d.depthFormat != VK_FORMAT_UNDEFINED;
  ds.depthWriteEnable = ds.depthTestEnable;
  ds.depthCompareOp = d.depthCompare;
  std::vector<VkPipelineColorBlendAttachmentState> blend(d.colorFormats.size());
  for (auto& b : blend) b.colorWriteMask = 0xF;
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = uint32_t(blend.size());
  cb.pAttachments = blend.data();
  VkDynamicState dyn[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR, VK_DYNAMIC_STATE_CULL_MODE,
                          VK_DYNAMIC_STATE_FRONT_FACE};
  VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dy.dynamicStateCount = d.dynamicCulling ? 4 : 2;
  dy.pDynamicStates = dyn;
  VkPipelineRenderingCreateInfo ri{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  ri.colorAttachmentCount = uint32_t(d.colorFormats.size());
  ri.pColorAttachmentFormats = d.colorFormats.data();
  ri.depthAttachmentFormat = d.depthFormat;

  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  ci.pNext = &ri;
  ci.stageCount = 2;
  ci.pStages = stages;
  ci.pVertexInputState = &vi;
  ci.pInputAssemblyState = &ia;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &rs;
  ci.pMultisampleState = &ms;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &cb;
  ci.pDynamicState = &dy;
  ci.layout = p.layout_;
  VkPipeline handle = VK_NULL_HANDLE;
  VK_CHECK(vkCreateGraphicsPipelines(ctx.device(), ctx.pipelineCache(), 1, &ci, nullptr, &handle));
  vkDestroyShaderModule(ctx.device(), vs, nullptr);
  vkDestroyShaderModule(ctx.device(), fs, nullptr);
  PipelineBuilder::setHandle(p, handle, VK_PIPELINE_BIND_POINT_GRAPHICS);
  return p;
}

DescriptorWriter& DescriptorWriter::storageImage(uint32_t binding, VkImageView view) {
  Entry& e = entries_.emplace_back();
  e.write = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  e.write.dstBinding = binding;
  e.write.descriptorCount = 1;
  e.write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  e.image = {VK_NULL_HANDLE, view, VK_IMAGE_LAYOUT_GENERAL};
  return *this;
}

DescriptorWriter& DescriptorWriter::sampledImage(uint32_t binding, VkImageView view, VkSampler sampler,
                                                 VkImageLayout layout) {
  Entry& e = entries_.emplace_back();
  e.write = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  e.write.dstBinding = binding;
  e.write.descriptorCount = 1;
  e.write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  e.image = {sampler, view, layout};
  return *this;
}

DescriptorWriter& DescriptorWriter::uniformBuffer(uint32_t binding, const Buffer& buffer) {
  Entry& e = entries_.emplace_back();
  e.write = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  e.write.dstBinding = binding;
  e.write.descriptorCount = 1;
  e.write.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  e.buffer = {buffer.handle(), 0, VK_WHOLE_SIZE};
  return *this;
}

DescriptorWriter& DescriptorWriter::storageBuffer(uint32_t binding, const Buffer& buffer) {
  uniformBuffer(binding, buffer);
  entries_.back().write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  return *this;
}

DescriptorWriter& DescriptorWriter::accelerationStructure(uint32_t binding, VkAccelerationStructureKHR as) {
  Entry& e = entries_.emplace_back();
  e.write = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  e.write.dstBinding = binding;
  e.write.descriptorCount = 1;
  e.write.descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
  e.asHandle = as;
  return *this;
}

void DescriptorWriter::push(VkCommandBuffer cmd, const Pipeline& pipeline) {
  std::vector<VkWriteDescriptorSet> writes;
  for (Entry& e : entries_) {
    VkWriteDescriptorSet w = e.write;
    switch (w.descriptorType) {
      case VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR:
        e.as = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR};
        e.as.accelerationStructureCount = 1;
        e.as.pAccelerationStructures = &e.asHandle;
        w.pNext = &e.as;
        break;
      case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
      case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
        w.pBufferInfo = &e.buffer;
        break;
      default:
        w.pImageInfo = &e.image;
        break;
    }
    writes.push_back(w);
  }
  vkCmdPushDescriptorSetKHR(cmd, pipeline.bindPoint(), pipeline.layout(), 0, uint32_t(writes.size()), writes.data());
  entries_.clear();
}

}  // namespace rayster::rhi
