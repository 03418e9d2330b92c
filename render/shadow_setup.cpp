#include "render/shadow_setup.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace rayster::render {
namespace {

std::array<glm::vec3, 8> corners(const scene::Aabb& b) {
  std::array<glm::vec3, 8> c;
  for (int i = 0; i < 8; ++i) c[i] = {i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z};
  return c;
}

// Any vector not parallel to `dir`, as the up axis of a light's view.
glm::vec3 upFor(glm::vec3 dir) { return std::abs(dir.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0); }

// Reversed-Z perspective (near → 1, far → 0), like the camera's.
glm::mat4 reversedPerspective(float fov, float nearPlane, float farPlane) {
  return glm::perspective(fov, 1.0f, farPlane, nearPlane);
}

gpu::ShadowView perspectiveView(glm::vec3 eye, glm::vec3 dir, glm::vec3 up, float fov, float nearPlane,
                                float farPlane) {
  gpu::ShadowView v{};
  v.clipFromWorld = reversedPerspective(fov, nearPlane, farPlane) * glm::lookAt(eye, eye + dir, up);
  v.nearPlane = nearPlane;
  v.farPlane = farPlane;
  v.texelWorld = 2.0f * std::tan(0.5f * fov) / float(kShadowTileSize);
  v.perspective = 1;
  return v;
}

}  // namespace

std::vector<float> cascadeSplits(float nearPlane, float farPlane, uint32_t count, float lambda) {
  std::vector<float> ends(count);
  for (uint32_t i = 0; i < count; ++i) {
    const float f = float(i + 1) / float(count);
    const float logSplit = nearPlane * std::pow(farPlane / nearPlane, f);
    const float uniformSplit = nearPlane + (farPlane - nearPlane) * f;
    ends[i] = lambda * logSplit + (1.0f - lambda) * uniformSplit;
  }
  ends.back() = farPlane;
  return ends;
}

ShadowAtlas planShadowAtlas(const scene::Scene& scene, scene::Aabb bounds, const scene::Camera& cam, float aspect,
                            uint32_t shadowLights) {
  ShadowAtlas atlas;
  gpu::ShadowSetup& s = atlas.setup;
  if (!bounds.valid()) bounds = {glm::vec3(-1.0f), glm::vec3(1.0f)};
  const auto box = corners(bounds);
  const float diagonal = std::max(glm::length(bounds.max - bounds.min), 1e-3f);
  const glm::vec3 forward = glm::normalize(cam.target - cam.position);
  s.cameraForward = glm::vec4(forward, 0.0f);
  s.pcfRadius = kShadowPcfRadius;

  // Shadows reach as far as the scene does, not to the (often huge) far plane.
  float sceneFar = cam.zNear * 2.0f;
  for (const glm::vec3& c : box) sceneFar = std::max(sceneFar, glm::dot(c - cam.position, forward));
  const float shadowFar = std::min(cam.zFar, sceneFar);
  const std::vector<float> ends = cascadeSplits(cam.zNear, shadowFar, gpu::kShadowCascades, kCascadeSplitLambda);
  for (uint32_t i = 0; i < gpu::kShadowCascades; ++i) s.cascadeEnds[int(i)] = ends[i];

  const glm::vec3 camRight = glm::normalize(glm::cross(forward, cam.up));
  const glm::vec3 camUp = glm::cross(camRight, forward);
  const float tanY = std::tan(0.5f * cam.yFov), tanX = tanY * aspect;

  std::vector<gpu::ShadowView> views;
  std::vector<glm::vec4>& rays = atlas.lightRays;
  const uint32_t count =
      std::min<uint32_t>(uint32_t(scene.lights.size()), std::min(shadowLights, gpu::kMaxShadowLights));
  for (uint32_t li = 0; li < count; ++li) {
    const scene::Light& light = scene.lights[li];
    gpu::ShadowLight& sl = s.lights[li];
    sl.firstView = uint32_t(views.size());
    if (light.type == scene::LightType::Directional) {
      sl.kind = gpu::kShadowCascaded;
      const glm::vec3 dir = glm::normalize(light.direction);
      float start = cam.zNear;
      for (uint32_t c = 0; c < gpu::kShadowCascades; ++c) {
        // The slice's bounding sphere: its size does not change as the camera turns, so the
        // texel grid can be snapped and edges do not shimmer.
        std::array<glm::vec3, 8> slice;
        for (int k = 0; k < 8; ++k) {
          const float d = k & 4 ? ends[c] : start;
          slice[k] = cam.position + forward * d + camRight * ((k & 1 ? 1.0f : -1.0f) * tanX * d) +
                     camUp * ((k & 2 ? 1.0f : -1.0f) * tanY * d);
        }
        glm::vec3 centre(0.0f);
        for (const glm::vec3& p : slice) centre += p / 8.0f;
        float radius = 0.0f;
        for (const glm::vec3& p : slice) radius = std::max(radius, glm::length(p - centre));
        radius = std::min(radius, 0.5f * diagonal + glm::length(centre - bounds.centre()));
        const glm::mat4 view = glm::lookAt(centre - dir, centre, upFor(dir));
        const float texel = 2.0f * radius / float(kShadowTileSize);
        glm::vec4 snapped = view * glm::vec4(centre, 1.0f);
        snapped.x = std::floor(snapped.x / texel) * texel;
        snapped.y = std::floor(snapped.y / texel) * texel;
        // Depth covers every caster in the scene, in front of the slice or behind it.
        float zMin = 1e30f, zMax = -1e30f;
        for (const glm::vec3& p : box) {
          const float z = -(view * glm::vec4(p, 1.0f)).z;
          zMin = std::min(zMin, z);
          zMax = std::max(zMax, z);
        }
        zMin -= 0.01f * diagonal;
        zMax += 0.01f * diagonal;
        gpu::ShadowView v{};
        // Reversed Z: glm::ortho maps -near → 0 and -far → 1, so swap the planes.
        v.clipFromWorld =
            glm::ortho(snapped.x - radius, snapped.x + radius, snapped.y - radius, snapped.y + radius, zMax, zMin) *
            view;
        v.nearPlane = zMin;
        v.farPlane = zMax;
        v.texelWorld = texel;
        v.perspective = 0;
        views.push_back(v);
        rays.push_back(glm::vec4(dir, 0.0f));
        start = ends[c];
      }
    } else {
      float reach = 0.0f;
      for (const glm::vec3& c : box) reach = std::max(reach, glm::length(c - light.position));
      const float farPlane = std::max(reach * 1.01f, 1e-2f);
      const float nearPlane = std::max(1e-3f * diagonal, 1e-4f);
      if (light.type == scene::LightType::Spot) {
        sl.kind = gpu::kShadowSpot;
        const glm::vec3 dir = glm::normalize(light.direction);
        const float fov = std::min(2.0f * light.outerConeAngle + 0.1f, glm::radians(170.0f));
        views.push_back(perspectiveView(light.position, dir, upFor(dir), fov, nearPlane, farPlane));
        rays.push_back(glm::vec4(light.position, 1.0f));
      } else {
        sl.kind = gpu::kShadowCube;
        // Cube face order and up axes of the Vulkan cube-map convention.
        const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
        for (int f = 0; f < 6; ++f) {
          views.push_back(perspectiveView(light.position, dirs[f], ups[f], glm::radians(90.0f), nearPlane, farPlane));
          rays.push_back(glm::vec4(light.position, 1.0f));
        }
      }
    }
  }

  s.viewCount = uint32_t(views.size());
  const uint32_t n = std::max<uint32_t>(s.viewCount, 1);
  atlas.columns = std::min(n, kShadowAtlasColumns);
  atlas.rows = (n + atlas.columns - 1) / atlas.columns;
  const float w = float(atlas.columns * kShadowTileSize), h = float(atlas.rows * kShadowTileSize);
  s.atlasTexel = {1.0f / w, 1.0f / h};
  for (uint32_t i = 0; i < s.viewCount; ++i) {
    const ShadowAtlas::Tile t{(i % atlas.columns) * kShadowTileSize, (i / atlas.columns) * kShadowTileSize};
    atlas.tiles.push_back(t);
    views[i].tile = {float(t.x) / w, float(t.y) / h, float(kShadowTileSize) / w, float(kShadowTileSize) / h};
    s.views[i] = views[i];
  }
  return atlas;
}

}  // namespace rayster::render
