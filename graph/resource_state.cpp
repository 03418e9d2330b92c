#include "graph/resource_state.h"

#include "core/error.h"

namespace rayster::graph {
namespace {

enum class Kind : uint8_t { Image, Buffer, Either };

struct UseDesc {
  Kind kind;
  VkPipelineStageFlags2 stages;
  VkAccessFlags2 access;
  VkImageLayout layout;  // for images; buffers always get UNDEFINED
  bool writes;
  bool reads;
  const char* name;
};

constexpr VkPipelineStageFlags2 kRt = VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR;
constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkAccessFlags2 kStorageRw = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;

// Only the write bits of a use's access need an availability operation later; read bits in a
// srcAccessMask do nothing.
constexpr VkAccessFlags2 kWriteAccess =
    VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_HOST_WRITE_BIT |
    VK_ACCESS_2_MEMORY_WRITE_BIT | VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;

// Attachment uses count as write-only: their reads (blending, depth test) happen in the same stage
// as the write, and a first use discards (the pass clears).
const UseDesc& describe(Use use) {
  static const UseDesc kTable[] = {
      {Kind::Image, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
       VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT,
       VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, true, false, "color-attachment"},
      {Kind::Image, VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
       VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
       VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, true, false, "depth-attachment"},
      {Kind::Image, kCs, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false, true,
       "sampled-compute"},
      {Kind::Image, kRt, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false, true,
       "sampled-ray-tracing"},
      {Kind::Image, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false, true, "sampled-fragment"},
      {Kind::Either, kCs, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_GENERAL, false, true,
       "storage-read-compute"},
      {Kind::Either, kCs, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL, true, false,
       "storage-write-compute"},
      {Kind::Either, kCs, kStorageRw, VK_IMAGE_LAYOUT_GENERAL, true, true, "storage-read-write-compute"},
      {Kind::Either, kRt, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_GENERAL, false, true,
       "storage-read-ray-tracing"},
      {Kind::Either, kRt, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL, true, false,
       "storage-write-ray-tracing"},
      {Kind::Either, kRt, kStorageRw, VK_IMAGE_LAYOUT_GENERAL, true, true, "storage-read-write-ray-tracing"},
      {Kind::Buffer, VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | kCs | kRt,
       VK_ACCESS_2_UNIFORM_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false, true, "uniform-read"},
      {Kind::Buffer, VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
       VK_IMAGE_LAYOUT_UNDEFINED, false, true, "vertex-shader-read"},
      {Kind::Buffer, VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT, VK_ACCESS_2_INDEX_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false,
       true, "index-read"},
      {Kind::Either, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
       VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, false, true, "transfer-src"},
      {Kind::Either, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, true, false, "transfer-dst"},
      // A refit reads the structure it updates in place, so the build counts as read-write.
      {Kind::Buffer, VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
       VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR | VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR,
       VK_IMAGE_LAYOUT_UNDEFINED, true, true, "accel-struct-build-write"},
      {Kind::Buffer, kRt, VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR, VK_IMAGE_LAYOUT_UNDEFINED, false, true,
       "accel-struct-read"},
      // Readback goes through a buffer; host-visible images are not used.
      {Kind::Buffer, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false, true,
       "host-read"},
      {Kind::Buffer, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT,
       VK_IMAGE_LAYOUT_UNDEFINED, false, true, "indirect-read"},
  };
  static_assert(sizeof(kTable) / sizeof(kTable[0]) == size_t(Use::IndirectRead) + 1,
                "one row per Use, in declaration order");
  const auto index = size_t(use);
  RAYSTER_ASSERT(index < sizeof(kTable) / sizeof(kTable[0]), "unknown graph::Use");
  return kTable[index];
}

bool visibleTo(const ResourceState& s, const AccessInfo& info) {
  return (info.stages & ~s.visibleStages) == 0 && (info.access & ~s.visibleAccess) == 0;
}

// Visibility is kept as one product stages x access so the check stays two masks. When the union
// with the new barrier's scope is not a product, keep only the new scope: that may cost a
// redundant barrier later, never a missing one.
void addVisibility(ResourceState& s, const AccessInfo& info) {
  if (s.visibleAccess == info.access) {
    s.visibleStages |= info.stages;
  } else if (s.visibleStages == info.stages) {
    s.visibleAccess |= info.access;
  } else {
    s.visibleStages = info.stages;
    s.visibleAccess = info.access;
  }
}

}  // namespace

AccessInfo accessInfo(Use use, bool isImage) {
  const UseDesc& d = describe(use);
  RAYSTER_ASSERT(d.kind != Kind::Image || isImage, "this graph::Use applies to images only");
  RAYSTER_ASSERT(d.kind != Kind::Buffer || !isImage, "this graph::Use applies to buffers only");
  return AccessInfo{d.stages, d.access, isImage ? d.layout : VK_IMAGE_LAYOUT_UNDEFINED, d.writes, d.reads};
}

const char* useName(Use use) { return describe(use).name; }

std::optional<Barrier> transition(ResourceState& s, Use use, bool isImage) {
  const AccessInfo info = accessInfo(use, isImage);
  Barrier b{VK_PIPELINE_STAGE_2_NONE, info.stages, 0, info.access, VK_IMAGE_LAYOUT_UNDEFINED, info.layout};
  bool needed = false;

  // Images without valid contents start from UNDEFINED: the driver may discard them, and with
  // nothing pending the barrier waits on nothing (srcStages NONE).
  if (isImage) b.oldLayout = s.contentsValid ? s.layout : VK_IMAGE_LAYOUT_UNDEFINED;
  const bool layoutChange = isImage && b.oldLayout != b.newLayout;

  // A layout transition reads and writes the whole image, so it waits for the last write and for
  // every reader since.
  if (layoutChange) {
    needed = true;
    b.srcStages |= s.writeStages | s.readStages;
    b.srcAccess |= s.writeAccess;
  }
  // Read-after-write: the pending write must be made visible to this stage and access, unless an
  // earlier barrier already did.
  if (info.reads && s.writeStages != 0 && !visibleTo(s, info)) {
    needed = true;
    b.srcStages |= s.writeStages;
    b.srcAccess |= s.writeAccess;
  }
  if (info.writes) {
    if (s.readStages != 0) {
      // Write-after-read needs only an execution dependency on the readers. Readers exist only
      // after a barrier that made the pending write available, so the chain also orders it.
      needed = true;
      b.srcStages |= s.readStages;
    } else if (s.writeStages != 0) {
      // Write-after-write: the earlier write must be available before this one lands.
      needed = true;
      b.srcStages |= s.writeStages;
      b.srcAccess |= s.writeAccess;
    }
  }

  if (isImage) s.layout = info.layout;
  s.contentsValid = true;
  if (info.writes) {
    s.writeStages = info.stages;
    s.writeAccess = info.access & kWriteAccess;
    s.readStages = 0;
    s.visibleStages = 0;
    s.visibleAccess = 0;
  } else if (layoutChange) {
    // The transition is now the last write; later readers chain through this barrier's stages.
    s.writeStages = info.stages;
    s.writeAccess = 0;
    s.readStages = info.stages;
    s.visibleStages = info.stages;
    s.visibleAccess = info.access;
  } else {
    if (needed) addVisibility(s, info);
    s.readStages |= info.stages;
  }

  if (!needed) return std::nullopt;
  RAYSTER_ASSERT(b.dstStages != 0, "a barrier must wait in some stage");
  return b;
}

}  // namespace rayster::graph
