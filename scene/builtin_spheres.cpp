// Analytic spheres (AABB geometry + intersection shader) on a triangle floor, so one frame mixes
// both BLAS kinds. A 5 x 3 grid spans the material space: diffuse colours at the back, metals of
// rising roughness in the middle, dielectrics (one of them glass) at the front.
#include <array>
#include <utility>

#include <glm/gtc/constants.hpp>

#include "scene/builtin.h"
#include "scene/builtin_parts.h"

namespace rayster::scene {
namespace {

using namespace builtin;

constexpr int kColumns = 5;
constexpr float kRadius = 0.45f;
constexpr float kSpacing = 1.2f;  // leaves a 0.3 m gap: contact shadows and reflections stay apart

Material diffuse(const char* name, glm::vec3 colour) {
  Material m;
  m.name = name;
  m.baseColor = glm::vec4(colour, 1.0f);
  m.roughness = 0.9f;
  return m;
}

Material metal(const char* name, glm::vec3 colour, float roughness) {
  Material m;
  m.name = name;
  m.baseColor = glm::vec4(colour, 1.0f);
  m.metallic = 1.0f;
  m.roughness = roughness;
  return m;
}

Material dielectric(const char* name, glm::vec3 colour, float roughness) {
  Material m = diffuse(name, colour);
  m.roughness = roughness;
  return m;
}

Material glass() {
  Material m;
  m.name = "glass";
  m.baseColor = glm::vec4(1.0f);
  m.roughness = 0.0f;
  m.transmission = 1.0f;
  m.ior = 1.5f;
  m.thickness = 2.0f * kRadius;  // solid: refracts like a lens, not a bubble
  return m;
}

// Rows back to front; metal colours are the F0 values of gold, copper, silver, iron, aluminium.
std::array<std::array<Material, kColumns>, 3> materialGrid() {
  return {{
      {diffuse("red", {0.7f, 0.08f, 0.06f}), diffuse("orange", {0.8f, 0.35f, 0.05f}),
       diffuse("yellow", {0.8f, 0.7f, 0.1f}), diffuse("green", {0.12f, 0.5f, 0.1f}),
       diffuse("blue", {0.08f, 0.15f, 0.7f})},
      {metal("gold", {1.0f, 0.78f, 0.34f}, 0.0f), metal("copper", {0.95f, 0.64f, 0.54f}, 0.15f),
       metal("silver", {0.97f, 0.96f, 0.91f}, 0.3f), metal("iron", {0.56f, 0.57f, 0.58f}, 0.5f),
       metal("aluminium", {0.91f, 0.92f, 0.92f}, 0.8f)},
      {dielectric("white-gloss", {0.85f, 0.85f, 0.85f}, 0.05f), dielectric("teal-gloss", {0.1f, 0.5f, 0.5f}, 0.2f),
       glass(), dielectric("purple-satin", {0.4f, 0.15f, 0.6f}, 0.45f),
       dielectric("black-gloss", {0.03f, 0.03f, 0.03f}, 0.1f)},
  }};
}

}  // namespace

Scene makeSpheresScene() {
  Scene scene;
  scene.name = "spheres";
  scene.environment = blueSky();

  Material ground;
  ground.name = "ground";
  ground.baseColor = glm::vec4(0.5f, 0.5f, 0.48f, 1.0f);
  ground.roughness = 0.8f;
  addFloor(scene, glm::vec3(0.0f), 30.0f, addMaterial(scene, std::move(ground)));

  // All spheres in one mesh: one AABB BLAS, one instance.
  Mesh spheres;
  spheres.name = "spheres";
  const auto grid = materialGrid();
  for (size_t row = 0; row < grid.size(); ++row) {
    for (int column = 0; column < kColumns; ++column) {
      Sphere s;
      s.center = glm::vec3((column - (kColumns - 1) * 0.5f) * kSpacing, kRadius, (float(row) - 1.0f) * kSpacing);
      s.radius = kRadius;
      s.material = addMaterial(scene, grid[row][column]);
      spheres.spheres.push_back(s);
    }
  }
  scene.meshes.push_back(std::move(spheres));
  addInstance(scene, "spheres", static_cast<uint32_t>(scene.meshes.size() - 1));

  // From the camera's right, behind it and high: shadows fall back and to the left, in view.
  addSun(scene, glm::vec3(-0.5f, -1.0f, -0.6f), 3.0f);

  Camera camera;
  camera.name = "default";
  camera.position = glm::vec3(0.0f, 2.6f, 6.5f);
  camera.target = glm::vec3(0.0f, 0.3f, 0.0f);
  camera.yFov = glm::radians(40.0f);
  camera.zNear = 0.05f;
  camera.zFar = 60.0f;
  scene.cameras.push_back(camera);
  return scene;
}

}  // namespace rayster::scene
