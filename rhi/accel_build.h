#pragma once
// A BLAS build in two halves (rhi/accel.h's buildBlases() is both at once): start records and
// submits the builds without waiting, so the host can stage other uploads (the scene's textures)
// while the device builds; finish waits, reads the compacted sizes and compacts.
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "rhi/accel.h"

namespace rayster::rhi {

struct PendingBlases {
  PendingBlases() = default;
  PendingBlases(PendingBlases&& o) noexcept { *this = std::move(o); }
  PendingBlases& operator=(PendingBlases&& o) noexcept {
    std::swap(todo, o.todo), std::swap(built, o.built), std::swap(scratch, o.scratch);
    std::swap(device, o.device), std::swap(pool, o.pool), std::swap(timeline, o.timeline);
    return *this;
  }
  ~PendingBlases() {
    if (pool) vkDestroyQueryPool(device, pool, nullptr);  // only when never finished
  }
  std::vector<size_t> todo;                  // meshes with geometry
  std::vector<AccelerationStructure> built;  // per mesh, uncompacted
  Buffer scratch;
  VkDevice device = VK_NULL_HANDLE;
  VkQueryPool pool = VK_NULL_HANDLE;  // compacted sizes
  uint64_t timeline = 0;              // the build's submission
};

PendingBlases startBlasBuild(Context& ctx, std::span<const std::vector<BlasGeometry>> meshes, AccelBuildStats* stats);
std::vector<AccelerationStructure> finishBlasBuild(Context& ctx, PendingBlases&& pending, AccelBuildStats* stats);

}  // namespace rayster::rhi
