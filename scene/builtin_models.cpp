// Built-in models (scene/builtin.h makeBuiltinModel): the embedded meshes and a sphere as single
// objects, for scene files to compose (bench/scenes/effects-*.json): geometry and one material,
// no light, camera or environment of their own.
#include <string>
#include <utility>

#include <fmt/format.h>

#include "scene/builtin.h"
#include "scene/builtin_parts.h"

namespace rayster::scene {
namespace {

using namespace builtin;

// The sizes whitted uses: a teapot 0.8 m tall, a bunny 1 m, a sphere of 1 m diameter; a scene file
// scales them ("scale").
constexpr float kTeapotHeight = 0.8f;
constexpr float kBunnyHeight = 1.0f;
constexpr float kSphereRadius = 0.5f;
constexpr float kFloorSize = 20.0f;

struct NamedMaterial {
  const char* name;
  glm::vec3 colour;
  float metallic, roughness;
};
// Diffuse colours (rough dielectrics: nothing for the specular pass to trace) and a perfect mirror.
constexpr NamedMaterial kMaterials[] = {
    {"white", {0.8f, 0.8f, 0.8f}, 0.0f, 1.0f},  {"grey", {0.45f, 0.45f, 0.45f}, 0.0f, 1.0f},
    {"red", {0.7f, 0.08f, 0.06f}, 0.0f, 1.0f},  {"green", {0.12f, 0.5f, 0.1f}, 0.0f, 1.0f},
    {"blue", {0.08f, 0.15f, 0.7f}, 0.0f, 1.0f}, {"mirror", {0.95f, 0.95f, 0.95f}, 1.0f, 0.0f},
};

std::string materialNames() {
  std::string names;
  for (const NamedMaterial& m : kMaterials) names += (names.empty() ? "" : ", ") + std::string(m.name);
  return names;
}

Result<uint32_t> addNamedMaterial(Scene& scene, std::string_view model, std::string_view name) {
  for (const NamedMaterial& m : kMaterials) {
    if (name != m.name) continue;
    Material material;
    material.name = m.name;
    material.baseColor = glm::vec4(m.colour, 1.0f);
    material.metallic = m.metallic;
    material.roughness = m.roughness;
    return addMaterial(scene, std::move(material));
  }
  return makeError(ExitCode::BadInput, "builtin:{}: unknown material '{}' (available: {})", model, name,
                   materialNames());
}

}  // namespace

std::vector<std::string> builtinModelNames() { return {"teapot", "bunny", "sphere", "floor"}; }

bool isBuiltinModel(std::string_view name) {
  std::string_view bare = name;
  if (bare.rfind("builtin:", 0) == 0) bare.remove_prefix(8);
  const std::string_view base = bare.substr(0, bare.find(':'));
  for (const std::string& m : builtinModelNames())
    if (base == m) return true;
  return false;
}

Result<Scene> makeBuiltinModel(std::string_view name) {
  std::string_view bare = name;
  if (bare.rfind("builtin:", 0) == 0) bare.remove_prefix(8);
  const size_t colon = bare.find(':');
  const std::string base(bare.substr(0, colon));
  const std::string_view materialName =
      colon == std::string_view::npos ? (base == "floor" ? "grey" : "white") : bare.substr(colon + 1);
  Scene scene;
  scene.name = base;
  Result<uint32_t> material = addNamedMaterial(scene, base, materialName);
  if (!material) return material.error();
  if (base == "teapot" || base == "bunny") {
    Result<Primitive> mesh = base == "teapot" ? loadStandingMesh(EmbeddedMesh::Teapot, kTeapotHeight, *material)
                                              : loadStandingMesh(EmbeddedMesh::Bunny, kBunnyHeight, *material);
    if (!mesh) return mesh.error();
    addInstance(scene, base, addMesh(scene, base, std::move(*mesh)));
  } else if (base == "sphere") {
    Mesh sphere;
    sphere.name = "sphere";
    sphere.spheres.push_back(Sphere{glm::vec3(0.0f, kSphereRadius, 0.0f), kSphereRadius, *material});
    scene.meshes.push_back(std::move(sphere));
    addInstance(scene, "sphere", uint32_t(scene.meshes.size() - 1));
  } else if (base == "floor") {
    addFloor(scene, glm::vec3(0.0f), kFloorSize, *material);
  } else {
    return makeError(ExitCode::BadInput, "unknown built-in model '{}' (available: teapot, bunny, sphere, floor)", name);
  }
  for (Material& m : scene.materials) m.doubleSided = true;  // as the built-in scenes' meshes (builtin.cpp)
  return scene;
}

}  // namespace rayster::scene
