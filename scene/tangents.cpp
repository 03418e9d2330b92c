#include "scene/tangents.h"

#include <cmath>

namespace rayster::scene {

namespace {
glm::vec3 anyPerpendicular(glm::vec3 n) {
  glm::vec3 a = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(glm::cross(a, n));
}
}  // namespace

void generateTangents(Primitive& prim) {
  const size_t n = prim.positions.size();
  prim.tangents.assign(n, glm::vec4(0.0f));
  if (prim.uvs.size() != n || prim.normals.size() != n) {
    for (size_t i = 0; i < n; ++i)
      prim.tangents[i] =
          glm::vec4(anyPerpendicular(prim.normals.size() == n ? prim.normals[i] : glm::vec3(0, 1, 0)), 1);
    return;
  }
  std::vector<glm::vec3> tan(n, glm::vec3(0.0f)), bitan(n, glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
    const uint32_t i0 = prim.indices[t], i1 = prim.indices[t + 1], i2 = prim.indices[t + 2];
    const glm::vec3 e1 = prim.positions[i1] - prim.positions[i0], e2 = prim.positions[i2] - prim.positions[i0];
    const glm::vec2 d1 = prim.uvs[i1] - prim.uvs[i0], d2 = prim.uvs[i2] - prim.uvs[i0];
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (std::abs(det) < 1e-12f) continue;
    // Unnormalised: larger triangles weigh more, as their frames are better conditioned.
    const glm::vec3 sdir = (e1 * d2.y - e2 * d1.y) / det;
    const glm::vec3 tdir = (e2 * d1.x - e1 * d2.x) / det;
    for (uint32_t i : {i0, i1, i2}) {
      tan[i] += sdir;
      bitan[i] += tdir;
    }
  }
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3 nrm = prim.normals[i];
    glm::vec3 t = tan[i] - nrm * glm::dot(nrm, tan[i]);
    const float len = glm::length(t);
    t = len > 1e-8f && std::isfinite(len) ? t / len : anyPerpendicular(nrm);
    const float w = glm::dot(glm::cross(nrm, t), bitan[i]) < 0.0f ? -1.0f : 1.0f;
    prim.tangents[i] = glm::vec4(t, w);
  }
}

}  // namespace rayster::scene
