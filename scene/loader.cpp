#include "scene/loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include <glm/gtc/constants.hpp>

#include "scene/builtin.h"
#include "scene/obj_loader.h"
#include "scene/scene_file.h"

#if __has_include("scene/gltf_loader.h")
#include "scene/gltf_loader.h"
#define RAYSTER_HAS_GLTF 1
#else
#define RAYSTER_HAS_GLTF 0
#endif

namespace rayster::scene {
namespace fs = std::filesystem;
namespace {

constexpr std::string_view kBuiltinPrefix = "builtin:";
constexpr std::string_view kSupported = ".gltf, .glb, .obj, .json or builtin:NAME";

// The default sun: about the real sun's angular radius (0.27 degrees), low enough in the sky that
// vertical walls are lit too, slightly warm.
constexpr float kSunIntensity = 3.0f;
constexpr float kSunAngularRadius = 0.0047f;
// Framing camera: a 45-degree lens, seen from +Z and a little above so floors read as floors.
constexpr float kFramingFov = glm::radians(45.0f);
constexpr float kFramingElevation = 0.25f;  // rise per unit of distance along +Z

std::string lowerExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

bool hasGeometry(const Scene& scene) {
  return std::any_of(scene.instances.begin(), scene.instances.end(), [&](const Instance& instance) {
    const Mesh& mesh = scene.meshes[instance.mesh];  // validate() checked the index
    return !mesh.primitives.empty() || !mesh.spheres.empty();
  });
}

bool isBuiltinName(const std::string& name) {
  const std::vector<std::string> names = builtinSceneNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

Result<fs::path> resolveRelativePath(const fs::path& baseDir, std::string_view ref, std::string_view what) {
  std::string text(ref);
  std::replace(text.begin(), text.end(), '\\', '/');
  if (text.empty()) return makeError(ExitCode::BadInput, "{} is an empty path", what);
  if (text.find('\0') != std::string::npos) return makeError(ExitCode::BadInput, "{} contains a NUL character", what);
  if (text[0] == '/')
    return makeError(ExitCode::BadInput, "{} '{}' is an absolute path; paths must be relative to the file's folder",
                     what, ref);
  // "http:", "file:", and Windows drive letters ("C:") all look like a scheme.
  const size_t colon = text.find(':');
  if (colon != std::string::npos && colon < text.find('/') && std::isalpha(static_cast<unsigned char>(text[0])))
    return makeError(ExitCode::BadInput, "{} '{}' is a URI or drive path; only relative file paths are supported", what,
                     ref);
  const fs::path relative(text);
  for (const fs::path& part : relative)
    if (part == "..")
      return makeError(ExitCode::BadInput, "{} '{}' leaves the file's folder ('..' is not allowed)", what, ref);
  return (baseDir / relative).lexically_normal();
}

Result<Scene> loadModelFile(const fs::path& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".obj") return loadObj(path);
  if (ext == ".gltf" || ext == ".glb") {
#if RAYSTER_HAS_GLTF
    return loadGltf(path);
#else
    return makeError(ExitCode::BadInput, "cannot read scene '{}': glTF support is not built", path.string());
#endif
  }
  return makeError(ExitCode::BadInput, "cannot read scene '{}': unsupported format '{}' (supported: {})", path.string(),
                   ext.empty() ? "no extension" : ext, kSupported);
}

Result<Scene> loadScene(const std::string& nameOrPath) {
  if (nameOrPath.rfind(kBuiltinPrefix, 0) == 0) {
    if (!isBuiltinModel(nameOrPath)) return makeBuiltinScene(nameOrPath);
    Result<Scene> model = makeBuiltinModel(nameOrPath);  // a model alone: completed as a file is
    if (model) applyDefaults(*model);
    return model;
  }
  const fs::path path(nameOrPath);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    if (isBuiltinName(nameOrPath))
      return makeError(ExitCode::BadInput, "cannot read scene '{}': no such file (did you mean builtin:{}?)",
                       nameOrPath, nameOrPath);
    return makeError(ExitCode::BadInput, "cannot read scene '{}': no such file", nameOrPath);
  }
  Result<Scene> loaded = lowerExtension(path) == ".json" ? loadSceneFile(path) : loadModelFile(path);
  if (!loaded) return loaded.error();
  Scene scene = std::move(*loaded);
  if (scene.name.empty()) scene.name = path.stem().string();
  applyDefaults(scene);
  RAYSTER_TRY(validate(scene));
  // Said here, before any device starts, and after the loaders' warnings of what they skipped.
  if (!hasGeometry(scene))
    return makeError(ExitCode::BadInput, "cannot render '{}': nothing to render (no instance has triangles or spheres)",
                     nameOrPath);
  return scene;
}

Camera makeFramingCamera(const Aabb& bounds) {
  const glm::vec3 centre = bounds.valid() ? bounds.centre() : glm::vec3(0.0f);
  float radius = bounds.valid() ? 0.5f * glm::length(bounds.max - bounds.min) : 1.0f;
  if (!std::isfinite(radius) || radius <= 0.0f) radius = 1.0f;
  // The bounding sphere touches the top and bottom of the view; wider images only add margin.
  const float distance = radius / std::sin(0.5f * kFramingFov);
  Camera camera;
  camera.name = "default";
  camera.target = centre;
  camera.position = centre + glm::normalize(glm::vec3(0.0f, kFramingElevation, 1.0f)) * distance;
  camera.up = glm::vec3(0, 1, 0);
  camera.yFov = kFramingFov;
  // Near close enough to orbit inside the model, far enough out to orbit away from it.
  camera.zNear = 0.01f * radius;
  camera.zFar = 20.0f * radius;
  return camera;
}

void applyDefaults(Scene& scene) {
  if (scene.lights.empty()) {
    Light sun;
    sun.name = "default sun";
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f));
    sun.color = glm::vec3(1.0f, 0.96f, 0.9f);
    sun.intensity = kSunIntensity;
    sun.angularRadius = kSunAngularRadius;
    scene.lights.push_back(sun);
    if (scene.environment.kind == Environment::Kind::Black) scene.environment.kind = Environment::Kind::Sky;
  }
  if (scene.cameras.empty()) scene.cameras.push_back(makeFramingCamera(scene.bounds()));
}

}  // namespace rayster::scene
