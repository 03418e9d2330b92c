// The path tracer's emissive-triangle light list: every triangle of a shadow-casting instance whose
// material emits (emissive factor > 0), in world space at upload, with an area-weighted CDF.
// Area-weighted rather than power-weighted: the pick then has the same density (1 / total area)
// on every emitter, so the MIS weight of a BSDF ray that hits one needs no table lookup; scenes
// whose emitters differ greatly in radiance pay some variance for it. Textured emission is
// evaluated per sample (TEXCOORD_0). Animated instances keep their upload-time positions here.
// Emissive analytic spheres are not in the list: BSDF rays find them (with MIS weight 1).
// Unlit materials (KHR_materials_unlit) are emitters of their base colour (× texture × vertex
// colour, looked up through `geometry` and `primitive`): the path tracer sees them with the same
// radiance from every direction, so they join the list and MIS stays unbiased for them.

#include <algorithm>

#include "render/gpu_scene.h"
#include "rhi/context.h"
#include "rhi/resources.h"

namespace rayster::render {

void uploadEmissiveTriangles(rhi::Context& ctx, const scene::Scene& scene,
                             const std::vector<uint32_t>& meshFirstGeometry, GpuScene& gs) {
  std::vector<gpu::EmissiveTriangle> rows;
  double area = 0;
  for (const scene::Instance& inst : scene.instances) {
    if (!inst.castsShadows) continue;  // a light's visible shape: the light itself is sampled
    const scene::Mesh& mesh = scene.meshes[inst.mesh];
    // A mirroring transform turns the world winding: the sampler's front is cross(p1 − p0, p2 − p0) ×
    // frontSign (single-sided emitters light only their front).
    const bool mirrored = glm::determinant(glm::mat3(inst.worldFromObject)) < 0.0f;
    for (size_t primIndex = 0; primIndex < mesh.primitives.size(); ++primIndex) {
      const scene::Primitive& prim = mesh.primitives[primIndex];
      if (prim.material >= scene.materials.size()) continue;
      const scene::Material& material = scene.materials[prim.material];
      const glm::vec3 e = material.unlit ? glm::vec3(material.baseColor) : material.emissive;
      if (std::max(e.x, std::max(e.y, e.z)) <= 0.0f) continue;
      for (size_t i = 0; i + 2 < prim.indices.size(); i += 3) {
        gpu::EmissiveTriangle t{};
        glm::vec3* p[3] = {&t.p0, &t.p1, &t.p2};
        glm::vec2* uv[3] = {&t.uv0, &t.uv1, &t.uv2};
        for (int k = 0; k < 3; ++k) {
          const uint32_t v = prim.indices[i + k];
          *p[k] = glm::vec3(inst.worldFromObject * glm::vec4(prim.positions[v], 1.0f));
          *uv[k] = v < prim.uvs.size() ? prim.uvs[v] : glm::vec2(0.0f);
        }
        const float a = 0.5f * glm::length(glm::cross(t.p1 - t.p0, t.p2 - t.p0));
        if (!(a > 0.0f)) continue;
        area += a;
        t.cdf = float(area);
        t.material = prim.material;
        t.frontSign = mirrored ? -1.0f : 1.0f;
        t.geometry = meshFirstGeometry[inst.mesh] + uint32_t(primIndex);
        t.primitive = uint32_t(i / 3);
        rows.push_back(t);
      }
    }
  }
  for (auto& t : rows) t.cdf = float(t.cdf / area);
  if (!rows.empty()) rows.back().cdf = 1.0f;
  gs.emissiveTriangleCount = uint32_t(rows.size());
  gs.emissiveArea = float(area);
  if (rows.empty()) rows.push_back({});  // a buffer must not be empty
  gs.emissiveTriangles = rhi::createBufferWithData(ctx, std::as_bytes(std::span(rows)),
                                                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "emissive-triangles");
}

}  // namespace rayster::render
