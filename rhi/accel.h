#pragma once
// Acceleration structures: one BLAS per unique mesh (one geometry per primitive), compacted; a TLAS
// of instances whose custom index points into the instance table (docs/techniques.md §5).
#include <cstdint>
#include <span>
#include <vector>

#include <volk.h>

#include "rhi/resources.h"

namespace rayster::rhi {

class Context;

class AccelerationStructure {
 public:
  AccelerationStructure() = default;
  ~AccelerationStructure() { reset(); }
  AccelerationStructure(AccelerationStructure&& o) noexcept { *this = std::move(o); }
  AccelerationStructure& operator=(AccelerationStructure&& o) noexcept;
  void reset();
  VkAccelerationStructureKHR handle() const { return handle_; }
  VkDeviceAddress address() const { return address_; }
  VkDeviceSize size() const { return buffer_.size(); }
  const Buffer& buffer() const { return buffer_; }

 private:
  friend AccelerationStructure createAccelerationStructure(Context&, VkAccelerationStructureTypeKHR, VkDeviceSize,
                                                           const char*);
  Context* ctx_ = nullptr;
  Buffer buffer_;
  VkAccelerationStructureKHR handle_ = VK_NULL_HANDLE;
  VkDeviceAddress address_ = 0;
};

AccelerationStructure createAccelerationStructure(Context& ctx, VkAccelerationStructureTypeKHR type, VkDeviceSize size,
                                                  const char* name);

struct BlasGeometry {
  uint32_t aabbCount = 0;  // > 0: procedural geometry, VkAabbPositionsKHR at aabbAddress
  VkDeviceAddress aabbAddress = 0;
  VkDeviceAddress vertexAddress = 0;  // R32G32B32 positions at offset 0 of each vertex
  uint32_t vertexStride = 0;
  uint32_t vertexCount = 0;
  VkDeviceAddress indexAddress = 0;  // uint32 triangle list
  uint32_t indexCount = 0;
  bool opaque = true;  // false: any-hit shaders run (alpha MASK)
};

struct AccelBuildStats {
  uint64_t builtBytes = 0;      // BLAS bytes before compaction
  uint64_t compactedBytes = 0;  // BLAS bytes after compaction
  uint64_t tlasBytes = 0;
  uint64_t triangles = 0;
};

// Builds one compacted BLAS per mesh; meshes[i] lists the geometries (primitives) of mesh i.
std::vector<AccelerationStructure> buildBlases(Context& ctx, std::span<const std::vector<BlasGeometry>> meshes,
                                               AccelBuildStats* stats);

// A BLAS whose vertices move (skinned and morphed meshes, render/deform.h): built with
// ALLOW_UPDATE and not compacted, then refitted in place (an UPDATE build: same triangles, new
// positions) or rebuilt, as the caller records it each frame. The geometry's buffers must outlive it.
class DynamicBlas {
 public:
  DynamicBlas() = default;
  DynamicBlas(Context& ctx, std::vector<BlasGeometry> geometries, const char* name);
  // Records a rebuild or, with `refit`, an update of the last build's structure. The caller
  // orders it after the vertex writes and before any use (barriers).
  void record(VkCommandBuffer cmd, bool refit) const;
  VkDeviceAddress address() const { return as_.address(); }
  VkDeviceSize size() const { return as_.size(); }

 private:
  Context* ctx_ = nullptr;
  std::vector<BlasGeometry> geometries_;
  AccelerationStructure as_;
  Buffer scratch_;
};

// A TLAS over instances whose accelerationStructureReference are BLAS addresses, kept up to date
// as instances move (docs/techniques.md §5): refitted (an UPDATE build, in place) when only transforms
// change, rebuilt when the instance count changes. The instance array lives in host-visible
// memory, written when an update is recorded: the caller keeps the previous frame's use finished.
class Tlas {
 public:
  Tlas() = default;
  // Builds and waits.
  static Tlas build(Context& ctx, std::span<const VkAccelerationStructureInstanceKHR> instances,
                    AccelBuildStats* stats);
  // A frame's update, in two steps. prepare() writes the instances (host side, while the frame is
  // recorded) and, when their count changed, allocates a new structure (so handle() changes before any
  // pass binds it); returns true for a refit. record() records the build or refit: the render graph's
  // "tlas-update" pass, whose barriers the graph derives (the TLAS is a graph resource, AccelHandle).
  bool prepare(std::span<const VkAccelerationStructureInstanceKHR> instances);
  void record(VkCommandBuffer cmd, bool refit) const;
  VkAccelerationStructureKHR handle() const { return as_.handle(); }
  const Buffer& buffer() const { return as_.buffer(); }  // the storage behind the structure
  VkDeviceSize size() const { return as_.size(); }

 private:
  void allocate(uint32_t count);
  Context* ctx_ = nullptr;
  AccelerationStructure as_;
  Buffer instances_;  // host-visible VkAccelerationStructureInstanceKHR[capacity]
  Buffer scratch_;
  uint32_t count_ = 0;
};

}  // namespace rayster::rhi
