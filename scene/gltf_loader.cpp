// glTF 2.0 loading: the file, tinygltf, and the node hierarchy (instances, cameras, lights).
// Accessors, meshes, materials and the pre-parse checks live in the other gltf_*.cpp files.
#include "scene/gltf_loader.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/load_progress.h"
#include "core/log.h"
#include "scene/gltf_internal.h"

namespace fs = std::filesystem;

namespace rayster::scene {
namespace gltf {
namespace {

// tinygltf takes lengths as unsigned int; nothing near this size is a sensible scene file anyway.
constexpr uint64_t kMaxFileBytes = 0x7fffffffu;

bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

Result<std::vector<uint8_t>> readFile(const fs::path& path, const std::string& file) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return bad(file, "cannot open {}: no such file", path.string());
  std::ifstream in(path, std::ios::binary);
  if (!in) return bad(file, "cannot open {}: {}", path.string(), std::strerror(errno));
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) return bad(file, "cannot read {}", path.string());
  if (uint64_t(size) > kMaxFileBytes) return bad(file, "file is too large ({} bytes)", size);
  in.seekg(0);
  std::vector<uint8_t> bytes(static_cast<size_t>(size));
  if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size))
    return bad(file, "cannot read {}", path.string());
  return bytes;
}

// The length from a GLB header that glbJsonChunk() accepted (at most the file's size).
unsigned glbLength(const std::vector<uint8_t>& bytes) {
  uint32_t length;
  std::memcpy(&length, bytes.data() + 8, 4);
  return length;
}

// The BIN chunk's length in a GLB that glbJsonChunk() accepted, -1 when there is none.
int64_t glbBinLength(const std::vector<uint8_t>& bytes, size_t jsonLength) {
  const size_t at = 20 + jsonLength;
  uint32_t length = 0, type = 0;
  if (at + 8 > glbLength(bytes)) return -1;
  std::memcpy(&length, bytes.data() + at, 4);
  std::memcpy(&type, bytes.data() + at + 4, 4);
  return type == 0x004E4942u ? int64_t(length) : -1;
}

// Reads and parses the file; `images` learns which images a material shows and which were found.
Result<tinygltf::Model> parse(const fs::path& path, const std::string& file, ImageDecodeState& images,
                              std::vector<FallbackBuffer>& fallbacks, std::vector<DetachedIndices>& detached) {
  LoadProgress parsed("loading " + file, "parse");  // reading, vetting and tinygltf
  Result<std::vector<uint8_t>> bytes = readFile(path, file);
  if (!bytes) return bytes.error();
  const bool binary = bytes->size() >= 4 && std::memcmp(bytes->data(), "glTF", 4) == 0;
  std::string_view json(reinterpret_cast<const char*>(bytes->data()), bytes->size());
  if (binary) {
    Result<std::string_view> chunk = glbJsonChunk(file, *bytes);
    if (!chunk) return chunk.error();
    json = *chunk;
  }
  Result<VettedJson> vetted = vetJson(file, json, binary);
  if (!vetted) return vetted.error();
  // EXT_meshopt_compression fallback buffers: tinygltf parses a JSON that gives them stand-in bytes.
  std::vector<uint8_t> rewrittenGlb;
  if (!vetted->rewrittenJson.empty()) {
    json = vetted->rewrittenJson;
    if (binary) {
      rewrittenGlb = glbWithJson(*bytes, json);
      bytes->swap(rewrittenGlb);
    }
  }
  fallbacks = vetted->fallbackBuffers;
  detached = vetted->detachedIndices;
  images.imageMaterial = vetted->imageMaterial;
  images.reached.assign(images.imageMaterial.size(), false);

  std::error_code ec;
  fs::path dir = fs::absolute(path, ec).parent_path();
  ConfinedFs confined{dir.string(), {}};
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(makeConfinedFsCallbacks(&confined));
  loader.SetImageLoader(&decodeImage, &images);
  tinygltf::Model model;
  std::string err, warn;
  bool ok = false;
  try {
    ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes->data(), glbLength(*bytes), confined.baseDir)
                : loader.LoadASCIIFromString(&model, &err, &warn, json.data(), unsigned(json.size()), confined.baseDir);
  } catch (const std::exception& e) {
    return bad(file, "invalid glTF: {}", oneLine(e.what()));
  }
  parsed.finish();
  if (!confined.violation.empty()) return bad(file, "{}", confined.violation);
  // Images are decoded now, in parallel. tinygltf reads them before anything after them that it
  // could fail on, so an image's failure still wins over a later parse error, as when it stopped
  // at the image.
  if (!decodeImages(model, file, images)) return bad(file, "{}", images.error);
  if (!ok) {
    if (binary) RAYSTER_TRY(explainGlbBuffer(file, json, glbBinLength(*bytes, json.size())));
    return bad(file, "invalid glTF: {}", oneLine(err.empty() ? std::string("tinygltf failed") : err));
  }
  if (!warn.empty()) log::debug("{}: tinygltf: {}", file, oneLine(warn));
  return model;
}

// The node's local transform as glTF gives it: a matrix, or TRS with a normalised rotation.
Result<SceneNode> convertNode(const tinygltf::Node& src, size_t index, const std::string& file) {
  SceneNode node;
  node.name = src.name.empty() ? fmt::format("node{}", index) : src.name;
  if (src.matrix.size() == 16) {
    node.hasMatrix = true;
    for (int i = 0; i < 16; ++i) glm::value_ptr(node.matrix)[i] = float(src.matrix[size_t(i)]);  // column-major, as glm
  } else {
    if (src.translation.size() == 3)
      node.translation = glm::vec3(src.translation[0], src.translation[1], src.translation[2]);
    if (src.scale.size() == 3) node.scale = glm::vec3(src.scale[0], src.scale[1], src.scale[2]);
    if (src.rotation.size() == 4) {  // glTF stores x, y, z, w
      glm::quat r(float(src.rotation[3]), float(src.rotation[0]), float(src.rotation[1]), float(src.rotation[2]));
      const float length = glm::length(r);
      if (length > 0.0f && std::isfinite(length)) r /= length;  // exporters round; a skewing matrix helps no one
      node.rotation = r;
    }
  }
  if (!finite(node.parentFromNode())) return bad(file, "node {} has a non-finite transform", index);
  return node;
}

Status addCamera(const tinygltf::Model& model, const tinygltf::Node& node, const glm::mat4& world, Scene& scene,
                 const std::string& file) {
  if (size_t(node.camera) >= model.cameras.size())
    return bad(file, "node '{}' uses camera {}, which does not exist", node.name, node.camera);
  const tinygltf::Camera& src = model.cameras[size_t(node.camera)];
  Camera camera;
  camera.name = !node.name.empty() ? node.name : !src.name.empty() ? src.name : fmt::format("camera{}", node.camera);
  // A glTF camera looks down its local -Z with +Y up.
  const glm::vec3 forward = glm::mat3(world) * glm::vec3(0, 0, -1);
  const glm::vec3 up = glm::mat3(world) * glm::vec3(0, 1, 0);
  if (!(glm::length(forward) > 0.0f) || !(glm::length(up) > 0.0f))
    return bad(file, "camera '{}' has a degenerate transform", camera.name);
  camera.position = glm::vec3(world[3]);
  camera.target = camera.position + glm::normalize(forward);
  camera.up = glm::normalize(up);
  double znear = 0.0, zfar = 0.0;
  if (src.type == "orthographic") {
    log::warn("{}: camera '{}' is orthographic; Rayster renders it as a perspective camera", file, camera.name);
    znear = src.orthographic.znear;
    zfar = src.orthographic.zfar;
  } else {
    const float yFov = float(src.perspective.yfov);
    if (yFov > 0.0f && yFov < 3.1f) camera.yFov = yFov;
    znear = src.perspective.znear;
    zfar = src.perspective.zfar;
  }
  if (znear > 0.0 && std::isfinite(float(znear))) camera.zNear = float(znear);
  // zfar absent means an infinite projection; a far plane well past the near one stands in for it.
  camera.zFar = zfar > znear && std::isfinite(float(zfar)) ? float(zfar) : std::max(camera.zFar, camera.zNear * 1e4f);
  scene.cameras.push_back(camera);
  return okStatus();
}

// KHR_lights_punctual gives point/spot intensity in candela (lm/sr) and directional in lux
// (lm/m^2). Rayster's lights are radiometric (W/sr-like intensity, irradiance), and the numbers
// are passed through unconverted: scenes tuned in other glTF viewers keep their relative balance,
// and no 683 lm/W factor makes exposure differ between a glTF and the same scene file.
Status addLight(const tinygltf::Model& model, const tinygltf::Node& node, int lightIndex, const glm::mat4& world,
                Scene& scene, const std::string& file) {
  if (lightIndex < 0 || size_t(lightIndex) >= model.lights.size())
    return bad(file, "node '{}' uses light {}, which does not exist", node.name, lightIndex);
  const tinygltf::Light& src = model.lights[size_t(lightIndex)];
  Light light;
  light.name = !node.name.empty() ? node.name : !src.name.empty() ? src.name : fmt::format("light{}", lightIndex);
  if (src.type == "point")
    light.type = LightType::Point;
  else if (src.type == "spot")
    light.type = LightType::Spot;
  else if (src.type == "directional")
    light.type = LightType::Directional;
  else {
    // The schema allows any string here (the validator only warns): a type glTF 2.0 does not
    // define is not drawn.
    log::warn("{}: light '{}' has type '{}', which KHR_lights_punctual does not define; not drawn", file, light.name,
              src.type);
    return okStatus();
  }
  if (src.color.size() == 3) light.color = glm::vec3(src.color[0], src.color[1], src.color[2]);
  light.intensity = float(src.intensity);
  light.position = glm::vec3(world[3]);
  const glm::vec3 direction = glm::mat3(world) * glm::vec3(0, 0, -1);  // lights shine down local -Z
  if (!(glm::length(direction) > 0.0f)) return bad(file, "light '{}' has a degenerate transform", light.name);
  light.direction = glm::normalize(direction);
  if (light.type == LightType::Spot) {
    light.innerConeAngle = float(src.spot.innerConeAngle);
    light.outerConeAngle = float(src.spot.outerConeAngle);
  }
  // Soft-shadow sizes are not in KHR_lights_punctual; Rayster reads them from extras.
  light.radius = std::max(0.0f, float(numberOr(src.extras, "radius", 0.0)));
  light.angularRadius = std::max(0.0f, float(numberOr(src.extras, "angularRadius", 0.0)));
  if (!std::isfinite(light.intensity) || !std::isfinite(light.radius) || !std::isfinite(light.angularRadius) ||
      !std::isfinite(light.color.x + light.color.y + light.color.z))
    return bad(file, "light '{}' has a non-finite parameter", light.name);
  scene.lights.push_back(light);
  return okStatus();
}

int nodeLight(const tinygltf::Node& node) {
  auto it = node.extensions.find("KHR_lights_punctual");
  if (it == node.extensions.end()) return -1;
  const double index = numberOr(it->second, "light", -1.0);
  return index >= 0.0 && index < 2147483647.0 ? int(index) : -2;  // -2: present but invalid
}

// The scene's root nodes, after checking that the hierarchy is a forest: children exist, and no
// node has two parents.
Result<std::vector<int>> rootNodes(const tinygltf::Model& model, const std::string& file) {
  std::vector<int> parent(model.nodes.size(), -1);
  for (size_t i = 0; i < model.nodes.size(); ++i)
    for (int child : model.nodes[i].children) {
      if (child < 0 || size_t(child) >= model.nodes.size())
        return bad(file, "node {} has child {}, which does not exist", i, child);
      if (parent[size_t(child)] >= 0)
        return bad(file, "node {} has two parents ({} and {}), or the hierarchy has a cycle", child,
                   parent[size_t(child)], i);
      parent[size_t(child)] = int(i);
    }
  std::vector<int> roots;
  if (!model.scenes.empty()) {
    const size_t s =
        model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size() ? size_t(model.defaultScene) : 0;
    for (int n : model.scenes[s].nodes) {
      if (n < 0 || size_t(n) >= model.nodes.size())
        return bad(file, "scene {} uses node {}, which does not exist", s, n);
      roots.push_back(n);
    }
  } else {
    for (size_t i = 0; i < model.nodes.size(); ++i)
      if (parent[i] < 0) roots.push_back(int(i));
  }
  return roots;
}

// meshMap[glTF mesh]: its index in Scene::meshes, or one of these.
constexpr int kMeshUnconverted = -1, kMeshEmpty = -2;

// Node `index` (Scene::nodes[self]) draws its mesh, converted on first use. A mesh with nothing to
// draw (every primitive skipped) adds no mesh and no instance, so no empty BLAS; its nodes stay in
// the hierarchy for their children and animations.
Status addMeshInstance(MeshBuilder& meshes, std::vector<int>& meshMap, int index, int32_t self,
                       const glm::mat4& world) {
  const tinygltf::Node& node = meshes.model.nodes[size_t(index)];
  const std::string& file = meshes.file;
  Scene& scene = meshes.scene;
  if (size_t(node.mesh) >= meshes.model.meshes.size())
    return bad(file, "node {} uses mesh {}, which does not exist", index, node.mesh);
  int& mapped = meshMap[size_t(node.mesh)];
  if (mapped == kMeshUnconverted) {
    Result<Mesh> mesh = convertMesh(meshes, node.mesh);
    if (!mesh) return mesh.error();
    if (mesh->primitives.empty()) {
      log::warn("{}: mesh '{}' has nothing to draw; node '{}' and any other node using it draw nothing", file,
                mesh->name, scene.nodes[size_t(self)].name);
      mapped = kMeshEmpty;
    } else {
      mapped = int(scene.meshes.size());
      scene.meshes.push_back(std::move(*mesh));
    }
  }
  if (mapped < 0) return okStatus();
  Instance instance;
  instance.name = node.name.empty() ? fmt::format("node{}", index) : node.name;
  instance.mesh = uint32_t(mapped);
  instance.worldFromObject = world;
  instance.node = self;  // reset by convertAnimations() unless the node moves
  const Mesh& mesh = scene.meshes[size_t(mapped)];
  bool skinned = false, morphed = false;
  for (const Primitive& p : mesh.primitives) skinned |= !p.influences.empty(), morphed |= !p.targets.empty();
  // A skin poses only meshes with JOINTS/WEIGHTS; it places them in world space on its own, so the
  // node's transform does not apply (glTF 2.0 §3.7.3.3: the skinned mesh node's transform is ignored).
  if (node.skin >= 0 && skinned) {
    instance.skin = node.skin;  // the glTF skin index; convertSkins() checks it
    instance.worldFromObject = glm::mat4(1.0f);
  } else if (node.skin >= 0) {
    log::warn("{}: node {} has a skin but its mesh has no JOINTS_0/WEIGHTS_0; drawn unskinned", file, index);
  }
  if (!node.weights.empty()) {
    size_t targets = mesh.primitives.front().targets.size();
    if (node.weights.size() != targets)
      return bad(file, "nodes[{}].weights: {} weights for {} morph targets", index, node.weights.size(), targets);
    for (double w : node.weights) {
      if (!std::isfinite(w)) return bad(file, "nodes[{}].weights: a weight is not finite", index);
      instance.morphWeights.push_back(float(w));
    }
  } else if (morphed) {
    instance.morphWeights = mesh.weights;
  }
  scene.nodes[size_t(self)].weights = instance.morphWeights;
  scene.instances.push_back(instance);
  return okStatus();
}

// The node's mesh once, or once per EXT_mesh_gpu_instancing element, each under a child node of
// its own (gltf_instancing.cpp).
Status addMeshInstances(MeshBuilder& meshes, std::vector<int>& meshMap, int index, int32_t self,
                        const glm::mat4& world) {
  Scene& scene = meshes.scene;
  Result<std::vector<SceneNode>> copies =
      gpuInstances(meshes.model, meshes.model.nodes[size_t(index)], size_t(index), meshes.file);
  if (!copies) return copies.error();
  if (copies->empty()) return addMeshInstance(meshes, meshMap, index, self, world);
  for (SceneNode& copy : *copies) {
    copy.parent = self;
    copy.worldFromNode = world * copy.parentFromNode();
    if (!finite(copy.worldFromNode)) return bad(meshes.file, "node {} has a non-finite instance transform", index);
    const int32_t child = int32_t(scene.nodes.size());
    const glm::mat4 childWorld = copy.worldFromNode;
    const std::string name = copy.name;
    scene.nodes.push_back(std::move(copy));
    const size_t before = scene.instances.size();
    RAYSTER_TRY(addMeshInstance(meshes, meshMap, index, child, childWorld));
    if (scene.instances.size() > before) scene.instances.back().name = name;
  }
  return okStatus();
}

// Walks the default scene's hierarchy into Scene::nodes (parents first), instances, cameras and
// lights. sceneNodeOf[glTF node] is its index in Scene::nodes, -1 where it is not reached.
Status convertNodes(const tinygltf::Model& model, const std::string& file, Scene& scene,
                    std::vector<int>& sceneNodeOf) {
  Result<std::vector<int>> roots = rootNodes(model, file);
  if (!roots) return roots.error();
  MeshBuilder meshes{model, file, scene, std::nullopt};
  std::vector<int> meshMap(model.meshes.size(), kMeshUnconverted);
  sceneNodeOf.assign(model.nodes.size(), -1);
  // Explicit stack of (glTF node, parent in Scene::nodes): hierarchies can be deep, and a hostile
  // file must not overflow ours.
  std::vector<std::pair<int, int32_t>> stack;
  for (auto it = roots->rbegin(); it != roots->rend(); ++it) stack.emplace_back(*it, -1);
  while (!stack.empty()) {
    auto [index, parent] = stack.back();
    stack.pop_back();
    if (sceneNodeOf[size_t(index)] >= 0)
      return bad(file, "node {} is reached twice: the node hierarchy has a cycle", index);
    const tinygltf::Node& node = model.nodes[size_t(index)];
    Result<SceneNode> converted = convertNode(node, size_t(index), file);
    if (!converted) return converted.error();
    converted->parent = parent;
    const glm::mat4 parentWorld = parent >= 0 ? scene.nodes[size_t(parent)].worldFromNode : glm::mat4(1.0f);
    const glm::mat4 world = parentWorld * converted->parentFromNode();
    if (!finite(world)) return bad(file, "node {} has a non-finite world transform", index);
    converted->worldFromNode = world;
    const int32_t self = int32_t(scene.nodes.size());
    sceneNodeOf[size_t(index)] = self;
    scene.nodes.push_back(std::move(*converted));

    if (node.mesh >= 0) RAYSTER_TRY(addMeshInstances(meshes, meshMap, index, self, world));
    // Cameras and lights remember their node: convertAnimations() keeps the link if it moves.
    if (node.camera >= 0) {
      RAYSTER_TRY(addCamera(model, node, world, scene, file));
      scene.cameras.back().node = self;
    }
    if (int light = nodeLight(node); light != -1) {
      const size_t lights = scene.lights.size();
      RAYSTER_TRY(addLight(model, node, light, world, scene, file));
      if (scene.lights.size() > lights) scene.lights.back().node = self;
    }
    for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) stack.emplace_back(*child, self);
  }
  return okStatus();
}

}  // namespace
}  // namespace gltf

Result<Scene> loadGltf(const fs::path& path) {
  const std::string file = path.filename().string();
  gltf::ImageDecodeState images;
  std::vector<gltf::FallbackBuffer> fallbacks;
  std::vector<gltf::DetachedIndices> detached;
  Result<tinygltf::Model> model = gltf::parse(path, file, images, fallbacks, detached);
  if (!model) return model.error();
  RAYSTER_TRY(gltf::reattachIndices(*model, file, detached));
  // The file as written is checked as the validator checks it (compressed data is the decoders'
  // to check: Draco dequantizes, so decoded extremes may differ from min/max by a step); then
  // compressed geometry becomes plain buffer data, so everything after reads it as such.
  RAYSTER_TRY(gltf::validateModel(*model, file));
  RAYSTER_TRY(gltf::decodeMeshopt(*model, file, fallbacks));
  RAYSTER_TRY(gltf::decodeDraco(*model, file));
  Scene scene;
  scene.name = path.stem().string();
  RAYSTER_TRY(gltf::convertMaterials(*model, file, images, scene));
  RAYSTER_TRY(gltf::readVariantNames(*model, file, scene));
  std::vector<int> sceneNodeOf;
  LoadProgress meshes("loading " + file, "mesh conversion");
  RAYSTER_TRY(gltf::convertNodes(*model, file, scene, sceneNodeOf));
  meshes.finish();
  RAYSTER_TRY(gltf::convertSkins(*model, file, sceneNodeOf, scene));
  RAYSTER_TRY(gltf::convertAnimations(*model, file, sceneNodeOf, scene));

  // validate() insists on a camera, but a camera-less file is fine here: applyDefaults() frames
  // one later. Check everything else with a stand-in that is removed again.
  const bool standIn = scene.cameras.empty();
  if (standIn) scene.cameras.push_back(Camera{});
  Status valid = validate(scene);
  if (standIn) scene.cameras.pop_back();
  if (!valid) return valid.error();
  return scene;
}

}  // namespace rayster::scene
