#include "render/deform.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <tuple>

#include "render/gpu_scene.h"
#include "render/passes/passes.h"
#include "rhi/commands.h"
#include "rhi/context.h"
#include "rhi/pipeline_library.h"
#include "scene/skinning.h"

namespace rayster::render {
namespace {

template <class T>
rhi::Buffer buffer(rhi::Context& ctx, const std::vector<T>& data, VkBufferUsageFlags usage, const char* name) {
  return rhi::createBufferWithData(ctx, std::as_bytes(std::span(data)), usage, name);
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace

float refitDrift(const DeformReach& reach, const DeformPose& built, const DeformPose& now) {
  float morph = 0.0f, widen = 0.0f;
  for (size_t t = 0; t < reach.targetReach.size(); ++t) {
    const float was = t < built.weights.size() ? built.weights[t] : 0.0f;
    const float is = t < now.weights.size() ? now.weights[t] : 0.0f;
    morph += reach.targetReach[t] * std::abs(is - was);
    widen += reach.targetReach[t] * std::max(std::abs(is), std::abs(was));
  }
  float skin = 0.0f;
  const size_t joints = std::min(built.joints.size(), now.joints.size());
  if (joints > 1) {
    // The first joint's motion since the build, R = M₀·B₀⁻¹, stands for the rigid part; a vertex
    // blended from joints j moved by Σ w_j (M_j − R·B_j) p beyond it, at most the largest term.
    const glm::mat4 rigid = now.joints[0] * glm::inverse(built.joints[0]);
    const glm::vec3 lo = reach.restMin - glm::vec3(widen), hi = reach.restMax + glm::vec3(widen);
    for (size_t j = 1; j < joints; ++j) {
      const glm::mat4 away = now.joints[j] - rigid * built.joints[j];
      for (int c = 0; c < 8; ++c) {
        const glm::vec4 corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z, 1.0f);
        skin = std::max(skin, glm::length(glm::vec3(away * corner)));
      }
    }
  }
  // A morph moves a vertex before its joints do: scaled by the largest stretch of any joint matrix.
  float scale = joints > 0 ? 0.0f : 1.0f;
  for (size_t j = 0; j < now.joints.size(); ++j)
    for (int k = 0; k < 3; ++k) scale = std::max(scale, glm::length(glm::vec3(now.joints[j][k])));
  return skin + morph * scale;
}

DeformBounds deformBounds(const scene::Primitive& primitive, bool skinned) {
  DeformBounds b;
  for (size_t i = 0; i < primitive.positions.size(); ++i) {
    b.restMin = i == 0 ? primitive.positions[i] : glm::min(b.restMin, primitive.positions[i]);
    b.restMax = i == 0 ? primitive.positions[i] : glm::max(b.restMax, primitive.positions[i]);
  }
  for (const scene::MorphTarget& target : primitive.targets) {
    // A vertex the target does not list moves by 0, so 0 is always in the range.
    glm::vec3 lo(0.0f), hi(0.0f);
    for (const glm::vec3& delta : target.positions) lo = glm::min(lo, delta), hi = glm::max(hi, delta);
    b.targetMin.push_back(lo);
    b.targetMax.push_back(hi);
  }
  if (!skinned || primitive.influences.empty()) return b;
  std::vector<bool> used;
  b.unweighted = false;
  for (size_t i = 0; i < primitive.positions.size(); ++i) {
    bool weighted = false;
    for (const scene::SkinInfluences& set : primitive.influences)
      for (int k = 0; k < 4; ++k) {
        if (!(set.weights[i][k] > 0.0f)) continue;
        const uint32_t j = set.joints[i][k];
        if (j >= used.size()) used.resize(j + 1, false);
        used[j] = true;
        weighted = true;
      }
    b.unweighted = b.unweighted || !weighted;
  }
  for (uint32_t j = 0; j < used.size(); ++j)
    if (used[j]) b.joints.push_back(j);
  return b;
}

std::pair<glm::vec3, glm::vec3> deformedBounds(const DeformBounds& bounds, const DeformPose& pose) {
  glm::vec3 morphLo = bounds.restMin, morphHi = bounds.restMax;
  for (size_t t = 0; t < bounds.targetMin.size(); ++t) {
    const float w = t < pose.weights.size() ? pose.weights[t] : 0.0f;
    const glm::vec3 a = w * bounds.targetMin[t], b = w * bounds.targetMax[t];
    morphLo += glm::min(a, b), morphHi += glm::max(a, b);
  }
  const glm::vec3 centre = 0.5f * (morphLo + morphHi);
  const glm::vec3 half = 0.5f * (morphHi - morphLo);
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  if (bounds.unweighted) lo = centre - half, hi = centre + half;
  for (uint32_t j : bounds.joints) {
    const glm::mat4& m = j < pose.joints.size() ? pose.joints[j] : glm::mat4(1.0f);
    // An affine box image: the centre moves, each half extent is |M| (the absolute 3×3) times it.
    const glm::vec3 c = glm::vec3(m * glm::vec4(centre, 1.0f));
    const glm::mat3 a(glm::abs(glm::vec3(m[0])), glm::abs(glm::vec3(m[1])), glm::abs(glm::vec3(m[2])));
    const glm::vec3 e = a * half;
    lo = glm::min(lo, c - e), hi = glm::max(hi, c + e);
  }
  return {lo, hi};
}

uint32_t addDeformer(rhi::Context& ctx, const scene::Scene& scene, uint32_t sceneInstance, uint32_t meshFirstGeometry,
                     const std::vector<rhi::BlasGeometry>& meshBlas, std::vector<gpu::GeometryRecord>& rows,
                     GpuScene& gs) {
  if (!gs.deformers) gs.deformers = std::make_shared<Deformers>();
  Deformers& d = *gs.deformers;
  const scene::Instance& instance = scene.instances[sceneInstance];
  const scene::Mesh& mesh = scene.meshes[instance.mesh];
  const VkBufferUsageFlags usage =
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
      (ctx.caps().rayTracing() ? VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR : 0);
  Deformers::Instance& out = d.instances.emplace_back();
  out.sceneInstance = sceneInstance;
  out.firstGeometry = uint32_t(rows.size());
  const bool skinned = instance.skin >= 0 && size_t(instance.skin) < scene.skins.size();
  if (skinned) {
    out.jointCount = uint32_t(scene.skins[size_t(instance.skin)].joints.size());
    for (const Deformers::Instance& other : d.instances) out.jointOffset += &other == &out ? 0 : other.jointCount;
  }
  out.weightCount = mesh.primitives.empty() ? 0 : uint32_t(mesh.primitives.front().targets.size());
  for (const Deformers::Instance& other : d.instances) out.weightOffset += &other == &out ? 0 : other.weightCount;

  out.reach.targetReach.assign(out.weightCount, 0.0f);
  bool anyPosition = false;
  for (const scene::Primitive& prim : mesh.primitives) {
    for (const glm::vec3& v : prim.positions) {
      out.reach.restMin = anyPosition ? glm::min(out.reach.restMin, v) : v;
      out.reach.restMax = anyPosition ? glm::max(out.reach.restMax, v) : v;
      anyPosition = true;
    }
    for (size_t t = 0; t < prim.targets.size() && t < out.weightCount; ++t)
      for (const glm::vec3& delta : prim.targets[t].positions)
        out.reach.targetReach[t] = std::max(out.reach.targetReach[t], glm::length(delta));
  }

  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    const scene::Primitive& prim = mesh.primitives[p];
    gpu::GeometryRecord row = rows[meshFirstGeometry + p];
    const std::vector<gpu::Vertex> rest = gpuVertices(prim);
    const uint32_t n = uint32_t(rest.size());
    Deformers::Primitive& dp = out.primitives.emplace_back();
    dp.bounds = deformBounds(prim, skinned);
    dp.vertices = buffer(ctx, rest, usage, "deformed-vertices");
    std::vector<glm::vec3> positions(rest.size());
    for (size_t i = 0; i < rest.size(); ++i) positions[i] = rest[i].position;
    dp.previous = buffer(ctx, positions, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "deformed-previous");
    gpu::DeformPush& push = dp.push;
    push.restVertices = row.vertexAddress;
    push.outVertices = dp.vertices.address();
    push.prevPositions = dp.previous.address();
    push.vertexCount = n;
    if (skinned && !prim.influences.empty()) {
      std::vector<gpu::SkinInfluence> influences;
      influences.reserve(prim.influences.size() * n);
      for (const scene::SkinInfluences& set : prim.influences)
        for (uint32_t i = 0; i < n; ++i) {
          const glm::u16vec4 j = set.joints[i];
          influences.push_back(
              {{uint32_t(j.x) | uint32_t(j.y) << 16, uint32_t(j.z) | uint32_t(j.w) << 16}, set.weights[i]});
        }
      dp.influences = buffer(ctx, influences, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "skin-influences");
      push.influences = dp.influences.address();
      push.influenceSets = uint32_t(prim.influences.size());
    }
    if (!prim.targets.empty()) {
      // Target t's deltas: positions, normals, tangents, each n long; absent attributes are zeros.
      std::vector<glm::vec3> deltas(prim.targets.size() * 3 * n, glm::vec3(0.0f));
      for (size_t t = 0; t < prim.targets.size(); ++t) {
        const scene::MorphTarget& target = prim.targets[t];
        const std::vector<glm::vec3>* attributes[3] = {&target.positions, &target.normals, &target.tangents};
        for (size_t k = 0; k < 3; ++k)
          for (size_t i = 0; i < attributes[k]->size() && i < n; ++i) deltas[(t * 3 + k) * n + i] = (*attributes[k])[i];
      }
      dp.targets = buffer(ctx, deltas, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "morph-targets");
      push.targets = dp.targets.address();
      push.targetCount = uint32_t(prim.targets.size());
    }
    row.vertexAddress = dp.vertices.address();
    row.prevPositionAddress = dp.previous.address();
    rows.push_back(row);
    rhi::BlasGeometry g = meshBlas[p];
    g.vertexAddress = dp.vertices.address();
    out.blasGeometries.push_back(g);
  }
  return out.firstGeometry;
}

void finishDeformers(rhi::Context& ctx, GpuScene& gs) {
  if (!gs.deformers) return;
  Deformers& d = *gs.deformers;
  uint32_t joints = 1, weights = 1;  // a buffer must not be empty
  for (const Deformers::Instance& i : d.instances) joints += i.jointCount, weights += i.weightCount;
  d.joints = rhi::Buffer(ctx, joints * sizeof(glm::mat4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, rhi::MemoryUsage::Upload,
                         "skin-joints");
  d.weights = rhi::Buffer(ctx, weights * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, rhi::MemoryUsage::Upload,
                          "morph-weights");
  if (!ctx.caps().rayTracing()) return;
  rhi::OneShot cmd(ctx);
  for (Deformers::Instance& i : d.instances) {
    i.blas = rhi::DynamicBlas(ctx, i.blasGeometries, "deforming-blas");
    i.blas.record(cmd, false);
  }
  memoryBarrier(
      cmd, VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR,
      VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR | VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR,
      VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR);
  cmd.submitAndWait();
}

void deformMeshes(graph::RenderGraph& graph, const FrameInputs& in, const scene::Scene& scene, const scene::Scene& pose,
                  bool first, bool traced) {
  Deformers* d = in.scene.deformers.get();
  if (!d) return;
  // The pose: joint matrices from the animated nodes, morph weights from the animated instances
  // (else the scene's), in the host-visible tables the pushes point into (frames are serialised).
  auto* joints = static_cast<glm::mat4*>(d->joints.mapped());
  auto* weights = static_cast<float*>(d->weights.mapped());
  auto* draws = static_cast<gpu::DrawRecord*>(in.scene.drawRecords.mapped());  // host-visible with deformers
  for (Deformers::Instance& i : d->instances) {
    const scene::Instance& src = scene.instances[i.sceneInstance];
    const scene::Instance& posed = i.sceneInstance < pose.instances.size() ? pose.instances[i.sceneInstance] : src;
    DeformPose now;
    if (i.jointCount > 0) {
      now.joints = scene::jointMatrices(pose.nodes.empty() ? scene : pose, scene.skins[size_t(src.skin)]);
      std::memcpy(joints + i.jointOffset, now.joints.data(), i.jointCount * sizeof(glm::mat4));
    }
    if (i.weightCount > 0) {
      scene::Instance withWeights = src;
      withWeights.morphWeights = posed.morphWeights;
      now.weights = scene::morphWeights(scene, withWeights, i.weightCount);
      std::memcpy(weights + i.weightOffset, now.weights.data(), i.weightCount * sizeof(float));
    }
    // The draws' culling boxes follow the pose.
    for (const Deformers::Primitive& p : i.primitives)
      if (draws && p.draw != ~0u)
        std::tie(draws[p.draw].aabbMin, draws[p.draw].aabbMax) = deformedBounds(p.bounds, now);
    // Refit while the pose stays close enough to the last build's (refitDrift()), else rebuild.
    // Without traced passes this frame no BLAS is touched: the last build's pose stays.
    const float size = glm::length(i.reach.restMax - i.reach.restMin);
    i.rebuild = first || refitDrift(i.reach, i.built, now) > Deformers::kRefitDriftLimit * size;
    if (traced && i.rebuild) i.built = std::move(now);
  }
  graph.addPass(
      "deform",
      [&](graph::PassBuilder& b) {
        b.pipeline(in.pipelines.compute("deform.comp"));
        if (traced) b.write(in.tlas.buffer, graph::Use::AccelStructBuildWrite);  // ordered before the TLAS update
        b.sideEffect();
      },
      [d, first, traced](graph::PassContext& pc) {
        for (const Deformers::Instance& i : d->instances)
          for (const Deformers::Primitive& p : i.primitives) {
            gpu::DeformPush push = p.push;
            push.joints = d->joints.address() + i.jointOffset * sizeof(glm::mat4);
            push.weights = d->weights.address() + i.weightOffset * sizeof(float);
            push.keepPrevious = first ? 0u : 1u;
            pc.push(push);
            vkCmdDispatch(pc.cmd, (push.vertexCount + gpu::kDeformGroupSize - 1) / gpu::kDeformGroupSize, 1, 1);
          }
        // The vertices are read through device addresses (draws, rays, BLAS builds): one barrier
        // for all of them.
        memoryBarrier(pc.cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_MEMORY_READ_BIT);
        if (!traced) return;
        for (Deformers::Instance& i : d->instances) {
          i.blas.record(pc.cmd, !i.rebuild);
        }
        memoryBarrier(pc.cmd, VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                      VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR,
                      VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR |
                          VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR);
      });
}

}  // namespace rayster::render
