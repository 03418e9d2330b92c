// GGX visible-normal sampling (Heitz, "Sampling the GGX Distribution of Visible Normals", JCGT 2018)
// and the height-correlated Smith terms of its weight (docs/techniques.md §13). Compiled as GLSL by the
// specular pass and as C++ by the DFG table (render/dfg.cpp) and the unit tests, so the sampler the
// tests check is the sampler the GPU runs. Everything is in the tangent frame: N = +z, V and L point
// away from the surface, α = roughness².
#ifndef RAYSTER_SHARED_VNDF_H
#define RAYSTER_SHARED_VNDF_H

#ifdef __cplusplus
#include <cmath>

#include "shaders/shared/types.h"
namespace rayster::gpu {
using glm::cross;
using glm::dot;
using glm::inversesqrt;
using glm::max;
using glm::normalize;
using std::cos;
using std::sin;
using std::sqrt;
#define RAYSTER_FN inline
#else
#include "shared/types.h"
#define RAYSTER_FN
#endif

RAYSTER_CONST float kVndfPi = 3.14159265358979f;

// A microfacet normal H distributed as D_V(H) = G1(V)·max(0, V·H)·D(H) / V.z, from u in [0,1)², for
// GGX with α `ax` along the tangent frame's x and `ay` along its y (anisotropic: stretched the same way).
RAYSTER_FN vec3 sampleGgxVndfAniso(vec3 v, float ax, float ay, vec2 u) {
  // Stretch V so the GGX lobe becomes the hemisphere of a unit-roughness configuration.
  vec3 vh = normalize(vec3(ax * v.x, ay * v.y, v.z));
  float lensq = vh.x * vh.x + vh.y * vh.y;
  vec3 t1 = lensq > 0.0f ? vec3(-vh.y, vh.x, 0.0f) * inversesqrt(lensq) : vec3(1.0f, 0.0f, 0.0f);
  vec3 t2 = cross(vh, t1);
  // A point on the disk, warped to the part of the hemisphere V sees (its projected area).
  float r = sqrt(u.x);
  float phi = 2.0f * kVndfPi * u.y;
  float p1 = r * cos(phi);
  float p2 = r * sin(phi);
  float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * sqrt(max(0.0f, 1.0f - p1 * p1)) + s * p2;
  vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  // Unstretch; the floor on z keeps α = 0 (exactly the mirror normal) free of 0/0.
  return normalize(vec3(ax * nh.x, ay * nh.y, max(1e-7f, nh.z)));
}
RAYSTER_FN vec3 sampleGgxVndf(vec3 v, float alpha, vec2 u) { return sampleGgxVndfAniso(v, alpha, alpha, u); }

// Isotropic GGX normal distribution D(H) for cosθ_H = nh.
RAYSTER_FN float ggxDistribution(float nh, float alpha) {
  float a2 = alpha * alpha;
  float d = nh * nh * (a2 - 1.0f) + 1.0f;
  return a2 / (kVndfPi * d * d);
}

// Smith Λ for GGX at a direction with cosine `c` to the normal.
RAYSTER_FN float smithLambda(float c, float alpha) {
  float c2 = max(c * c, 1e-12f);
  float t2 = max(0.0f, 1.0f - c2) / c2;
  return 0.5f * (-1.0f + sqrt(1.0f + alpha * alpha * t2));
}
RAYSTER_FN float smithG1(float nv, float alpha) { return 1.0f / (1.0f + smithLambda(nv, alpha)); }
// Height-correlated G2(V, L) / G1(V): the VNDF sample's weight without Fresnel.
RAYSTER_FN float smithG2OverG1(float nv, float nl, float alpha) {
  float lv = smithLambda(nv, alpha);
  return (1.0f + lv) / (1.0f + lv + smithLambda(nl, alpha));
}

// Density of sampleGgxVndf() over microfacet normals (solid angle of H); the density of the
// reflected direction L is this / (4·V·H).
RAYSTER_FN float ggxVndfPdf(vec3 v, vec3 h, float alpha) {
  return smithG1(v.z, alpha) * max(0.0f, dot(v, h)) * ggxDistribution(h.z, alpha) / v.z;
}

#ifdef __cplusplus
}  // namespace rayster::gpu
#endif

#endif
