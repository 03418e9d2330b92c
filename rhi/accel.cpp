#include "rhi/accel.h"
#include "rhi/accel_build.h"

#include <algorithm>
#include <cstring>

#include "rhi/commands.h"
#include "rhi/context.h"
#include "rhi/vk_check.h"

namespace rayster::rhi {

AccelerationStructure& AccelerationStructure::operator=(AccelerationStructure&& o) noexcept {
  if (this != &o) {
    reset();
    ctx_ = std::exchange(o.ctx_, nullptr);
    buffer_ = std::move(o.buffer_);
    handle_ = std::exchange(o.handle_, VK_NULL_HANDLE);
    address_ = std::exchange(o.address_, 0);
  }
  return *this;
}

void AccelerationStructure::reset() {
  if (handle_)
    ctx_->retire([dev = ctx_->device(), h = handle_] { vkDestroyAccelerationStructureKHR(dev, h, nullptr); });
  handle_ = VK_NULL_HANDLE;
  buffer_.reset();  // retired after the handle, so destroyed after it too
}

AccelerationStructure createAccelerationStructure(Context& ctx, VkAccelerationStructureTypeKHR type, VkDeviceSize size,
                                                  const char* name) {
  AccelerationStructure as;
  as.ctx_ = &ctx;
  as.buffer_ = Buffer(ctx, size, VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR, MemoryUsage::GpuOnly, name);
  VkAccelerationStructureCreateInfoKHR ci{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
  ci.buffer = as.buffer_.handle();
  ci.size = size;
  ci.type = type;
  VK_CHECK(vkCreateAccelerationStructureKHR(ctx.device(), &ci, nullptr, &as.handle_));
  VkAccelerationStructureDeviceAddressInfoKHR ai{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
  ai.accelerationStructure = as.handle_;
  as.address_ = vkGetAccelerationStructureDeviceAddressKHR(ctx.device(), &ai);
  ctx.setName(VK_OBJECT_TYPE_ACCELERATION_STRUCTURE_KHR, uint64_t(as.handle_), name);
  return as;
}

namespace {

void asBuildBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  b.srcStageMask = VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR;
  b.srcAccessMask = VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

VkDeviceSize alignUp(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

}  // namespace

PendingBlases startBlasBuild(Context& ctx, std::span<const std::vector<BlasGeometry>> meshes, AccelBuildStats* stats) {
  PendingBlases pending;
  const size_t n = meshes.size();
  std::vector<std::vector<VkAccelerationStructureGeometryKHR>> geoms(n);
  std::vector<std::vector<VkAccelerationStructureBuildRangeInfoKHR>> ranges(n);
  std::vector<VkAccelerationStructureBuildGeometryInfoKHR> infos(n);
  std::vector<AccelerationStructure>& built = pending.built;
  built.resize(n);
  std::vector<VkDeviceSize> scratchOffsets(n);
  VkDeviceSize scratchTotal = 0;
  const VkDeviceSize scratchAlign = std::max<uint32_t>(ctx.caps().minScratchOffsetAlignment, 1);

  std::vector<size_t>& todo = pending.todo;  // meshes with geometry; an empty mesh gets no BLAS
  for (size_t m = 0; m < n; ++m)
    if (!meshes[m].empty()) todo.push_back(m);
  for (size_t m : todo) {
    std::vector<uint32_t> maxPrims;
    for (const BlasGeometry& g : meshes[m]) {
      VkAccelerationStructureGeometryKHR geo{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
      geo.flags = g.opaque ? VK_GEOMETRY_OPAQUE_BIT_KHR : 0;
      if (g.aabbCount > 0) {
        geo.geometryType = VK_GEOMETRY_TYPE_AABBS_KHR;
        geo.geometry.aabbs.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_AABBS_DATA_KHR;
        geo.geometry.aabbs.data.deviceAddress = g.aabbAddress;
        geo.geometry.aabbs.stride = sizeof(VkAabbPositionsKHR);
        geoms[m].push_back(geo);
        ranges[m].push_back({g.aabbCount, 0, 0, 0});
        maxPrims.push_back(g.aabbCount);
        continue;
      }
      geo.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
      auto& t = geo.geometry.triangles;
      t.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR;
      t.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
      t.vertexData.deviceAddress = g.vertexAddress;
      t.vertexStride = g.vertexStride;
      t.maxVertex = g.vertexCount - 1;
      t.indexType = VK_INDEX_TYPE_UINT32;
      t.indexData.deviceAddress = g.indexAddress;
      geoms[m].push_back(geo);
      // primitiveCount is triangles, not vertices (a published mistake).
      const uint32_t triangles = g.indexCount / 3;
      ranges[m].push_back({triangles, 0, 0, 0});
      maxPrims.push_back(triangles);
      if (stats) stats->triangles += triangles;
    }
    VkAccelerationStructureBuildGeometryInfoKHR& info = infos[m];
    info = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
    info.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
    info.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR |
                 VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_COMPACTION_BIT_KHR;
    info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
    info.geometryCount = uint32_t(geoms[m].size());
    info.pGeometries = geoms[m].data();
    VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    vkGetAccelerationStructureBuildSizesKHR(ctx.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &info,
                                            maxPrims.data(), &sizes);
    built[m] = createAccelerationStructure(ctx, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR,
                                           sizes.accelerationStructureSize, "blas");
    info.dstAccelerationStructure = built[m].handle();
    scratchOffsets[m] = scratchTotal;
    scratchTotal = alignUp(scratchTotal + sizes.buildScratchSize, scratchAlign);
    if (stats) stats->builtBytes += sizes.accelerationStructureSize;
  }
  if (todo.empty()) return pending;

  pending.scratch = Buffer(ctx, scratchTotal + scratchAlign, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly,
                           "blas-scratch");
  const VkDeviceAddress scratchBase = alignUp(pending.scratch.address(), scratchAlign);
  std::vector<VkAccelerationStructureBuildGeometryInfoKHR> buildInfos;
  std::vector<const VkAccelerationStructureBuildRangeInfoKHR*> rangePtrs;
  for (size_t m : todo) {
    infos[m].scratchData.deviceAddress = scratchBase + scratchOffsets[m];
    buildInfos.push_back(infos[m]);
    rangePtrs.push_back(ranges[m].data());
  }
  const uint32_t count = uint32_t(todo.size());

  VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  qci.queryType = VK_QUERY_TYPE_ACCELERATION_STRUCTURE_COMPACTED_SIZE_KHR;
  qci.queryCount = count;
  pending.device = ctx.device();
  VK_CHECK(vkCreateQueryPool(ctx.device(), &qci, nullptr, &pending.pool));
  const VkQueryPool pool = pending.pool;
  {
    CommandList cmd(ctx);
    cmd.begin();
    vkCmdResetQueryPool(cmd, pool, 0, count);
    vkCmdBuildAccelerationStructuresKHR(cmd, count, buildInfos.data(), rangePtrs.data());
    asBuildBarrier(cmd, VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                   VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR);
    std::vector<VkAccelerationStructureKHR> handles;
    for (size_t m : todo) handles.push_back(built[m].handle());
    vkCmdWriteAccelerationStructuresPropertiesKHR(cmd, count, handles.data(),
                                                  VK_QUERY_TYPE_ACCELERATION_STRUCTURE_COMPACTED_SIZE_KHR, pool, 0);
    pending.timeline = cmd.submit();  // the command pool is retired until this has run
  }
  return pending;
}

std::vector<AccelerationStructure> finishBlasBuild(Context& ctx, PendingBlases&& pending, AccelBuildStats* stats) {
  const std::vector<size_t>& todo = pending.todo;
  std::vector<AccelerationStructure>& built = pending.built;
  const size_t n = built.size();
  if (todo.empty()) return std::move(built);
  ctx.wait(pending.timeline);
  const uint32_t count = uint32_t(todo.size());
  const VkQueryPool pool = pending.pool;
  std::vector<VkDeviceSize> compacted(count);
  VK_CHECK(vkGetQueryPoolResults(ctx.device(), pool, 0, count, count * sizeof(VkDeviceSize), compacted.data(),
                                 sizeof(VkDeviceSize), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  vkDestroyQueryPool(ctx.device(), pool, nullptr);
  pending.pool = VK_NULL_HANDLE;

  std::vector<AccelerationStructure> result(n);
  OneShot cmd(ctx);
  for (size_t k = 0; k < todo.size(); ++k) {
    const size_t m = todo[k];
    result[m] = createAccelerationStructure(ctx, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, compacted[k], "blas");
    VkCopyAccelerationStructureInfoKHR copy{VK_STRUCTURE_TYPE_COPY_ACCELERATION_STRUCTURE_INFO_KHR};
    copy.src = built[m].handle();
    copy.dst = result[m].handle();
    copy.mode = VK_COPY_ACCELERATION_STRUCTURE_MODE_COMPACT_KHR;
    vkCmdCopyAccelerationStructureKHR(cmd, &copy);
    if (stats) stats->compactedBytes += compacted[k];
  }
  asBuildBarrier(
      cmd, VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR | VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR,
      VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR);
  cmd.submitAndWait();
  return result;  // `built` (uncompacted) is retired here
}

std::vector<AccelerationStructure> buildBlases(Context& ctx, std::span<const std::vector<BlasGeometry>> meshes,
                                               AccelBuildStats* stats) {
  return finishBlasBuild(ctx, startBlasBuild(ctx, meshes, stats), stats);
}

namespace {

// The Vulkan description of triangle geometries (a dynamic BLAS holds no spheres).
std::vector<VkAccelerationStructureGeometryKHR> triangleGeometries(const std::vector<BlasGeometry>& geometries) {
  std::vector<VkAccelerationStructureGeometryKHR> out;
  for (const BlasGeometry& g : geometries) {
    VkAccelerationStructureGeometryKHR geo{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
    geo.flags = g.opaque ? VK_GEOMETRY_OPAQUE_BIT_KHR : 0;
    geo.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
    auto& t = geo.geometry.triangles;
    t.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR;
    t.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
    t.vertexData.deviceAddress = g.vertexAddress;
    t.vertexStride = g.vertexStride;
    t.maxVertex = g.vertexCount - 1;
    t.indexType = VK_INDEX_TYPE_UINT32;
    t.indexData.deviceAddress = g.indexAddress;
    out.push_back(geo);
  }
  return out;
}

VkAccelerationStructureBuildGeometryInfoKHR dynamicBlasInfo(
    const std::vector<VkAccelerationStructureGeometryKHR>& geos) {
  VkAccelerationStructureBuildGeometryInfoKHR info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  info.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
  info.flags =
      VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR | VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_UPDATE_BIT_KHR;
  info.geometryCount = uint32_t(geos.size());
  info.pGeometries = geos.data();
  return info;
}

}  // namespace

DynamicBlas::DynamicBlas(Context& ctx, std::vector<BlasGeometry> geometries, const char* name)
    : ctx_(&ctx), geometries_(std::move(geometries)) {
  const std::vector<VkAccelerationStructureGeometryKHR> geos = triangleGeometries(geometries_);
  VkAccelerationStructureBuildGeometryInfoKHR info = dynamicBlasInfo(geos);
  info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  std::vector<uint32_t> triangles;
  for (const BlasGeometry& g : geometries_) triangles.push_back(g.indexCount / 3);
  VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  vkGetAccelerationStructureBuildSizesKHR(ctx.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &info,
                                          triangles.data(), &sizes);
  as_ = createAccelerationStructure(ctx, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR,
                                    sizes.accelerationStructureSize, name);
  const VkDeviceSize align = std::max<uint32_t>(ctx.caps().minScratchOffsetAlignment, 1);
  scratch_ = Buffer(ctx, std::max(sizes.buildScratchSize, sizes.updateScratchSize) + align,
                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "dynamic-blas-scratch");
}

void DynamicBlas::record(VkCommandBuffer cmd, bool refit) const {
  const std::vector<VkAccelerationStructureGeometryKHR> geos = triangleGeometries(geometries_);
  VkAccelerationStructureBuildGeometryInfoKHR info = dynamicBlasInfo(geos);
  info.mode = refit ? VK_BUILD_ACCELERATION_STRUCTURE_MODE_UPDATE_KHR : VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  info.srcAccelerationStructure = refit ? as_.handle() : VK_NULL_HANDLE;
  info.dstAccelerationStructure = as_.handle();
  const VkDeviceSize align = std::max<uint32_t>(ctx_->caps().minScratchOffsetAlignment, 1);
  info.scratchData.deviceAddress = alignUp(scratch_.address(), align);
  std::vector<VkAccelerationStructureBuildRangeInfoKHR> ranges;
  for (const BlasGeometry& g : geometries_) ranges.push_back({g.indexCount / 3, 0, 0, 0});
  const VkAccelerationStructureBuildRangeInfoKHR* rangePtr = ranges.data();
  vkCmdBuildAccelerationStructuresKHR(cmd, 1, &info, &rangePtr);
}

namespace {
VkAccelerationStructureBuildGeometryInfoKHR tlasBuildInfo(const VkAccelerationStructureGeometryKHR* geo) {
  VkAccelerationStructureBuildGeometryInfoKHR info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  info.type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR;
  info.flags =
      VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR | VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_UPDATE_BIT_KHR;
  info.geometryCount = 1;
  info.pGeometries = geo;
  return info;
}

VkAccelerationStructureGeometryKHR tlasGeometry(VkDeviceAddress instances) {
  VkAccelerationStructureGeometryKHR geo{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  geo.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
  geo.geometry.instances.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR;
  geo.geometry.instances.data.deviceAddress = instances;
  return geo;
}
}  // namespace

void Tlas::allocate(uint32_t count) {
  count_ = count;
  const size_t bytes = std::max<size_t>(count, 1) * sizeof(VkAccelerationStructureInstanceKHR);
  instances_ = Buffer(
      *ctx_, bytes,
      VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
      MemoryUsage::Upload, "tlas-instances");
  VkAccelerationStructureGeometryKHR geo = tlasGeometry(instances_.address());
  VkAccelerationStructureBuildGeometryInfoKHR info = tlasBuildInfo(&geo);
  VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  vkGetAccelerationStructureBuildSizesKHR(ctx_->device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &info,
                                          &count, &sizes);
  as_ = createAccelerationStructure(*ctx_, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR,
                                    sizes.accelerationStructureSize, "tlas");
  const VkDeviceSize align = std::max<uint32_t>(ctx_->caps().minScratchOffsetAlignment, 1);
  scratch_ = Buffer(*ctx_, std::max(sizes.buildScratchSize, sizes.updateScratchSize) + align,
                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "tlas-scratch");
}

void Tlas::record(VkCommandBuffer cmd, bool refit) const {
  VkAccelerationStructureGeometryKHR geo = tlasGeometry(instances_.address());
  VkAccelerationStructureBuildGeometryInfoKHR info = tlasBuildInfo(&geo);
  info.mode = refit ? VK_BUILD_ACCELERATION_STRUCTURE_MODE_UPDATE_KHR : VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  info.srcAccelerationStructure = refit ? as_.handle() : VK_NULL_HANDLE;
  info.dstAccelerationStructure = as_.handle();
  const VkDeviceSize align = std::max<uint32_t>(ctx_->caps().minScratchOffsetAlignment, 1);
  info.scratchData.deviceAddress = alignUp(scratch_.address(), align);
  VkAccelerationStructureBuildRangeInfoKHR range{count_, 0, 0, 0};
  const VkAccelerationStructureBuildRangeInfoKHR* rangePtr = &range;
  vkCmdBuildAccelerationStructuresKHR(cmd, 1, &info, &rangePtr);
}

Tlas Tlas::build(Context& ctx, std::span<const VkAccelerationStructureInstanceKHR> instances, AccelBuildStats* stats) {
  Tlas t;
  t.ctx_ = &ctx;
  t.allocate(uint32_t(instances.size()));
  std::memcpy(t.instances_.mapped(), instances.data(), instances.size_bytes());
  OneShot cmd(ctx);
  t.record(cmd, false);
  asBuildBarrier(cmd, VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR, VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR);
  cmd.submitAndWait();
  if (stats) stats->tlasBytes = t.as_.size();
  return t;
}

bool Tlas::prepare(std::span<const VkAccelerationStructureInstanceKHR> instances) {
  const bool refit = instances.size() == count_;
  if (!refit) allocate(uint32_t(instances.size()));  // the old structure is retired, not freed under the GPU
  std::memcpy(instances_.mapped(), instances.data(), instances.size_bytes());
  return refit;
}

}  // namespace rayster::rhi
