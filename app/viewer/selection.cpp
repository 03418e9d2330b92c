#include "app/viewer/selection.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

namespace rayster::app {
namespace {

// The object-space bounds of a mesh (primitives and spheres).
scene::Aabb meshBounds(const scene::Mesh& mesh) {
  scene::Aabb box;
  for (const scene::Primitive& prim : mesh.primitives)
    for (const glm::vec3& p : prim.positions) box.extend(p);
  for (const scene::Sphere& s : mesh.spheres) {
    box.extend(s.center - glm::vec3(s.radius));
    box.extend(s.center + glm::vec3(s.radius));
  }
  return box;
}

// Slab test; returns the entry distance (0 inside), or infinity on a miss. Flat boxes (a quad)
// get a sliver of thickness so that rays still enter them.
float enterBox(glm::vec3 origin, glm::vec3 dir, scene::Aabb box) {
  const glm::vec3 pad = glm::max(glm::vec3(1e-4f), (box.max - box.min) * 1e-3f);
  box.min -= pad;
  box.max += pad;
  float t0 = 0.0f, t1 = std::numeric_limits<float>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (std::abs(dir[a]) < 1e-12f) {
      if (origin[a] < box.min[a] || origin[a] > box.max[a]) return std::numeric_limits<float>::infinity();
      continue;
    }
    float n = (box.min[a] - origin[a]) / dir[a], f = (box.max[a] - origin[a]) / dir[a];
    if (n > f) std::swap(n, f);
    t0 = std::max(t0, n);
    t1 = std::min(t1, f);
  }
  // A box around the camera (a room) would hide everything in it: only boxes in front count.
  return t0 > 0.0f && t0 <= t1 ? t0 : std::numeric_limits<float>::infinity();
}

}  // namespace

Trs decompose(const glm::mat4& m) {
  Trs t;
  t.position = glm::vec3(m[3]);
  glm::vec3 x(m[0]), y(m[1]), z(m[2]);
  t.scale = {glm::length(x), glm::length(y), glm::length(z)};
  if (glm::determinant(glm::mat3(m)) < 0.0f) t.scale.x = -t.scale.x;
  const glm::mat3 r(x / t.scale.x, y / t.scale.y, z / t.scale.z);
  // R = Rz·Ry·Rx (XYZ order, as compose builds it).
  const float sy = std::clamp(-r[0][2], -1.0f, 1.0f);
  const float ry = std::asin(sy);
  float rx, rz;
  if (std::abs(sy) < 0.9999f) {
    rx = std::atan2(r[1][2], r[2][2]);
    rz = std::atan2(r[0][1], r[0][0]);
  } else {  // gimbal lock: all rotation about one axis
    rx = std::atan2(-r[2][1], r[1][1]);
    rz = 0.0f;
  }
  t.rotationDeg = glm::degrees(glm::vec3(rx, ry, rz));
  return t;
}

glm::mat4 compose(const Trs& t) {
  const glm::vec3 r = glm::radians(t.rotationDeg);
  glm::mat4 m = glm::translate(glm::mat4(1.0f), t.position);
  m = glm::rotate(m, r.z, {0, 0, 1});
  m = glm::rotate(m, r.y, {0, 1, 0});
  m = glm::rotate(m, r.x, {1, 0, 0});
  return glm::scale(m, t.scale);
}

int32_t pickInstance(const scene::Scene& scene, const std::vector<glm::mat4>& transforms, const scene::Camera& cam,
                     glm::vec2 pixel, glm::vec2 size) {
  const glm::vec3 forward = glm::normalize(cam.target - cam.position);
  const glm::vec3 right = glm::normalize(glm::cross(forward, cam.up));
  const glm::vec3 up = glm::cross(right, forward);
  const float tanHalf = std::tan(0.5f * cam.yFov);
  const glm::vec2 ndc = (pixel + 0.5f) / size * 2.0f - 1.0f;
  const glm::vec3 dir = forward + right * (ndc.x * tanHalf * size.x / size.y) - up * (ndc.y * tanHalf);
  int32_t best = -1;
  float bestT = std::numeric_limits<float>::infinity();
  for (size_t i = 0; i < scene.instances.size() && i < transforms.size(); ++i) {
    const scene::Instance& inst = scene.instances[i];
    if (inst.mesh >= scene.meshes.size() || !inst.castsShadows) continue;  // skip lights' visible shapes
    const scene::Aabb box = meshBounds(scene.meshes[inst.mesh]);
    if (!box.valid()) continue;
    // In object space the ray's parameter is the world one (the direction is not renormalised).
    const glm::mat4 objectFromWorld = glm::inverse(transforms[i]);
    const glm::vec3 o(objectFromWorld * glm::vec4(cam.position, 1.0f)), d(objectFromWorld * glm::vec4(dir, 0.0f));
    const float t = enterBox(o, d, box);
    if (t < bestT) bestT = t, best = int32_t(i);
  }
  return best;
}

glm::vec3 dragOffset(const scene::Camera& cam, glm::vec3 point, glm::vec2 delta, float height) {
  const glm::vec3 forward = glm::normalize(cam.target - cam.position);
  const glm::vec3 right = glm::normalize(glm::cross(forward, cam.up));
  const glm::vec3 up = glm::cross(right, forward);
  const float depth = std::max(1e-3f, glm::dot(point - cam.position, forward));
  const float unitsPerPixel = 2.0f * depth * std::tan(0.5f * cam.yFov) / std::max(1.0f, height);
  return (right * delta.x - up * delta.y) * unitsPerPixel;
}

}  // namespace rayster::app
