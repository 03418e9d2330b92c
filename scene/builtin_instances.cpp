// A scaling scene: N instances of one bunny mesh on a square grid, so BLAS memory stays fixed
// while the TLAS, culling and draw submission grow with N.
#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/builtin.h"
#include "scene/builtin_parts.h"

namespace rayster::scene {
namespace {

using namespace builtin;

constexpr float kBunnyHeight = 1.0f;
constexpr float kSpacing = 1.5f;          // the bunny is ~1.1 m wide: 0.4 m clear between neighbours
constexpr float kCameraElevation = 0.6f;  // radians above the horizon: sees rows, not just the front

}  // namespace

Result<Scene> makeInstancesScene(uint32_t count) {
  if (count == 0 || count > kMaxBuiltinInstances)
    return makeError(ExitCode::BadInput, "builtin:instances: count {} is outside 1..{}", count, kMaxBuiltinInstances);
  Scene scene;
  scene.name = fmt::format("instances:{}", count);
  scene.environment = blueSky();

  const auto side = static_cast<uint32_t>(std::ceil(std::sqrt(double(count))));
  const float extent = float(side) * kSpacing;

  Material ground;
  ground.name = "ground";
  ground.baseColor = glm::vec4(0.45f, 0.45f, 0.43f, 1.0f);
  ground.roughness = 0.8f;
  addFloor(scene, glm::vec3(0.0f), extent + 4.0f * kSpacing, addMaterial(scene, std::move(ground)));

  Material clay;
  clay.name = "clay";
  clay.baseColor = glm::vec4(0.8f, 0.55f, 0.4f, 1.0f);
  clay.roughness = 0.6f;
  Result<Primitive> bunny = loadStandingMesh(EmbeddedMesh::Bunny, kBunnyHeight, addMaterial(scene, std::move(clay)));
  if (!bunny) return bunny.error();
  const uint32_t mesh = addMesh(scene, "bunny", std::move(*bunny));

  scene.instances.reserve(scene.instances.size() + count);
  const float origin = -0.5f * float(side - 1) * kSpacing;
  for (uint32_t i = 0; i < count; ++i) {
    const glm::vec3 at(origin + float(i % side) * kSpacing, 0.0f, origin + float(i / side) * kSpacing);
    // Turned towards the camera (the scan faces -x); a per-instance twist so rows do not look cloned.
    const float yaw = glm::radians(90.0f + float(int(i % 7) - 3) * 10.0f);
    addInstance(scene, fmt::format("bunny-{}", i), mesh,
                glm::rotate(glm::translate(glm::mat4(1.0f), at), yaw, glm::vec3(0, 1, 0)));
  }

  addSun(scene, glm::vec3(-0.5f, -1.0f, -0.6f), 3.0f);

  // Far enough back that the grid's width fits a 40 degree vertical field at 16:9 with margin.
  Camera camera;
  camera.name = "default";
  camera.yFov = glm::radians(40.0f);
  const float distance = std::max(4.0f, 1.4f * extent);
  camera.target = glm::vec3(0.0f, 0.3f, 0.0f);
  camera.position = camera.target + distance * glm::vec3(0.0f, std::sin(kCameraElevation), std::cos(kCameraElevation));
  camera.zNear = std::max(0.05f, distance * 0.005f);  // depth precision over a grid kilometres wide
  camera.zFar = 2.0f * (distance + extent);
  scene.cameras.push_back(camera);
  return scene;
}

}  // namespace rayster::scene
