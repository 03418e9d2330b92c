#include "scene/merge.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace rayster::scene {
namespace {

uint32_t rebase(uint32_t index, size_t base) { return index + static_cast<uint32_t>(base); }

void rebase(TextureRef& ref, size_t textureBase) {
  if (ref.valid()) ref.texture += static_cast<int32_t>(textureBase);
}

glm::vec3 transformPoint(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

// Directions of travel and up vectors are vectors, not normals: the linear part moves them.
glm::vec3 transformDirection(const glm::mat4& m, glm::vec3 d) {
  const glm::vec3 moved = glm::mat3(m) * d;
  const float len = glm::length(moved);
  return len > 0.0f && std::isfinite(len) ? moved / len : d;
}

}  // namespace

void appendScene(Scene& dst, Scene src, const glm::mat4& transform) {
  const size_t meshBase = dst.meshes.size(), materialBase = dst.materials.size(), imageBase = dst.images.size(),
               samplerBase = dst.samplers.size(), textureBase = dst.textures.size(), skinBase = dst.skins.size();

  // Variants of the same name in two models are one variant of the scene.
  std::vector<uint32_t> variantOf(src.variants.size());
  for (size_t v = 0; v < src.variants.size(); ++v) {
    auto it = std::find(dst.variants.begin(), dst.variants.end(), src.variants[v]);
    variantOf[v] = uint32_t(it - dst.variants.begin());
    if (it == dst.variants.end()) dst.variants.push_back(src.variants[v]);
  }
  for (Mesh& mesh : src.meshes) {
    for (Primitive& prim : mesh.primitives) {
      prim.material = rebase(prim.material, materialBase);
      prim.defaultMaterial = rebase(prim.defaultMaterial, materialBase);
      for (auto& [variant, material] : prim.variantMaterials) {
        variant = variantOf[variant];
        material = rebase(material, materialBase);
      }
    }
    for (Sphere& sphere : mesh.spheres) sphere.material = rebase(sphere.material, materialBase);
    dst.meshes.push_back(std::move(mesh));
  }
  for (Material& m : src.materials) {
    for (TextureRef* ref : m.textureRefs()) rebase(*ref, textureBase);
    dst.materials.push_back(std::move(m));
  }
  for (ImageData& image : src.images) dst.images.push_back(std::move(image));
  for (Sampler& sampler : src.samplers) dst.samplers.push_back(sampler);
  for (Texture& texture : src.textures)
    dst.textures.push_back({rebase(texture.image, imageBase), rebase(texture.sampler, samplerBase)});

  // The placement becomes a fixed root above src's hierarchy, so animation re-evaluated later
  // keeps the model where the scene file put it.
  if (!src.nodes.empty()) {
    SceneNode placement;
    placement.name = src.name.empty() ? std::string("placement") : src.name;
    placement.hasMatrix = true;
    placement.matrix = placement.worldFromNode = transform;
    dst.nodes.push_back(std::move(placement));
  }
  const size_t nodeBase = dst.nodes.size();
  for (SceneNode& node : src.nodes) {
    node.parent = node.parent >= 0 ? int32_t(rebase(uint32_t(node.parent), nodeBase)) : int32_t(nodeBase) - 1;
    node.worldFromNode = transform * node.worldFromNode;
    dst.nodes.push_back(std::move(node));
  }
  for (Animation& animation : src.animations) {
    for (AnimationChannel& channel : animation.channels) channel.node = rebase(channel.node, nodeBase);
    dst.animations.push_back(std::move(animation));
  }
  for (Skin& skin : src.skins) {
    for (uint32_t& joint : skin.joints) joint = rebase(joint, nodeBase);
    dst.skins.push_back(std::move(skin));
  }

  for (Instance& instance : src.instances) {
    instance.mesh = rebase(instance.mesh, meshBase);
    // A skinned instance is placed by its joints, which hang under the placement; its own
    // transform stays the identity.
    if (instance.skin < 0) instance.worldFromObject = transform * instance.worldFromObject;
    if (instance.skin >= 0) instance.skin = int32_t(rebase(uint32_t(instance.skin), skinBase));
    if (instance.node >= 0) instance.node = int32_t(rebase(uint32_t(instance.node), nodeBase));
    dst.instances.push_back(std::move(instance));
  }

  // A sphere light keeps its look relative to the model it lights: scale its radius like the model.
  const float meanScale = std::cbrt(std::abs(glm::determinant(glm::mat3(transform))));
  for (Light& light : src.lights) {
    light.position = transformPoint(transform, light.position);
    light.direction = transformDirection(transform, light.direction);
    if (std::isfinite(meanScale)) light.radius *= meanScale;
    if (light.node >= 0) light.node = int32_t(rebase(uint32_t(light.node), nodeBase));
    dst.lights.push_back(std::move(light));
  }
  for (Camera& camera : src.cameras) {
    camera.position = transformPoint(transform, camera.position);
    camera.target = transformPoint(transform, camera.target);
    camera.up = transformDirection(transform, camera.up);
    if (camera.node >= 0) camera.node = int32_t(rebase(uint32_t(camera.node), nodeBase));
    dst.cameras.push_back(std::move(camera));
  }

  // Two camera paths or environments cannot be blended; the first one given wins.
  if (dst.cameraPath.empty()) {
    for (CameraKey& key : src.cameraPath) {
      key.position = transformPoint(transform, key.position);
      key.target = transformPoint(transform, key.target);
    }
    dst.cameraPath = std::move(src.cameraPath);
  }
  if (dst.environment.kind == Environment::Kind::Black) dst.environment = std::move(src.environment);
  if (dst.ambient == glm::vec3(0.0f)) dst.ambient = src.ambient;
  if (dst.name.empty()) dst.name = std::move(src.name);
}

}  // namespace rayster::scene
