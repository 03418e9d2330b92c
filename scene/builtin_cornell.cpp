#include <array>
#include <cmath>
#include <utility>

#include <glm/gtc/constants.hpp>

#include "scene/builtin.h"
#include "scene/geometry.h"

namespace rayster::scene {
namespace {

// The measured data is in millimetres; 0.01 gives a ~5.5 m room, large enough that the default
// near plane and ray epsilons need no special casing.
constexpr float kScale = 0.01f;

glm::vec3 mm(float x, float y, float z) { return glm::vec3(x, y, z) * kScale; }

// Sphere tessellation: fine enough that the silhouette of the visible light looks round at 1080p.
constexpr int kLightRings = 16;
constexpr int kLightSegments = 32;

uint32_t addMaterial(Scene& scene, Material material) {
  scene.materials.push_back(std::move(material));
  return static_cast<uint32_t>(scene.materials.size() - 1);
}

void addObject(Scene& scene, std::string name, Primitive prim, bool castsShadows = true) {
  Mesh mesh;
  mesh.name = name;
  mesh.primitives.push_back(std::move(prim));
  scene.meshes.push_back(std::move(mesh));
  Instance instance;
  instance.name = std::move(name);
  instance.mesh = static_cast<uint32_t>(scene.meshes.size() - 1);
  instance.castsShadows = castsShadows;
  scene.instances.push_back(std::move(instance));
}

}  // namespace

Scene makeCornellBox() {
  Scene scene;
  scene.name = "cornell";
  // A little ambient stands in for the interreflection when RT indirect light is off.
  scene.ambient = glm::vec3(0.02f);

  const uint32_t white = addMaterial(scene, {"white", glm::vec4(0.725f, 0.71f, 0.68f, 1.0f), 0.0f, 1.0f, {}, false});
  const uint32_t red = addMaterial(scene, {"red", glm::vec4(0.63f, 0.065f, 0.05f, 1.0f), 0.0f, 1.0f, {}, false});
  const uint32_t green = addMaterial(scene, {"green", glm::vec4(0.14f, 0.45f, 0.091f, 1.0f), 0.0f, 1.0f, {}, false});
  // The tall block is a near-mirror so the default scene exercises RT reflections.
  const uint32_t mirror = addMaterial(scene, {"mirror", glm::vec4(0.95f, 0.95f, 0.95f, 1.0f), 1.0f, 0.08f, {}, false});

  // Corner orders follow the original data, which is counter-clockwise seen from inside the room.
  addObject(scene, "floor", makeQuad(mm(552.8f, 0, 0), mm(0, 0, 0), mm(0, 0, 559.2f), mm(549.6f, 0, 559.2f), white));
  addObject(scene, "ceiling",
            makeQuad(mm(556, 548.8f, 0), mm(556, 548.8f, 559.2f), mm(0, 548.8f, 559.2f), mm(0, 548.8f, 0), white));
  addObject(scene, "back-wall",
            makeQuad(mm(549.6f, 0, 559.2f), mm(0, 0, 559.2f), mm(0, 548.8f, 559.2f), mm(556, 548.8f, 559.2f), white));
  addObject(scene, "red-wall",
            makeQuad(mm(552.8f, 0, 0), mm(549.6f, 0, 559.2f), mm(556, 548.8f, 559.2f), mm(556, 548.8f, 0), red));
  addObject(scene, "green-wall",
            makeQuad(mm(0, 0, 559.2f), mm(0, 0, 0), mm(0, 548.8f, 0), mm(0, 548.8f, 559.2f), green));
  // Blocks sit on the floor, so they have no bottom face (it could never be seen or lit).
  const std::array<glm::vec2, 4> shortBlock{glm::vec2(130, 65) * kScale, glm::vec2(82, 225) * kScale,
                                            glm::vec2(240, 272) * kScale, glm::vec2(290, 114) * kScale};
  addObject(scene, "short-block", makePrism(shortBlock, 0.0f, 165 * kScale, /*capBottom=*/false, white));
  const std::array<glm::vec2, 4> tallBlock{glm::vec2(423, 247) * kScale, glm::vec2(265, 296) * kScale,
                                           glm::vec2(314, 456) * kScale, glm::vec2(472, 406) * kScale};
  addObject(scene, "tall-block", makePrism(tallBlock, 0.0f, 330 * kScale, /*capBottom=*/false, mirror));

  // A sphere light replaces the original ceiling quad: it gives soft shadows through the
  // sphere-light sampling path, which every renderer mode supports.
  Light light;
  light.name = "ceiling-light";
  light.type = LightType::Point;
  light.position = glm::vec3(2.78f, 4.9f, 2.795f);
  light.radius = 0.3f;
  light.color = glm::vec3(1.0f, 0.85f, 0.7f);
  light.intensity = 12.0f;
  light.visibleShape = true;  // the emissive sphere below
  scene.lights.push_back(light);

  // The visible light: radiance of a uniformly emitting sphere with radiant intensity I is
  // L = I / (pi r^2), since its projected area is pi r^2 from every direction.
  const glm::vec3 radiance = light.color * light.intensity / (glm::pi<float>() * light.radius * light.radius);
  const uint32_t emitter =
      addMaterial(scene, {"light", glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), 0.0f, 1.0f, radiance, false});
  // Baked into the vertices so every Cornell instance keeps an identity transform.
  Primitive sphere = makeUvSphere(light.radius, kLightRings, kLightSegments, emitter);
  for (glm::vec3& p : sphere.positions) p += light.position;
  addObject(scene, "light-sphere", std::move(sphere), /*castsShadows=*/false);

  // The original camera: 35 mm focal length, 25 mm film, at z = -800 mm looking down +z.
  Camera camera;
  camera.name = "default";
  camera.position = glm::vec3(2.78f, 2.73f, -8.0f);
  camera.target = glm::vec3(2.78f, 2.73f, 0.0f);
  camera.up = glm::vec3(0, 1, 0);
  camera.yFov = 2.0f * std::atan(0.0125f / 0.035f);
  camera.zNear = 0.1f;
  camera.zFar = 30.0f;
  scene.cameras.push_back(camera);
  return scene;
}

}  // namespace rayster::scene
