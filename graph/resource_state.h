#pragma once
// Barrier derivation for the render graph (docs/architecture.md §2.3): given what the graph knows about a
// resource and how the next pass uses it, compute the synchronization2 barrier. Pure functions on
// Vulkan types only, so every hazard rule is unit-tested without a GPU.
#include <cstdint>
#include <optional>

#include <vulkan/vulkan_core.h>

namespace rayster::graph {

// How a pass touches a resource. Each use fixes stages, access and (for images) layout, so passes
// declare intent and never spell out masks themselves.
enum class Use : uint8_t {
  ColorAttachment,
  DepthAttachment,
  SampledCompute,
  SampledRayTracing,
  SampledFragment,
  StorageReadCompute,
  StorageWriteCompute,
  StorageReadWriteCompute,
  StorageReadRayTracing,
  StorageWriteRayTracing,
  StorageReadWriteRayTracing,
  UniformRead,
  VertexShaderRead,  // buffer read through a device address in the vertex shader
  IndexRead,
  TransferSrc,
  TransferDst,
  AccelStructBuildWrite,  // the buffer backing an acceleration structure being built or refitted
  AccelStructRead,        // ray tracing shaders tracing against a TLAS
  HostRead,               // CPU readback after a copy
  IndirectRead,           // draw commands and draw counts of vkCmdDraw*Indirect*
};

struct AccessInfo {
  VkPipelineStageFlags2 stages;
  VkAccessFlags2 access;
  VkImageLayout layout;  // UNDEFINED for buffers
  bool writes;
  bool reads;
};

// Asserts when `use` makes no sense for the resource kind (e.g. a sampled buffer).
AccessInfo accessInfo(Use use, bool isImage);
const char* useName(Use use);

// What the graph knows about one resource (or subresource) between passes.
struct ResourceState {
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  // The last write not yet followed by another write. A layout transition counts as a write that
  // completes before the stages of the barrier that performed it, with no access of its own.
  VkPipelineStageFlags2 writeStages = 0;
  VkAccessFlags2 writeAccess = 0;
  VkPipelineStageFlags2 readStages = 0;  // stages that read since the last write (for write-after-read)
  // Where the last write has already been made visible, kept as a product stages x access.
  VkPipelineStageFlags2 visibleStages = 0;
  VkAccessFlags2 visibleAccess = 0;
  bool contentsValid = false;  // false: the next layout transition may start from UNDEFINED (discard)
};

struct Barrier {
  VkPipelineStageFlags2 srcStages;
  VkPipelineStageFlags2 dstStages;
  VkAccessFlags2 srcAccess;
  VkAccessFlags2 dstAccess;
  VkImageLayout oldLayout;  // equal to newLayout (UNDEFINED) for buffers
  VkImageLayout newLayout;
};

// Returns the barrier needed before `use`, if any, and updates `state` as if the access happened.
std::optional<Barrier> transition(ResourceState& state, Use use, bool isImage);

}  // namespace rayster::graph
