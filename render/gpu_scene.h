#pragma once
// The scene on the GPU: vertex and index buffers per primitive, sphere buffers, the geometry /
// instance / material / light tables (read through device addresses, layouts in
// shaders/shared/types.h), textures in the bindless array, the environment, one compacted BLAS per
// unique mesh and a TLAS of instances.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "core/error.h"
#include "graph/resource_state.h"
#include "rhi/accel.h"
#include "rhi/bindless.h"
#include "rhi/resources.h"
#include "scene/scene.h"
#include "shaders/shared/types.h"

namespace rayster::render {

struct GpuEnvironment {
  uint32_t kind = 0;                        // gpu::kEnvironment*
  uint32_t slot = 0xFFFFFFFFu;              // bindless slot of the equirect map
  uint32_t prefilteredSlot = 0xFFFFFFFFu;   // GGX-prefiltered levels (gpu::kPrefilteredLevels)
  std::array<glm::vec3, 9> irradianceSh{};  // cosine-convolved SH9 of the radiance, × intensity
  // Importance sampling (the path tracer): a piecewise-constant 2D distribution over cdfWidth ×
  // cdfHeight equirect cells ∝ luminance × sinθ; 0 × 0 for a black environment.
  uint32_t cdfWidth = 0, cdfHeight = 0;
};

// The GPU row of one light (lights edited in the viewer are re-encoded with it).
gpu::LightRecord toRecord(const scene::Light& light);

struct GpuScene {
  struct Draw {
    uint32_t instance;
    uint32_t geometry;
    uint32_t count;  // triangles: index count; spheres: sphere count (one box each)
    bool spheres;
    bool castsShadows = true;     // false for a light's visible shape (no shadow-map draw)
    bool cullsBackFaces = false;  // scene::Material::cullsBackFaces(): rays (and shadow maps) skip back faces
    glm::vec3 aabbMin{0.0f}, aabbMax{0.0f};  // object space at upload: what GPU culling tests (deforming
                                             // draws: the DrawRecord's box follows the pose, render/deform.h)
  };
  std::vector<rhi::Buffer> vertexBuffers;  // one per primitive (AABBs for sphere sets)
  std::vector<rhi::Buffer> indexBuffers;   // one per primitive (SphereRecords for sphere sets)
  std::vector<rhi::Buffer> colorBuffers;   // one per primitive with vertex colours (RGBA16 UNORM)
  rhi::Buffer geometries, instances, materials, lights;
  rhi::Buffer materialLayers;  // gpu::MaterialLayers of the layered materials (MaterialRecord::layers)
  std::vector<rhi::Image> textures;
  std::vector<rhi::Sampler> samplers;
  std::unique_ptr<rhi::BindlessTextures> bindless;
  rhi::Image environmentMap;
  rhi::Buffer environmentCdf;     // float[]: see GpuEnvironment
  rhi::Buffer emissiveTriangles;  // gpu::EmissiveTriangle[] (render/gpu_emissive.cpp)
  uint32_t emissiveTriangleCount = 0;
  float emissiveArea = 0.0f;
  bool emissiveFollowsPose = false;         // an emitter is animated or deforms: poseEmissiveTriangles()
  std::vector<uint32_t> meshFirstGeometry;  // kept for it: each mesh's first GeometryRecord row
  rhi::Image environmentPrefiltered;        // built once at upload; glossy environment light of the raster mode
  GpuEnvironment environment;
  rhi::Image dfgTable;               // split-sum DFG (render/dfg.h), RG16F
  uint32_t dfgSlot = 0xFFFFFFFFu;    // its bindless slot
  rhi::Image sheenTable;             // the sheen's directional albedo (shaders/shared/sheen.h), R16F
  uint32_t sheenSlot = 0xFFFFFFFFu;  // its bindless slot
  // Built only on devices with ray tracing (rhi::Capabilities::rayTracing()); empty otherwise.
  std::vector<rhi::AccelerationStructure> blases;
  rhi::Tlas tlas;
  std::vector<VkAccelerationStructureInstanceKHR> tlasInstances;  // as built; updated when instances move
  graph::ResourceState tlasState;  // the TLAS as a graph resource (render/passes/passes.h beginFrameGraph)
  std::vector<Draw> draws;         // raster: one per (instance, primitive or sphere set)
  rhi::Buffer drawRecords;         // gpu::DrawRecord[], one per draw, in order (render/passes/cull.cpp)
  // The culling pass's per-frame buffers and their graph states (render/passes/cull.h). Shared
  // ownership only so the type may stay incomplete here; mutable state of a const scene.
  std::shared_ptr<struct CullBuffers> cull;
  // Skinned and morphed instances' own vertices and BLASes (render/deform.h); null when none deforms.
  std::shared_ptr<struct Deformers> deformers;
  // The CPU copy of the instance table (its buffer is host-visible for animated scenes, and once an
  // instance is edited), and for each scene instance its row (-1: nothing to draw) — the row is
  // also its TLAS instance index.
  std::vector<gpu::InstanceRecord> instanceRecords;
  std::vector<int32_t> instanceRowOf;
  bool instancesDynamic = false;  // animated, or edited since upload: the instance table is rewritten per frame
  uint32_t lightCount = 0;
  // Some material has a clear coat or a sheen: the G-buffer's layers target is written (else it is
  // a one-texel zero image, and 32 MiB at 1080p are not allocated).
  bool layeredGBuffer = false;
  bool anyHit = false;  // some geometry is not opaque (alpha tests, back-face rejection): rays may not be forced opaque
  uint64_t triangleCount = 0;  // over all instances
  // The scene's world bounds at upload (rest pose): scene::Scene::bounds() visits every vertex of
  // every instance, far too slow per frame with thousands of instances.
  scene::Aabb bounds;
  uint64_t sphereCount = 0;
  rhi::AccelBuildStats accelStats;
  double uploadMs = 0, accelBuildMs = 0;
};

Result<GpuScene> uploadScene(rhi::Context& ctx, const scene::Scene& scene);

// A primitive's vertices as uploaded (tangents generated where the file has none).
std::vector<gpu::Vertex> gpuVertices(const scene::Primitive& prim);

// What the scene's materials can ask of the hybrid's specular pass (render/gpu_materials.cpp): the
// lowest roughness any lit material can reach (its factor × the lowest G of its metallic-roughness
// texture: filtering only averages texels) and whether any material transmits. A scene whose
// surfaces are all rougher than the traced range records no specular pass.
struct SpecularSurfaces {
  float minRoughness = 1.0f;
  bool transmission = false;
  // The roughness range of every material that may be opaque somewhere (its factor times its
  // texture's lowest and highest G): with none in the half-rate glossy range, rt-specular traces
  // every pixel it traces at all and its fill has nothing to do (Renderer::Impl::specularFillOn).
  std::vector<std::pair<float, float>> opaqueRoughness;
};
SpecularSurfaces specularSurfaces(const scene::Scene& scene);

// One line saying which material layers of the scene (clearcoat, sheen, iridescence, anisotropy,
// dispersion) the hybrid and raster modes render only as their base, for the path tracer renders
// them; empty when the scene has none.
std::string layersApproximated(const scene::Scene& scene);

// Materials and textures (render/gpu_materials.cpp).
void uploadMaterials(rhi::Context& ctx, const scene::Scene& scene, GpuScene& gs);
// Environment map and its irradiance (render/gpu_environment.cpp).
void uploadEnvironment(rhi::Context& ctx, const scene::Scene& scene, GpuScene& gs);
// The path tracer's emissive-triangle list (render/gpu_emissive.cpp); `meshFirstGeometry`: each
// mesh's first GeometryRecord row.
void uploadEmissiveTriangles(rhi::Context& ctx, const scene::Scene& scene,
                             const std::vector<uint32_t>& meshFirstGeometry, GpuScene& gs);
// Lists the emissive triangles again for `pose` (the scene as animated now, or `scene`) where an
// emitter follows the pose; waits for the device first. The path tracer calls it once it posed the scene.
void poseEmissiveTriangles(rhi::Context& ctx, const scene::Scene& scene, const scene::Scene& pose, GpuScene& gs);
// The split-sum DFG table of glossy reflections and the sheen albedo table, into the bindless array
// (render/gpu_environment.cpp).
void uploadDfgTable(rhi::Context& ctx, GpuScene& gs);
// Uploads RGBA8 pixels to a sampled image with a full mip chain (render/gpu_materials.cpp).
rhi::Image uploadTexture(rhi::Context& ctx, const scene::ImageData& image);

}  // namespace rayster::render
