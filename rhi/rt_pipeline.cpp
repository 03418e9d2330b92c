#include "rhi/rt_pipeline.h"

#include <cstring>

#include "rhi/context.h"
#include "rhi/vk_check.h"

namespace rayster::rhi {
namespace {
uint32_t alignUp(uint32_t v, uint32_t a) { return (v + a - 1) / a * a; }
}  // namespace

SbtLayout computeSbtLayout(uint32_t handleSize, uint32_t handleAlignment, uint32_t baseAlignment, uint32_t missCount,
                           uint32_t hitCount) {
  SbtLayout l;
  l.handleSize = handleSize;
  l.stride = alignUp(handleSize, handleAlignment);
  // Raygen's size must equal its stride (VUID-vkCmdTraceRaysKHR-size-04023).
  l.raygenOffset = 0;
  l.raygenSize = alignUp(l.stride, baseAlignment);
  l.missOffset = l.raygenSize;
  l.missSize = alignUp(l.stride * missCount, baseAlignment);
  l.hitOffset = l.missOffset + l.missSize;
  l.hitSize = alignUp(l.stride * hitCount, baseAlignment);
  l.totalSize = l.hitOffset + l.hitSize;
  return l;
}

RayTracingPipeline::RayTracingPipeline(Context& ctx, const RayTracingPipelineDesc& d) {
  stages_ = VK_SHADER_STAGE_RAYGEN_BIT_KHR | VK_SHADER_STAGE_MISS_BIT_KHR | VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR |
            VK_SHADER_STAGE_ANY_HIT_BIT_KHR | VK_SHADER_STAGE_INTERSECTION_BIT_KHR;
  PipelineBuilder::addStage(*this, d.raygen, VK_SHADER_STAGE_RAYGEN_BIT_KHR);
  for (auto m : d.miss) PipelineBuilder::addStage(*this, m, VK_SHADER_STAGE_MISS_BIT_KHR);
  for (const HitGroup& h : d.hitGroups) {
    if (!h.closestHit.empty()) PipelineBuilder::addStage(*this, h.closestHit, VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR);
    if (!h.anyHit.empty()) PipelineBuilder::addStage(*this, h.anyHit, VK_SHADER_STAGE_ANY_HIT_BIT_KHR);
    if (!h.intersection.empty()) PipelineBuilder::addStage(*this, h.intersection, VK_SHADER_STAGE_INTERSECTION_BIT_KHR);
  }
  PipelineBuilder::makeLayout(ctx, *this, d.globalSet);

  std::vector<VkPipelineShaderStageCreateInfo> stages;
  std::vector<VkRayTracingShaderGroupCreateInfoKHR> groups;
  auto addStage = [&](std::string_view name, VkShaderStageFlagBits stage) -> uint32_t {
    if (name.empty()) return VK_SHADER_UNUSED_KHR;
    VkPipelineShaderStageCreateInfo s{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    s.stage = stage;
    s.module = createShaderModule(ctx, name);
    s.pName = "main";
    stages.push_back(s);
    return uint32_t(stages.size() - 1);
  };
  auto general = [&](uint32_t stage) {
    VkRayTracingShaderGroupCreateInfoKHR g{VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR};
    g.type = VK_RAY_TRACING_SHADER_GROUP_TYPE_GENERAL_KHR;
    g.generalShader = stage;
    g.closestHitShader = g.anyHitShader = g.intersectionShader = VK_SHADER_UNUSED_KHR;
    groups.push_back(g);
  };
  general(addStage(d.raygen, VK_SHADER_STAGE_RAYGEN_BIT_KHR));
  for (auto m : d.miss) general(addStage(m, VK_SHADER_STAGE_MISS_BIT_KHR));
  for (const HitGroup& h : d.hitGroups) {
    VkRayTracingShaderGroupCreateInfoKHR g{VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR};
    g.type = h.intersection.empty() ? VK_RAY_TRACING_SHADER_GROUP_TYPE_TRIANGLES_HIT_GROUP_KHR
                                    : VK_RAY_TRACING_SHADER_GROUP_TYPE_PROCEDURAL_HIT_GROUP_KHR;
    g.generalShader = VK_SHADER_UNUSED_KHR;
    g.closestHitShader = addStage(h.closestHit, VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR);
    g.anyHitShader = addStage(h.anyHit, VK_SHADER_STAGE_ANY_HIT_BIT_KHR);
    g.intersectionShader = addStage(h.intersection, VK_SHADER_STAGE_INTERSECTION_BIT_KHR);
    groups.push_back(g);
  }

  const Capabilities& caps = ctx.caps();
  VkRayTracingPipelineCreateInfoKHR ci{VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR};
  ci.stageCount = uint32_t(stages.size());
  ci.pStages = stages.data();
  ci.groupCount = uint32_t(groups.size());
  ci.pGroups = groups.data();
  RAYSTER_ASSERT(d.maxRecursionDepth <= caps.maxRayRecursionDepth, "recursion depth above the device limit");
  ci.maxPipelineRayRecursionDepth = d.maxRecursionDepth;
  ci.layout = layout_;
  VkPipeline handle = VK_NULL_HANDLE;
  VK_CHECK(vkCreateRayTracingPipelinesKHR(ctx.device(), VK_NULL_HANDLE, ctx.pipelineCache(), 1, &ci, nullptr, &handle));
  for (auto& s : stages) vkDestroyShaderModule(ctx.device(), s.module, nullptr);
  PipelineBuilder::setHandle(*this, handle, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR);
  ctx.setName(VK_OBJECT_TYPE_PIPELINE, uint64_t(handle), std::string(d.raygen).c_str());

  const uint32_t missCount = uint32_t(d.miss.size()), hitCount = uint32_t(d.hitGroups.size());
  sbtLayout_ = computeSbtLayout(caps.shaderGroupHandleSize, caps.shaderGroupHandleAlignment,
                                caps.shaderGroupBaseAlignment, missCount, hitCount);
  std::vector<uint8_t> handles(groups.size() * sbtLayout_.handleSize);
  VK_CHECK(vkGetRayTracingShaderGroupHandlesKHR(ctx.device(), handle, 0, uint32_t(groups.size()), handles.size(),
                                                handles.data()));
  std::vector<uint8_t> table(sbtLayout_.totalSize, 0);
  auto put = [&](uint32_t group, uint32_t offset) {
    std::memcpy(table.data() + offset, handles.data() + size_t(group) * sbtLayout_.handleSize, sbtLayout_.handleSize);
  };
  put(0, sbtLayout_.raygenOffset);
  for (uint32_t i = 0; i < missCount; ++i) put(1 + i, sbtLayout_.missOffset + i * sbtLayout_.stride);
  for (uint32_t i = 0; i < hitCount; ++i) put(1 + missCount + i, sbtLayout_.hitOffset + i * sbtLayout_.stride);
  // The SBT's base must honour shaderGroupBaseAlignment: over-allocate and offset the regions.
  const uint32_t pad = caps.shaderGroupBaseAlignment;
  sbt_ = Buffer(ctx, table.size() + pad, VK_BUFFER_USAGE_SHADER_BINDING_TABLE_BIT_KHR, MemoryUsage::Upload, "sbt");
  const VkDeviceAddress base = (sbt_.address() + pad - 1) / pad * pad;
  std::memcpy(static_cast<uint8_t*>(sbt_.mapped()) + (base - sbt_.address()), table.data(), table.size());
  sbtBase_ = base;
}

RayTracingPipeline::Regions RayTracingPipeline::regions() const {
  const SbtLayout& l = sbtLayout_;
  Regions r;
  r.raygen = {sbtBase_ + l.raygenOffset, l.raygenSize, l.raygenSize};
  if (l.missSize != 0) r.miss = {sbtBase_ + l.missOffset, l.stride, l.missSize};
  if (l.hitSize != 0) r.hit = {sbtBase_ + l.hitOffset, l.stride, l.hitSize};
  return r;
}

void RayTracingPipeline::trace(VkCommandBuffer cmd, uint32_t width, uint32_t height, uint32_t depth) const {
  const Regions r = regions();
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipeline_);
  vkCmdTraceRaysKHR(cmd, &r.raygen, &r.miss, &r.hit, &r.callable, width, height, depth);
}

void RayTracingPipeline::traceIndirect(VkCommandBuffer cmd, VkDeviceAddress command) const {
  const Regions r = regions();
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipeline_);
  vkCmdTraceRaysIndirectKHR(cmd, &r.raygen, &r.miss, &r.hit, &r.callable, command);
}

}  // namespace rayster::rhi
