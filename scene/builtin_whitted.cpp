// The classic Whitted-style scene as ray-tracing articles rebuild it: a chrome Utah teapot and a
// glass (ice) Stanford bunny on a marble floor, a sphere light and a blue sky.
#include <utility>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/builtin.h"
#include "scene/builtin_parts.h"

namespace rayster::scene {
namespace {

using namespace builtin;

// 1024^2 keeps the veins crisp on a floor tile seen up close; generated once per process.
constexpr int kMarbleSize = 1024;
// The floor is large enough that its edge stays outside the default view; 4 marble tiles across
// it give slabs of 4 m, about the size of real marble floor slabs seen from this distance.
constexpr float kFloorSize = 16.0f;
constexpr float kMarbleTiles = 4.0f;

// Teapot is about twice as wide as tall; 0.8 m tall keeps both objects near 1 m in screen size.
constexpr float kTeapotHeight = 0.8f;
constexpr float kBunnyHeight = 1.0f;

const ImageData& marbleImage() {
  static const ImageData image = makeMarbleImage(kMarbleSize);  // thread-safe once-only init
  return image;
}

glm::mat4 placeOnFloor(float x, float z, float yawDegrees) {
  const glm::mat4 moved = glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.0f, z));
  return glm::rotate(moved, glm::radians(yawDegrees), glm::vec3(0, 1, 0));
}

uint32_t addMarbleMaterial(Scene& scene) {
  scene.images.push_back(marbleImage());
  scene.samplers.push_back(Sampler{});  // Repeat in both directions, linear, mipmapped
  Texture texture;
  texture.image = static_cast<uint32_t>(scene.images.size() - 1);
  texture.sampler = static_cast<uint32_t>(scene.samplers.size() - 1);
  scene.textures.push_back(texture);

  Material marble;
  marble.name = "marble";
  marble.roughness = 0.3f;  // polished stone: blurred reflections of the teapot and bunny
  marble.baseColorTexture.texture = static_cast<int32_t>(scene.textures.size() - 1);
  marble.baseColorTexture.scale = glm::vec2(kMarbleTiles);
  return addMaterial(scene, std::move(marble));
}

}  // namespace

Result<Scene> makeWhittedScene() {
  Scene scene;
  scene.name = "whitted";
  scene.environment = blueSky();

  const uint32_t marble = addMarbleMaterial(scene);
  addFloor(scene, glm::vec3(0.0f), kFloorSize, marble);

  Material chrome;
  chrome.name = "chrome";
  chrome.baseColor = glm::vec4(0.95f, 0.93f, 0.88f, 1.0f);
  chrome.metallic = 1.0f;
  chrome.roughness = 0.05f;
  Result<Primitive> teapot = loadStandingMesh(EmbeddedMesh::Teapot, kTeapotHeight, addMaterial(scene, chrome));
  if (!teapot) return teapot.error();
  // Turned a little so the spout points towards the bunny and the camera.
  addInstance(scene, "teapot", addMesh(scene, "teapot", std::move(*teapot)), placeOnFloor(-1.0f, 0.0f, -25.0f));

  Material ice;
  ice.name = "ice";
  ice.baseColor = glm::vec4(0.9f, 0.95f, 1.0f, 1.0f);
  ice.roughness = 0.0f;
  ice.transmission = 1.0f;
  ice.ior = 1.31f;  // water ice
  // A solid volume (not thin-walled), faintly blue where it is thick.
  ice.thickness = 0.5f;
  ice.attenuationColor = glm::vec3(0.8f, 0.9f, 1.0f);
  ice.attenuationDistance = 2.0f;
  Result<Primitive> bunny = loadStandingMesh(EmbeddedMesh::Bunny, kBunnyHeight, addMaterial(scene, ice));
  if (!bunny) return bunny.error();
  // The scan faces -x; 50 degrees turns it three-quarters towards the camera and the teapot.
  addInstance(scene, "bunny", addMesh(scene, "bunny", std::move(*bunny)), placeOnFloor(0.9f, 0.1f, 50.0f));

  // Up and to the side, so both objects cast visible shadows across the marble.
  addSphereLight(scene, "light", glm::vec3(-2.5f, 4.0f, 2.5f), 0.25f, glm::vec3(1.0f, 0.95f, 0.88f), 60.0f);

  Camera camera;
  camera.name = "default";
  camera.position = glm::vec3(0.0f, 1.6f, 4.5f);
  camera.target = glm::vec3(0.0f, 0.45f, 0.0f);
  camera.yFov = glm::radians(40.0f);
  camera.zNear = 0.05f;
  camera.zFar = 50.0f;
  scene.cameras.push_back(camera);
  return scene;
}

}  // namespace rayster::scene
