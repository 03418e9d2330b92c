#include "scene/geometry.h"

#include <cmath>

#include <glm/gtc/constants.hpp>

namespace rayster::scene {
namespace {

// Appends a quad that faces away from `inside` whatever order the corners were given in.
void appendQuadFacingAway(Primitive& prim, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 inside) {
  const glm::vec3 normal = glm::cross(c - a, d - b);
  const glm::vec3 centre = (a + b + c + d) * 0.25f;
  if (glm::dot(normal, centre - inside) < 0.0f)
    appendQuad(prim, d, c, b, a);
  else
    appendQuad(prim, a, b, c, d);
}

}  // namespace

Primitive makeUvSphere(float radius, int rings, int segments, uint32_t material) {
  RAYSTER_ASSERT(rings >= 2 && segments >= 3, "sphere needs at least 2 rings and 3 segments");
  Primitive prim;
  prim.material = material;
  // segments + 1 columns: the seam vertices are duplicated so uvs do not wrap backwards.
  for (int i = 0; i <= rings; ++i) {
    const float theta = glm::pi<float>() * static_cast<float>(i) / static_cast<float>(rings);
    for (int j = 0; j <= segments; ++j) {
      const float phi = glm::two_pi<float>() * static_cast<float>(j) / static_cast<float>(segments);
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      prim.positions.push_back(n * radius);
      prim.normals.push_back(n);
      prim.uvs.emplace_back(static_cast<float>(j) / static_cast<float>(segments),
                            static_cast<float>(i) / static_cast<float>(rings));
    }
  }
  const auto vertex = [segments](int i, int j) { return static_cast<uint32_t>(i * (segments + 1) + j); };
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const uint32_t a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1), d = vertex(i, j + 1);
      // Skip the triangle that collapses at each pole: degenerate triangles waste BLAS memory.
      if (i != rings - 1) prim.indices.insert(prim.indices.end(), {a, c, b});
      if (i != 0) prim.indices.insert(prim.indices.end(), {a, d, c});
    }
  }
  return prim;
}

void appendQuad(Primitive& prim, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
  const glm::vec3 normal = glm::normalize(glm::cross(c - a, d - b));
  const auto base = static_cast<uint32_t>(prim.positions.size());
  for (const glm::vec3& p : {a, b, c, d}) {
    prim.positions.push_back(p);
    prim.normals.push_back(normal);
  }
  // Keep uvs consistent: either every vertex has them or none (validate() checks this).
  if (!prim.uvs.empty() || base == 0) prim.uvs.insert(prim.uvs.end(), {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  prim.indices.insert(prim.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

Primitive makeQuad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, uint32_t material) {
  Primitive prim;
  prim.material = material;
  appendQuad(prim, a, b, c, d);
  return prim;
}

Primitive makeBox(glm::vec3 min, glm::vec3 max, uint32_t material) {
  const std::array<glm::vec2, 4> footprint{glm::vec2(min.x, min.z), glm::vec2(max.x, min.z), glm::vec2(max.x, max.z),
                                           glm::vec2(min.x, max.z)};
  return makePrism(footprint, min.y, max.y, /*capBottom=*/true, material);
}

Primitive makePrism(const std::array<glm::vec2, 4>& footprintXz, float y0, float y1, bool capBottom,
                    uint32_t material) {
  Primitive prim;
  prim.material = material;
  std::array<glm::vec3, 4> bottom, top;
  glm::vec3 centre(0.0f);
  for (size_t k = 0; k < 4; ++k) {
    bottom[k] = glm::vec3(footprintXz[k].x, y0, footprintXz[k].y);
    top[k] = glm::vec3(footprintXz[k].x, y1, footprintXz[k].y);
    centre += (bottom[k] + top[k]) * 0.125f;
  }
  appendQuadFacingAway(prim, top[0], top[1], top[2], top[3], centre);
  for (size_t k = 0; k < 4; ++k) {
    const size_t n = (k + 1) % 4;
    appendQuadFacingAway(prim, bottom[k], bottom[n], top[n], top[k], centre);
  }
  if (capBottom) appendQuadFacingAway(prim, bottom[0], bottom[1], bottom[2], bottom[3], centre);
  return prim;
}

}  // namespace rayster::scene
