// The path tracer's emissive-triangle light list: every triangle of a shadow-casting instance whose
// material emits (emissive factor > 0), in world space at upload, with an area-weighted CDF.
// Area-weighted rather than power-weighted: the pick then has the same density (1 / total area)
// on every emitter, so the MIS weight of a BSDF ray that hits one needs no table lookup; scenes
// whose emitters differ greatly in radiance pay some variance for it. Textured emission is
// evaluated per sample (TEXCOORD_0). Where an emitter is animated or deforms, the list is made again
// from the pose the path tracer renders (poseEmissiveTriangles): the deforming emitters' primitives
// are posed on the CPU by scene::deformPrimitive, as the GPU's deform pass poses their vertices.
// Emissive analytic spheres are not in the list: BSDF rays find them (with MIS weight 1).
// Unlit materials (KHR_materials_unlit) are emitters of their base colour (× texture × vertex
// colour, looked up through `geometry` and `primitive`): the path tracer sees them with the same
// radiance from every direction, so they join the list and MIS stays unbiased for them.

#include <algorithm>

#include "render/gpu_scene.h"
#include "rhi/context.h"
#include "rhi/resources.h"
#include "scene/skinning.h"

namespace rayster::render {
namespace {

struct EmissiveList {
  std::vector<gpu::EmissiveTriangle> rows;
  double area = 0;
  bool followsPose = false;  // some emitter is on an animated node or deforms
};

// The list for `pose` (instances, nodes and morph weights as animated now; `scene` itself for the
// rest pose): the emissive triangles in world space, their area CDF not yet normalised.
EmissiveList emissiveList(const scene::Scene& scene, const scene::Scene& pose,
                          const std::vector<uint32_t>& meshFirstGeometry) {
  EmissiveList list;
  scene::Scene joints;  // what deformPrimitive reads of the pose: its nodes and the skins
  bool jointsReady = false;
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const scene::Instance& rest = scene.instances[i];
    if (!rest.castsShadows) continue;  // a light's visible shape: the light itself is sampled
    const scene::Instance& inst = i < pose.instances.size() ? pose.instances[i] : rest;
    const scene::Mesh& mesh = scene.meshes[rest.mesh];
    const bool deforming = scene::deforms(scene, rest);
    // A mirroring transform turns the world winding: the sampler's front is cross(p1 − p0, p2 − p0) ×
    // frontSign (single-sided emitters light only their front).
    const bool mirrored = glm::determinant(glm::mat3(inst.worldFromObject)) < 0.0f;
    for (size_t primIndex = 0; primIndex < mesh.primitives.size(); ++primIndex) {
      const scene::Primitive& prim = mesh.primitives[primIndex];
      if (prim.material >= scene.materials.size()) continue;
      const scene::Material& material = scene.materials[prim.material];
      const glm::vec3 e = material.unlit ? glm::vec3(material.baseColor) : material.emissive;
      if (std::max(e.x, std::max(e.y, e.z)) <= 0.0f) continue;
      list.followsPose = list.followsPose || deforming || rest.node >= 0;
      std::vector<glm::vec3> posed;
      if (deforming) {
        if (!jointsReady) {
          joints.nodes = pose.nodes.empty() ? scene.nodes : pose.nodes;
          joints.skins = scene.skins;
          jointsReady = true;
        }
        scene::Instance weighted = rest;  // the pose's weights, else the mesh's defaults, resolved here
        weighted.morphWeights = inst.morphWeights;
        weighted.morphWeights = scene::morphWeights(scene, weighted, prim.targets.size());
        posed = scene::deformPrimitive(joints, weighted, prim).positions;
      }
      const std::vector<glm::vec3>& positions = deforming ? posed : prim.positions;
      for (size_t k = 0; k + 2 < prim.indices.size(); k += 3) {
        gpu::EmissiveTriangle t{};
        glm::vec3* p[3] = {&t.p0, &t.p1, &t.p2};
        glm::vec2* uv[3] = {&t.uv0, &t.uv1, &t.uv2};
        for (int c = 0; c < 3; ++c) {
          const uint32_t v = prim.indices[k + c];
          *p[c] = glm::vec3(inst.worldFromObject * glm::vec4(positions[v], 1.0f));
          *uv[c] = v < prim.uvs.size() ? prim.uvs[v] : glm::vec2(0.0f);
        }
        const float a = 0.5f * glm::length(glm::cross(t.p1 - t.p0, t.p2 - t.p0));
        if (!(a > 0.0f)) continue;
        list.area += a;
        t.cdf = float(list.area);
        t.material = prim.material;
        t.frontSign = mirrored ? -1.0f : 1.0f;
        t.geometry = meshFirstGeometry[rest.mesh] + uint32_t(primIndex);
        t.primitive = uint32_t(k / 3);
        list.rows.push_back(t);
      }
    }
  }
  return list;
}

void store(rhi::Context& ctx, EmissiveList list, GpuScene& gs) {
  for (auto& t : list.rows) t.cdf = float(t.cdf / list.area);
  if (!list.rows.empty()) list.rows.back().cdf = 1.0f;
  gs.emissiveTriangleCount = uint32_t(list.rows.size());
  gs.emissiveArea = float(list.area);
  if (list.rows.empty()) list.rows.push_back({});  // a buffer must not be empty
  gs.emissiveTriangles = rhi::createBufferWithData(ctx, std::as_bytes(std::span(list.rows)),
                                                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "emissive-triangles");
}

}  // namespace

void uploadEmissiveTriangles(rhi::Context& ctx, const scene::Scene& scene,
                             const std::vector<uint32_t>& meshFirstGeometry, GpuScene& gs) {
  EmissiveList list = emissiveList(scene, scene, meshFirstGeometry);
  gs.emissiveFollowsPose = list.followsPose;
  if (list.followsPose) gs.meshFirstGeometry = meshFirstGeometry;
  store(ctx, std::move(list), gs);
}

void poseEmissiveTriangles(rhi::Context& ctx, const scene::Scene& scene, const scene::Scene& pose, GpuScene& gs) {
  if (!gs.emissiveFollowsPose) return;
  EmissiveList list = emissiveList(scene, pose, gs.meshFirstGeometry);
  ctx.waitIdle();  // the old list may still be read by the frame that posed the scene
  store(ctx, std::move(list), gs);
}

}  // namespace rayster::render
