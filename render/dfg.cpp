#include "render/dfg.h"

#include <algorithm>
#include <cmath>

#include "shaders/shared/vndf.h"

namespace rayster::render {
namespace {

float radicalInverse(uint32_t bits) {
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return float(bits) * 2.3283064365386963e-10f;
}

}  // namespace

glm::vec2 integrateDfg(float nv, float roughness, uint32_t samples) {
  // n·v = 0 has no visible normals; the grazing texel uses a nearly grazing view instead.
  nv = std::clamp(nv, 1e-3f, 1.0f);
  const float alpha = roughness * roughness;
  const glm::vec3 v(std::sqrt(1.0f - nv * nv), 0.0f, nv);
  double a = 0, b = 0;
  for (uint32_t i = 0; i < samples; ++i) {
    const glm::vec2 u((i + 0.5f) / float(samples), radicalInverse(i));  // Hammersley
    const glm::vec3 h = gpu::sampleGgxVndf(v, alpha, u);
    const float vh = glm::dot(v, h);
    const glm::vec3 l = 2.0f * vh * h - v;
    if (l.z <= 0.0f) continue;  // reflected below the surface: weight 0
    const float w = gpu::smithG2OverG1(nv, l.z, alpha);
    const float fc = std::pow(1.0f - std::clamp(vh, 0.0f, 1.0f), 5.0f);
    a += (1.0f - fc) * w;
    b += fc * w;
  }
  return glm::vec2(float(a / samples), float(b / samples));
}

std::vector<glm::vec2> computeDfgTable(uint32_t size, uint32_t samples) {
  std::vector<glm::vec2> table(size_t(size) * size);
  for (uint32_t j = 0; j < size; ++j)
    for (uint32_t i = 0; i < size; ++i)
      table[size_t(j) * size + i] = integrateDfg(float(i) / float(size - 1), float(j) / float(size - 1), samples);
  return table;
}

}  // namespace rayster::render
