#pragma once
// Ray-tracing pipelines and their shader binding tables. All traceRayEXT calls sit in raygen
// (docs/techniques.md §0), so the recursion depth is 1 unless a pipeline asks for more.
#include <cstdint>
#include <string_view>
#include <vector>

#include "rhi/pipelines.h"

namespace rayster::rhi {

struct Capabilities;

struct HitGroup {
  std::string_view closestHit, anyHit, intersection;  // empty: none
};

struct RayTracingPipelineDesc {
  std::string_view raygen;
  std::vector<std::string_view> miss;  // index = miss index in traceRayEXT
  std::vector<HitGroup> hitGroups;     // index = sbtRecordOffset (+ instance offset)
  uint32_t maxRecursionDepth = 1;
  VkDescriptorSetLayout globalSet = VK_NULL_HANDLE;  // set 1 (bindless textures)
};

// Where each region of the SBT starts; computed from device properties, never hard-coded: lavapipe
// and the H100 have different handle sizes and alignments.
struct SbtLayout {
  uint32_t handleSize = 0;
  uint32_t stride = 0;  // handleSize rounded up to shaderGroupHandleAlignment
  uint32_t raygenOffset = 0, raygenSize = 0;
  uint32_t missOffset = 0, missSize = 0;
  uint32_t hitOffset = 0, hitSize = 0;
  uint32_t totalSize = 0;
};
SbtLayout computeSbtLayout(uint32_t handleSize, uint32_t handleAlignment, uint32_t baseAlignment, uint32_t missCount,
                           uint32_t hitCount);

class RayTracingPipeline : public Pipeline {
 public:
  RayTracingPipeline() = default;
  RayTracingPipeline(Context& ctx, const RayTracingPipelineDesc& desc);
  void trace(VkCommandBuffer cmd, uint32_t width, uint32_t height, uint32_t depth = 1) const;
  // The launch size read by the GPU from a VkTraceRaysIndirectCommandKHR at `command` (a buffer
  // with VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT); needs Capabilities::traceRaysIndirect.
  void traceIndirect(VkCommandBuffer cmd, VkDeviceAddress command) const;
  const SbtLayout& sbtLayout() const { return sbtLayout_; }

 private:
  struct Regions {
    VkStridedDeviceAddressRegionKHR raygen{}, miss{}, hit{}, callable{};
  };
  Regions regions() const;
  Buffer sbt_;
  VkDeviceAddress sbtBase_ = 0;
  SbtLayout sbtLayout_;
};

}  // namespace rayster::rhi
