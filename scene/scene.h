#pragma once
// The CPU scene model every loader produces and every renderer consumes. Plain data, no Vulkan:
// render/ uploads it, tests inspect it directly.
#include <cfloat>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/error.h"

namespace rayster::scene {

// glTF metallic-roughness subset; textures and transmission are added as loaders need them.
struct Material {
  std::string name;
  glm::vec4 baseColor{1.0f};
  float metallic = 0.0f;
  float roughness = 1.0f;
  glm::vec3 emissive{0.0f}; // linear radiance, strength folded in
  bool doubleSided = false;
};

struct Primitive {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs; // may be empty
  std::vector<uint32_t> indices; // triangle list, counter-clockwise seen from the front
  uint32_t material = 0;
};

struct Mesh {
  std::string name;
  std::vector<Primitive> primitives;
};

struct Instance {
  std::string name;
  uint32_t mesh = 0;
  glm::mat4 worldFromObject{1.0f};
  bool castsShadows = true; // false for the visible shape of an area light
};

enum class LightType { Point, Spot, Directional };

struct Light {
  std::string name;
  LightType type = LightType::Point;
  glm::vec3 position{0.0f};
  glm::vec3 direction{0, -1, 0}; // direction light travels, for spot/directional
  glm::vec3 color{1.0f};
  float intensity = 1.0f;        // W/sr-like radiant intensity for point/spot; irradiance for directional
  float radius = 0.0f;           // sphere light radius, 0 = hard point
  float angularRadius = 0.0f;    // directional, radians
  float innerConeAngle = 0.0f, outerConeAngle = 0.7853982f;
};

struct Camera {
  std::string name;
  glm::vec3 position{0, 0, 5};
  glm::vec3 target{0.0f};
  glm::vec3 up{0, 1, 0};
  float yFov = 0.7f; // radians
  float zNear = 0.05f;
  float zFar = 100.0f;
};

struct Aabb {
  glm::vec3 min{FLT_MAX}, max{-FLT_MAX};
  void extend(glm::vec3 p);
  bool valid() const;
  glm::vec3 centre() const { return (min + max) * 0.5f; }
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Instance> instances;
  std::vector<Light> lights;
  std::vector<Camera> cameras;
  glm::vec3 ambient{0.0f}; // uniform ambient radiance, stand-in for indirect light until RT indirect exists

  Aabb bounds() const; // world-space, over all instances
  size_t triangleCount() const; // over all instances, i.e. what the TLAS holds
};

// Checks what the renderer would otherwise crash on or silently mis-draw. Failures are
// ExitCode::BadInput with a message naming the mesh/primitive/instance.
Status validate(const Scene& scene);

} // namespace rayster::scene
