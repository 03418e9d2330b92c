#include "scene/builtin_parts.h"

#include <utility>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/geometry.h"

namespace rayster::scene::builtin {
namespace {

// Fine enough that a visible light's silhouette looks round at 1080p (as in the Cornell box).
constexpr int kLightRings = 16;
constexpr int kLightSegments = 32;

// The sun's angular radius: about 0.27 degrees in reality; 0.5 degrees reads as a slightly hazy
// sun and keeps contact shadows soft without many samples.
constexpr float kSunAngularRadius = 0.5f * glm::pi<float>() / 180.0f;

}  // namespace

uint32_t addMaterial(Scene& scene, Material material) {
  scene.materials.push_back(std::move(material));
  return static_cast<uint32_t>(scene.materials.size() - 1);
}

uint32_t addMesh(Scene& scene, std::string name, Primitive prim) {
  Mesh mesh;
  mesh.name = std::move(name);
  mesh.primitives.push_back(std::move(prim));
  scene.meshes.push_back(std::move(mesh));
  return static_cast<uint32_t>(scene.meshes.size() - 1);
}

void addInstance(Scene& scene, std::string name, uint32_t mesh, const glm::mat4& worldFromObject, bool castsShadows) {
  Instance instance;
  instance.name = std::move(name);
  instance.mesh = mesh;
  instance.worldFromObject = worldFromObject;
  instance.castsShadows = castsShadows;
  scene.instances.push_back(std::move(instance));
}

uint32_t addFloor(Scene& scene, glm::vec3 centre, float size, uint32_t material) {
  const float h = size * 0.5f;
  // Counter-clockwise seen from above, so the normal is +y.
  Primitive floor = makeQuad(centre + glm::vec3(-h, 0, -h), centre + glm::vec3(-h, 0, h), centre + glm::vec3(h, 0, h),
                             centre + glm::vec3(h, 0, -h), material);
  const uint32_t mesh = addMesh(scene, "floor", std::move(floor));
  addInstance(scene, "floor", mesh);
  return mesh;
}

void addSphereLight(Scene& scene, std::string name, glm::vec3 position, float radius, glm::vec3 color,
                    float intensity) {
  Light light;
  light.name = name;
  light.type = LightType::Point;
  light.position = position;
  light.radius = radius;
  light.color = color;
  light.intensity = intensity;
  light.visibleShape = true;  // the emissive sphere below
  scene.lights.push_back(light);
  // Radiance of a uniformly emitting sphere of radiant intensity I: L = I / (pi r^2), since its
  // projected area is pi r^2 from every direction. Same relation as the Cornell box light.
  const glm::vec3 radiance = color * intensity / (glm::pi<float>() * radius * radius);
  Material emitter;
  emitter.name = name;
  emitter.baseColor = glm::vec4(0, 0, 0, 1);
  emitter.emissive = radiance;
  const uint32_t material = addMaterial(scene, std::move(emitter));
  Primitive sphere = makeUvSphere(radius, kLightRings, kLightSegments, material);
  const uint32_t mesh = addMesh(scene, name + "-sphere", std::move(sphere));
  addInstance(scene, name + "-sphere", mesh, glm::translate(glm::mat4(1.0f), position), /*castsShadows=*/false);
}

void addSun(Scene& scene, glm::vec3 direction, float irradiance) {
  Light sun;
  sun.name = "sun";
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(direction);
  sun.color = glm::vec3(1.0f, 0.96f, 0.9f);  // a little warm against the blue sky
  sun.intensity = irradiance;
  sun.angularRadius = kSunAngularRadius;
  scene.lights.push_back(sun);
}

Environment blueSky() {
  Environment sky;
  sky.kind = Environment::Kind::Sky;
  sky.zenith = glm::vec3(0.18f, 0.38f, 0.85f);
  sky.horizon = glm::vec3(0.75f, 0.85f, 1.0f);
  sky.ground = glm::vec3(0.3f, 0.28f, 0.25f);
  return sky;
}

Result<Primitive> loadStandingMesh(EmbeddedMesh which, float height, uint32_t material) {
  Result<Primitive> parsed = parseMeshAsset(embeddedMeshBytes(which), material);
  if (!parsed) return parsed.error();
  Primitive prim = std::move(*parsed);
  Aabb box;
  for (const glm::vec3& p : prim.positions) box.extend(p);
  const float extent = box.max.y - box.min.y;
  if (!(extent > 0.0f)) return makeError(ExitCode::BadInput, "embedded mesh is flat (height {})", extent);
  const float scale = height / extent;
  const glm::vec3 base(box.centre().x, box.min.y, box.centre().z);
  // Uniform scale: normals keep their direction, so the smooth normals stay valid.
  for (glm::vec3& p : prim.positions) p = (p - base) * scale;
  return prim;
}

}  // namespace rayster::scene::builtin
