#pragma once
// The scene on the GPU: vertex and index buffers per primitive, the geometry / instance / material /
// light tables (read through device addresses, layouts in shaders/shared/types.h), one compacted
// BLAS per unique mesh and a TLAS of instances.
#include <cstdint>
#include <vector>

#include "core/error.h"
#include "rhi/accel.h"
#include "rhi/resources.h"
#include "scene/scene.h"

namespace rayster::render {

struct GpuScene {
  struct Draw {
    uint32_t instance;
    uint32_t geometry;
    uint32_t indexCount;
  };
  std::vector<rhi::Buffer> vertexBuffers;  // one per primitive
  std::vector<rhi::Buffer> indexBuffers;
  rhi::Buffer geometries, instances, materials, lights;
  std::vector<rhi::AccelerationStructure> blases;
  rhi::AccelerationStructure tlas;
  std::vector<Draw> draws;  // raster: one per (instance, primitive)
  uint32_t lightCount = 0;
  uint64_t triangleCount = 0;  // over all instances
  rhi::AccelBuildStats accelStats;
  double uploadMs = 0, accelBuildMs = 0;
};

Result<GpuScene> uploadScene(rhi::Context& ctx, const scene::Scene& scene);

} // namespace rayster::render
