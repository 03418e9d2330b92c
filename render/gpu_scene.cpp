#include "render/gpu_scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include <glm/gtc/matrix_inverse.hpp>

#include "core/load_progress.h"
#include "core/log.h"
#include "core/parallel.h"
#include "render/deform.h"
#include "render/gpu_upload.h"
#include "render/passes/cull.h"
#include "rhi/accel_build.h"
#include "rhi/context.h"
#include "scene/skinning.h"
#include "scene/tangents.h"
#include "shaders/shared/types.h"

namespace rayster::render {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// Geometry feeds BLAS builds only where ray tracing exists: the usage bit needs the extension.
VkBufferUsageFlags geometryUsage(const rhi::Context& ctx) {
  return VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
         (ctx.caps().rayTracing() ? VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR : 0);
}

template <class T>
rhi::Buffer tableBuffer(rhi::Context& ctx, const std::vector<T>& rows, const char* name) {
  return rhi::createBufferWithData(ctx, std::as_bytes(std::span(rows)), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, name);
}

}  // namespace

gpu::LightRecord toRecord(const scene::Light& l) {
  gpu::LightRecord r{};
  r.position = l.position;
  r.radius = l.radius;
  r.radiance = l.color * l.intensity;
  r.type = l.type == scene::LightType::Point  ? gpu::kLightPoint
           : l.type == scene::LightType::Spot ? gpu::kLightSpot
                                              : gpu::kLightDirectional;
  r.direction = glm::normalize(l.direction);
  r.angularRadius = l.angularRadius;
  r.cosInner = std::cos(l.innerConeAngle);
  r.cosOuter = std::cos(l.outerConeAngle);
  r.flags = l.visibleShape ? gpu::kLightVisibleShape : 0u;
  return r;
}

namespace {

bool alphaTested(const scene::Scene& scene, uint32_t material) {
  return material < scene.materials.size() && scene.materials[material].alphaMode != scene::AlphaMode::Opaque;
}

bool cullsBackFaces(const scene::Scene& scene, uint32_t material) {
  return material < scene.materials.size() && scene.materials[material].cullsBackFaces();
}

// How a mesh's triangles meet back faces. Facing culling is per TLAS instance, so a mesh whose
// triangles all cull (the glTF default) or none cull is culled (or not) by the hardware; a mesh that
// mixes them keeps culling off and its culling triangles run any-hit (alpha.rahit), which ignores
// their back faces.
enum class Sidedness { AllCull, NoneCull, Mixed };
Sidedness sidedness(const scene::Scene& scene, const scene::Mesh& mesh) {
  size_t culling = 0;
  for (const scene::Primitive& p : mesh.primitives) culling += cullsBackFaces(scene, p.material) ? 1 : 0;
  return mesh.primitives.empty() || culling == 0 ? Sidedness::NoneCull
         : culling == mesh.primitives.size()     ? Sidedness::AllCull
                                                 : Sidedness::Mixed;
}

}  // namespace

std::vector<gpu::Vertex> gpuVertices(const scene::Primitive& src) {
  scene::Primitive generated;
  const scene::Primitive* prim = &src;
  if (src.tangents.size() != src.positions.size()) {
    generated = src;
    scene::generateTangents(generated);
    prim = &generated;
  }
  std::vector<gpu::Vertex> vertices(prim->positions.size());
  for (size_t i = 0; i < vertices.size(); ++i) {
    vertices[i].position = prim->positions[i];
    vertices[i].normal = prim->normals.empty() ? glm::vec3(0, 1, 0) : prim->normals[i];
    vertices[i].tangent = prim->tangents[i];
    vertices[i].uv0 = prim->uvs.empty() ? glm::vec2(0) : prim->uvs[i];
    vertices[i].uv1 = prim->uvs1.empty() ? vertices[i].uv0 : prim->uvs1[i];
  }
  return vertices;
}

namespace {

// Triangles: vertices (with tangents) and indices; the BLAS reads positions at offset 0.
void addTriangles(rhi::UploadBatch& batch, const scene::Scene& scene, const scene::Primitive& prim,
                  const std::vector<gpu::Vertex>& vertices, bool mixedSides, GpuScene& gs,
                  std::vector<gpu::GeometryRecord>& rows, std::vector<rhi::BlasGeometry>& blas) {
  const VkBufferUsageFlags usage = geometryUsage(batch.context());
  const rhi::Buffer& vb =
      gs.vertexBuffers.emplace_back(batch.buffer(std::as_bytes(std::span(vertices)), usage, "vertices"));
  const rhi::Buffer& ib =
      gs.indexBuffers.emplace_back(batch.buffer(std::as_bytes(std::span(prim.indices)), usage, "indices"));
  uint64_t colorAddress = 0;  // no COLOR_0: white, and no buffer (gpu::GeometryRecord::colorAddress)
  if (!prim.colors.empty()) {
    std::vector<glm::uvec2> colors(prim.colors.size());
    for (size_t i = 0; i < colors.size(); ++i) {
      const glm::uvec4 c(glm::round(glm::clamp(prim.colors[i], 0.0f, 1.0f) * 65535.0f));
      colors[i] = {c.r | (c.g << 16), c.b | (c.a << 16)};  // unpackUnorm2x16's order: low half first
    }
    colorAddress = gs.colorBuffers
                       .emplace_back(batch.buffer(std::as_bytes(std::span(colors)), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                  "vertex-colors"))
                       .address();
  }
  rows.push_back({vb.address(), ib.address(), prim.material, uint32_t(vertices.size()), uint32_t(prim.indices.size()),
                  gpu::kGeometryTriangles, colorAddress});
  blas.push_back({0, 0, vb.address(), sizeof(gpu::Vertex), uint32_t(vertices.size()), ib.address(),
                  uint32_t(prim.indices.size()),
                  !alphaTested(scene, prim.material) && !(mixedSides && cullsBackFaces(scene, prim.material))});
}

// Spheres: one AABB each for the BLAS, and SphereRecords for the intersection shader.
void addSpheres(rhi::Context& ctx, const scene::Scene& scene, const std::vector<scene::Sphere>& spheres, GpuScene& gs,
                std::vector<gpu::GeometryRecord>& rows, std::vector<rhi::BlasGeometry>& blas) {
  std::vector<VkAabbPositionsKHR> boxes;
  std::vector<gpu::SphereRecord> records;
  bool opaque = true;
  for (const scene::Sphere& s : spheres) {
    boxes.push_back({s.center.x - s.radius, s.center.y - s.radius, s.center.z - s.radius, s.center.x + s.radius,
                     s.center.y + s.radius, s.center.z + s.radius});
    records.push_back({s.center, s.radius, s.material, 0, 0, 0});
    opaque = opaque && !alphaTested(scene, s.material);
  }
  const rhi::Buffer& ab = gs.vertexBuffers.emplace_back(
      rhi::createBufferWithData(ctx, std::as_bytes(std::span(boxes)), geometryUsage(ctx), "sphere-aabbs"));
  const rhi::Buffer& sb = gs.indexBuffers.emplace_back(
      rhi::createBufferWithData(ctx, std::as_bytes(std::span(records)), geometryUsage(ctx), "spheres"));
  rows.push_back(
      {sb.address(), ab.address(), records.front().material, uint32_t(records.size()), 0, gpu::kGeometrySpheres, 0});
  blas.push_back({uint32_t(boxes.size()), ab.address(), 0, 0, 0, 0, 0, opaque});
}

// Every primitive's vertices as uploaded, [mesh][primitive], converted in parallel (tangent
// generation dominates on files without tangents).
std::vector<std::vector<std::vector<gpu::Vertex>>> convertVertices(const scene::Scene& scene) {
  std::vector<std::vector<std::vector<gpu::Vertex>>> out(scene.meshes.size());
  std::vector<std::pair<size_t, size_t>> work;
  size_t vertices = 0;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    out[m].resize(scene.meshes[m].primitives.size());
    for (size_t p = 0; p < out[m].size(); ++p) {
      work.emplace_back(m, p);
      vertices += scene.meshes[m].primitives[p].positions.size();
    }
  }
  // Largest first, so one huge primitive does not start last and run alone.
  std::sort(work.begin(), work.end(), [&](const auto& a, const auto& b) {
    return scene.meshes[a.first].primitives[a.second].positions.size() >
           scene.meshes[b.first].primitives[b.second].positions.size();
  });
  LoadProgress progress("loading " + scene.name, "primitives converted", work.size());
  parallelFor(work.size(), [&](size_t k) {
    const auto [m, p] = work[k];
    out[m][p] = gpuVertices(scene.meshes[m].primitives[p]);
    progress.advance();
  });
  progress.finish();
  log::debug("scene '{}': {} vertices in {} primitives converted", scene.name, vertices, work.size());
  return out;
}

}  // namespace

Result<GpuScene> uploadScene(rhi::Context& ctx, const scene::Scene& scene) {
  RAYSTER_TRY(scene::validate(scene));
  GpuScene gs;
  auto t0 = Clock::now();
  std::vector<std::vector<std::vector<gpu::Vertex>>> vertices = convertVertices(scene);
  rhi::UploadBatch batch(ctx);
  LoadProgress uploadPhase("loading " + scene.name, "upload");

  std::vector<gpu::GeometryRecord> geometryRows;
  std::vector<uint32_t> meshFirstGeometry;
  std::vector<std::vector<rhi::BlasGeometry>> blasInputs;
  std::vector<uint64_t> meshTriangles;
  std::vector<std::vector<std::pair<glm::vec3, glm::vec3>>> meshBounds;  // per primitive, then the sphere set
  std::vector<Sidedness> meshSides;
  for (const scene::Mesh& mesh : scene.meshes) {
    meshSides.push_back(sidedness(scene, mesh));
    auto& bounds = meshBounds.emplace_back();
    for (const scene::Primitive& prim : mesh.primitives) {
      glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
      for (const glm::vec3& p : prim.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
      bounds.emplace_back(lo, hi);
    }
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const scene::Sphere& sp : mesh.spheres)
      lo = glm::min(lo, sp.center - glm::vec3(sp.radius)), hi = glm::max(hi, sp.center + glm::vec3(sp.radius));
    bounds.emplace_back(lo, hi);
    meshFirstGeometry.push_back(uint32_t(geometryRows.size()));
    auto& inputs = blasInputs.emplace_back();
    uint64_t triangles = 0;
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const scene::Primitive& prim = mesh.primitives[p];
      std::vector<gpu::Vertex>& converted = vertices[size_t(&mesh - scene.meshes.data())][p];
      addTriangles(batch, scene, prim, converted, meshSides.back() == Sidedness::Mixed, gs, geometryRows, inputs);
      std::vector<gpu::Vertex>().swap(converted);  // staged: the host copy can go
      triangles += prim.indices.size() / 3;
    }
    if (!mesh.spheres.empty()) addSpheres(ctx, scene, mesh.spheres, gs, geometryRows, inputs);
    meshTriangles.push_back(triangles);
  }
  // The geometry first: the BLAS builds, submitted next on the same queue, read it (the batch's
  // last barrier orders its copies before them, so nothing waits here). The device builds while
  // the host stages the textures.
  batch.submit();
  const bool rayTracing = ctx.caps().rayTracing();
  auto t1 = Clock::now();
  std::optional<LoadProgress> accelPhase;
  rhi::PendingBlases pendingBlases;
  if (rayTracing) {
    accelPhase.emplace("loading " + scene.name, "BLAS build");
    pendingBlases = rhi::startBlasBuild(ctx, blasInputs, &gs.accelStats);
  }
  double accelMs = msSince(t1);
  uploadMaterials(ctx, scene, gs, batch);
  batch.submit();
  log::debug("scene '{}': {:.1f} MiB uploaded in {} submissions", scene.name, double(batch.bytes()) / (1 << 20),
             batch.submissions());
  uploadEnvironment(ctx, scene, gs);
  uploadDfgTable(ctx, gs);

  std::vector<gpu::InstanceRecord> instanceRows;
  std::vector<VkAccelerationStructureInstanceKHR> tlasInstances;
  std::vector<int32_t> tlasDeformer;  // per TLAS instance: its Deformers::instances row, -1: the mesh's BLAS
  for (uint32_t i = 0; i < scene.instances.size(); ++i) {
    const scene::Instance& inst = scene.instances[i];
    const scene::Mesh& mesh = scene.meshes[inst.mesh];
    gs.instanceRowOf.push_back(-1);
    if (mesh.primitives.empty() && mesh.spheres.empty()) continue;  // nothing to trace or draw
    gs.instanceRowOf.back() = int32_t(instanceRows.size());
    const uint32_t mask = gpu::kMaskVisible | (inst.castsShadows ? gpu::kMaskCastsShadow : 0u);
    const uint32_t row = uint32_t(instanceRows.size());
    // A deforming instance draws and traces geometry of its own (render/deform.h).
    const bool deforming = scene::deforms(scene, inst);
    const uint32_t firstGeometry =
        deforming ? addDeformer(ctx, scene, i, meshFirstGeometry[inst.mesh], blasInputs[inst.mesh], geometryRows, gs)
                  : meshFirstGeometry[inst.mesh];
    tlasDeformer.push_back(deforming ? int32_t(gs.deformers->instances.size() - 1) : -1);
    instanceRows.push_back({inst.worldFromObject, glm::inverseTranspose(inst.worldFromObject), firstGeometry, mask, 0,
                            0, inst.worldFromObject});
    for (uint32_t p = 0; p < mesh.primitives.size(); ++p) {
      // A deforming draw's box is rewritten with each pose (render/deform.h).
      if (deforming) gs.deformers->instances.back().primitives[p].draw = uint32_t(gs.draws.size());
      gs.draws.push_back({row, firstGeometry + p, uint32_t(mesh.primitives[p].indices.size()), false, inst.castsShadows,
                          cullsBackFaces(scene, mesh.primitives[p].material), meshBounds[inst.mesh][p].first,
                          meshBounds[inst.mesh][p].second});
    }
    if (!mesh.spheres.empty())
      gs.draws.push_back({row, meshFirstGeometry[inst.mesh] + uint32_t(mesh.primitives.size()),
                          uint32_t(mesh.spheres.size()), true, inst.castsShadows, false,
                          meshBounds[inst.mesh].back().first, meshBounds[inst.mesh].back().second});
    gs.triangleCount += meshTriangles[inst.mesh];
    gs.sphereCount += mesh.spheres.size();

    VkAccelerationStructureInstanceKHR ti{};
    const glm::mat4& m = inst.worldFromObject;  // column-major; VkTransformMatrixKHR is 3x4 row-major
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) ti.transform.matrix[r][c] = m[c][r];
    ti.instanceCustomIndex = row;
    ti.mask = mask;
    ti.instanceShaderBindingTableRecordOffset = mesh.spheres.empty() ? gpu::kHitGroupTriangles : gpu::kHitGroupSpheres;
    // Facing is decided in object space, where glTF's counter-clockwise fronts hold whatever the
    // instance's determinant: a mirrored node needs no flip (glTF 2.0 §3.7.4).
    ti.flags = meshSides[inst.mesh] == Sidedness::AllCull
                   ? 0u
                   : uint32_t(VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR);
    ti.accelerationStructureReference = inst.mesh;  // patched with the BLAS address below
    tlasInstances.push_back(ti);
  }
  if (instanceRows.empty()) return makeError(ExitCode::BadInput, "scene '{}' has nothing to render", scene.name);

  std::vector<gpu::LightRecord> lightRows;
  for (const scene::Light& l : scene.lights) lightRows.push_back(toRecord(l));
  gs.lightCount = uint32_t(lightRows.size());
  if (lightRows.empty()) lightRows.push_back({});  // a buffer must not be empty

  gs.geometries = tableBuffer(ctx, geometryRows, "geometries");
  finishDeformers(ctx, gs);
  if (scene.animated()) {
    gs.instancesDynamic = true;
    // Rewritten by the host every frame while instances move (frames are serialised).
    gs.instances = rhi::Buffer(ctx, instanceRows.size() * sizeof(gpu::InstanceRecord),
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, rhi::MemoryUsage::Upload, "instances");
    std::memcpy(gs.instances.mapped(), instanceRows.data(), instanceRows.size() * sizeof(gpu::InstanceRecord));
  } else {
    gs.instances = tableBuffer(ctx, instanceRows, "instances");
  }
  gs.instanceRecords = instanceRows;  // edits (render/instance_motion.h) start from it
  gs.lights = tableBuffer(ctx, lightRows, "lights");
  std::vector<gpu::DrawRecord> drawRows;
  for (const GpuScene::Draw& d : gs.draws)
    drawRows.push_back({d.instance, d.geometry, d.count, d.spheres ? gpu::kDrawSpheres : 0u, d.aabbMin, d.aabbMax});
  if (gs.deformers) {
    // The deforming draws' boxes are rewritten by the host with every pose (frames are serialised).
    const size_t bytes = drawRows.size() * sizeof(gpu::DrawRecord);
    gs.drawRecords =
        rhi::Buffer(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, rhi::MemoryUsage::Upload, "draw-records");
    std::memcpy(gs.drawRecords.mapped(), drawRows.data(), bytes);
  } else {
    gs.drawRecords = tableBuffer(ctx, drawRows, "draw-records");
  }
  gs.cull = createCullBuffers(ctx, uint32_t(gs.draws.size()));
  uploadEmissiveTriangles(ctx, scene, meshFirstGeometry, gs);
  for (const auto& inputs : blasInputs)
    for (const rhi::BlasGeometry& g : inputs) gs.anyHit = gs.anyHit || !g.opaque;
  gs.bounds = scene.bounds();
  batch.wait();  // upload_ms counts the copies too; a no-op when a later upload waited already
  gs.uploadMs = msSince(t0) - accelMs;
  uploadPhase.finish();

  // The uploads waited for the device: their staging buffers can go, and the blocks they emptied
  // with them (they would stay reserved for the whole run otherwise).
  auto releaseStaging = [&ctx] {
    ctx.collectGarbage();
    ctx.memory().releaseEmptyBlocks();
  };
  if (!rayTracing) {                              // the raster mode needs no acceleration structures
    gs.tlasInstances = std::move(tlasInstances);  // animation still poses them (never built)
    releaseStaging();
    return gs;
  }
  t1 = Clock::now();
  gs.blases = rhi::finishBlasBuild(ctx, std::move(pendingBlases), &gs.accelStats);
  for (size_t t = 0; t < tlasInstances.size(); ++t) {
    auto& ti = tlasInstances[t];
    ti.accelerationStructureReference = tlasDeformer[t] >= 0
                                            ? gs.deformers->instances[size_t(tlasDeformer[t])].blas.address()
                                            : gs.blases[ti.accelerationStructureReference].address();
  }
  gs.tlas = rhi::Tlas::build(ctx, tlasInstances, &gs.accelStats);
  gs.tlasInstances = std::move(tlasInstances);
  gs.accelBuildMs = accelMs + msSince(t1);  // without the texture staging it overlapped
  accelPhase->finish();
  releaseStaging();  // and the build's scratch
  return gs;
}

}  // namespace rayster::render
