#include "render/gpu_scene.h"

#include <chrono>
#include <cmath>

#include <glm/gtc/matrix_inverse.hpp>

#include "rhi/context.h"
#include "shaders/shared/types.h"

namespace rayster::render {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

template <class T>
rhi::Buffer tableBuffer(rhi::Context& ctx, const std::vector<T>& rows, const char* name) {
  return rhi::createBufferWithData(ctx, std::as_bytes(std::span(rows)), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, name);
}

gpu::LightRecord toRecord(const scene::Light& l) {
  gpu::LightRecord r{};
  r.position = l.position;
  r.radius = l.radius;
  r.radiance = l.color * l.intensity;
  r.type = l.type == scene::LightType::Point ? gpu::kLightPoint
           : l.type == scene::LightType::Spot ? gpu::kLightSpot
                                              : gpu::kLightDirectional;
  r.direction = glm::normalize(l.direction);
  r.angularRadius = l.angularRadius;
  r.cosInner = std::cos(l.innerConeAngle);
  r.cosOuter = std::cos(l.outerConeAngle);
  return r;
}

} // namespace

Result<GpuScene> uploadScene(rhi::Context& ctx, const scene::Scene& scene) {
  RAYSTER_TRY(scene::validate(scene));
  GpuScene gs;
  auto t0 = Clock::now();
  const VkBufferUsageFlags geometryUsage =
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR;

  std::vector<gpu::GeometryRecord> geometryRows;
  std::vector<uint32_t> meshFirstGeometry;
  std::vector<std::vector<rhi::BlasGeometry>> blasInputs;
  std::vector<uint64_t> meshTriangles;
  for (const scene::Mesh& mesh : scene.meshes) {
    meshFirstGeometry.push_back(uint32_t(geometryRows.size()));
    auto& inputs = blasInputs.emplace_back();
    uint64_t triangles = 0;
    for (const scene::Primitive& prim : mesh.primitives) {
      std::vector<gpu::Vertex> vertices(prim.positions.size());
      for (size_t i = 0; i < vertices.size(); ++i) {
        vertices[i].position = prim.positions[i];
        vertices[i].normal = prim.normals.empty() ? glm::vec3(0, 1, 0) : prim.normals[i];
        vertices[i].uv = prim.uvs.empty() ? glm::vec2(0) : prim.uvs[i];
      }
      const rhi::Buffer& vb = gs.vertexBuffers.emplace_back(
          rhi::createBufferWithData(ctx, std::as_bytes(std::span(vertices)), geometryUsage, "vertices"));
      const rhi::Buffer& ib = gs.indexBuffers.emplace_back(
          rhi::createBufferWithData(ctx, std::as_bytes(std::span(prim.indices)), geometryUsage, "indices"));
      geometryRows.push_back({vb.address(), ib.address(), prim.material, uint32_t(vertices.size()),
                              uint32_t(prim.indices.size()), 0});
      inputs.push_back({vb.address(), sizeof(gpu::Vertex), uint32_t(vertices.size()), ib.address(),
                        uint32_t(prim.indices.size()), true});
      triangles += prim.indices.size() / 3;
    }
    meshTriangles.push_back(triangles);
  }

  std::vector<gpu::MaterialRecord> materialRows;
  for (const scene::Material& m : scene.materials)
    materialRows.push_back({m.baseColor, m.emissive, m.metallic, m.roughness, 0, 0, 0});
  if (materialRows.empty()) materialRows.push_back({glm::vec4(0.8f), glm::vec3(0), 0, 1, 0, 0, 0});

  std::vector<gpu::InstanceRecord> instanceRows;
  std::vector<VkAccelerationStructureInstanceKHR> tlasInstances;
  for (uint32_t i = 0; i < scene.instances.size(); ++i) {
    const scene::Instance& inst = scene.instances[i];
    const uint32_t mask = gpu::kMaskVisible | (inst.castsShadows ? gpu::kMaskCastsShadow : 0u);
    instanceRows.push_back({inst.worldFromObject, glm::inverseTranspose(inst.worldFromObject),
                            meshFirstGeometry[inst.mesh], mask, 0, 0});
    for (uint32_t p = 0; p < scene.meshes[inst.mesh].primitives.size(); ++p)
      gs.draws.push_back({i, meshFirstGeometry[inst.mesh] + p,
                          uint32_t(scene.meshes[inst.mesh].primitives[p].indices.size())});
    gs.triangleCount += meshTriangles[inst.mesh];
  }

  std::vector<gpu::LightRecord> lightRows;
  for (const scene::Light& l : scene.lights) lightRows.push_back(toRecord(l));
  gs.lightCount = uint32_t(lightRows.size());
  if (lightRows.empty()) lightRows.push_back({});  // a buffer must not be empty

  gs.geometries = tableBuffer(ctx, geometryRows, "geometries");
  gs.instances = tableBuffer(ctx, instanceRows, "instances");
  gs.materials = tableBuffer(ctx, materialRows, "materials");
  gs.lights = tableBuffer(ctx, lightRows, "lights");
  gs.uploadMs = msSince(t0);

  auto t1 = Clock::now();
  gs.blases = rhi::buildBlases(ctx, blasInputs, &gs.accelStats);
  for (uint32_t i = 0; i < scene.instances.size(); ++i) {
    const scene::Instance& inst = scene.instances[i];
    VkAccelerationStructureInstanceKHR ti{};
    const glm::mat4& m = inst.worldFromObject;  // column-major; VkTransformMatrixKHR is 3x4 row-major
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) ti.transform.matrix[r][c] = m[c][r];
    ti.instanceCustomIndex = i;
    ti.mask = instanceRows[i].mask;
    ti.instanceShaderBindingTableRecordOffset = 0;
    ti.flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR;
    ti.accelerationStructureReference = gs.blases[inst.mesh].address();
    tlasInstances.push_back(ti);
  }
  gs.tlas = rhi::buildTlas(ctx, tlasInstances, &gs.accelStats);
  gs.accelBuildMs = msSince(t1);
  return gs;
}

} // namespace rayster::render
