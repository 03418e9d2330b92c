#include "scene/scene.h"

#include <algorithm>
#include <cmath>

#include "scene/skinning.h"

namespace rayster::scene {
namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

std::string meshLabel(const Mesh& mesh, size_t index) {
  return mesh.name.empty() ? fmt::format("mesh {}", index) : fmt::format("mesh {} '{}'", index, mesh.name);
}

Status validatePrimitive(const Scene& scene, const Mesh& mesh, size_t meshIndex, const Primitive& prim,
                         size_t primIndex) {
  const std::string where = fmt::format("{} primitive {}", meshLabel(mesh, meshIndex), primIndex);
  const size_t vertexCount = prim.positions.size();
  if (prim.normals.size() != vertexCount)
    return makeError(ExitCode::BadInput, "{}: {} normals for {} positions", where, prim.normals.size(), vertexCount);
  if (!prim.uvs.empty() && prim.uvs.size() != vertexCount)
    return makeError(ExitCode::BadInput, "{}: {} uvs for {} positions", where, prim.uvs.size(), vertexCount);
  if (!prim.uvs1.empty() && prim.uvs1.size() != vertexCount)
    return makeError(ExitCode::BadInput, "{}: {} second uvs for {} positions", where, prim.uvs1.size(), vertexCount);
  if (!prim.colors.empty() && prim.colors.size() != vertexCount)
    return makeError(ExitCode::BadInput, "{}: {} colours for {} positions", where, prim.colors.size(), vertexCount);
  if (!prim.tangents.empty() && prim.tangents.size() != vertexCount)
    return makeError(ExitCode::BadInput, "{}: {} tangents for {} positions", where, prim.tangents.size(), vertexCount);
  if (prim.indices.size() % 3 != 0)
    return makeError(ExitCode::BadInput, "{}: index count {} is not a multiple of 3", where, prim.indices.size());
  for (size_t i = 0; i < prim.indices.size(); ++i)
    if (prim.indices[i] >= vertexCount)
      return makeError(ExitCode::BadInput, "{}: index {} is {}, past the vertex count {}", where, i, prim.indices[i],
                       vertexCount);
  for (size_t i = 0; i < vertexCount; ++i)
    if (!finite(prim.positions[i])) return makeError(ExitCode::BadInput, "{}: position {} is not finite", where, i);
  if (prim.material >= scene.materials.size())
    return makeError(ExitCode::BadInput, "{}: material {} out of range ({} materials)", where, prim.material,
                     scene.materials.size());
  for (const auto& [variant, material] : prim.variantMaterials)
    if (variant >= scene.variants.size() || material >= scene.materials.size() ||
        prim.defaultMaterial >= scene.materials.size())
      return makeError(ExitCode::BadInput, "{}: a material variant mapping is out of range", where);
  for (size_t s = 0; s < prim.influences.size(); ++s)
    if (prim.influences[s].joints.size() != vertexCount || prim.influences[s].weights.size() != vertexCount)
      return makeError(ExitCode::BadInput, "{}: skin influence set {} has {}/{} joints/weights for {} positions", where,
                       s, prim.influences[s].joints.size(), prim.influences[s].weights.size(), vertexCount);
  for (size_t t = 0; t < prim.targets.size(); ++t) {
    const MorphTarget& target = prim.targets[t];
    for (size_t n : {target.positions.size(), target.normals.size(), target.tangents.size()})
      if (n != 0 && n != vertexCount)
        return makeError(ExitCode::BadInput, "{}: morph target {} has {} elements for {} positions", where, t, n,
                         vertexCount);
  }
  return okStatus();
}

// A skinned instance's joints exist, and every joint index of its mesh names one of them (the
// deformation reads joint matrices by these indices).
Status validateSkin(const Scene& scene, const Instance& instance, size_t index, const std::string& sceneName) {
  if (instance.skin < 0) return okStatus();
  if (size_t(instance.skin) >= scene.skins.size())
    return makeError(ExitCode::BadInput, "{}: instance {} '{}' uses skin {} ({} skins)", sceneName, index,
                     instance.name, instance.skin, scene.skins.size());
  const Skin& skin = scene.skins[size_t(instance.skin)];
  if (skin.joints.empty() || skin.inverseBindMatrices.size() != skin.joints.size())
    return makeError(ExitCode::BadInput, "{}: skin '{}' has {} joints and {} inverse bind matrices", sceneName,
                     skin.name, skin.joints.size(), skin.inverseBindMatrices.size());
  for (uint32_t joint : skin.joints)
    if (joint >= scene.nodes.size())
      return makeError(ExitCode::BadInput, "{}: skin '{}' uses node {} ({} nodes)", sceneName, skin.name, joint,
                       scene.nodes.size());
  const Mesh& mesh = scene.meshes[instance.mesh];
  for (size_t p = 0; p < mesh.primitives.size(); ++p)
    for (const SkinInfluences& set : mesh.primitives[p].influences)
      for (size_t v = 0; v < set.joints.size(); ++v)
        for (int k = 0; k < 4; ++k)
          if (set.weights[v][k] > 0.0f && set.joints[v][k] >= skin.joints.size())
            return makeError(ExitCode::BadInput, "{}: {} primitive {} vertex {} uses joint {} of skin '{}' ({} joints)",
                             sceneName, meshLabel(mesh, instance.mesh), p, v, set.joints[v][k], skin.name,
                             skin.joints.size());
  return okStatus();
}

Status validateAnimation(const Scene& scene, const std::string& sceneName) {
  for (size_t i = 0; i < scene.nodes.size(); ++i)
    if (scene.nodes[i].parent >= int32_t(i) || scene.nodes[i].parent < -1)
      return makeError(ExitCode::BadInput, "{}: node {} '{}' has parent {}, which does not come before it", sceneName,
                       i, scene.nodes[i].name, scene.nodes[i].parent);
  for (size_t i = 0; i < scene.instances.size(); ++i)
    if (scene.instances[i].node >= int32_t(scene.nodes.size()) || scene.instances[i].node < -1)
      return makeError(ExitCode::BadInput, "{}: instance {} '{}' follows node {} ({} nodes)", sceneName, i,
                       scene.instances[i].name, scene.instances[i].node, scene.nodes.size());
  for (const Animation& animation : scene.animations)
    for (size_t c = 0; c < animation.channels.size(); ++c) {
      const AnimationChannel& channel = animation.channels[c];
      const size_t per = channel.interp == AnimationChannel::CubicSpline ? 3 : 1;
      const bool weights = channel.path == AnimationChannel::Weights;
      if (channel.node >= scene.nodes.size() || channel.times.empty() ||
          (!weights && channel.values.size() != per * channel.times.size()) ||
          (weights &&
           (channel.weightCount == 0 || channel.weights.size() != per * channel.times.size() * channel.weightCount)))
        return makeError(ExitCode::BadInput, "{}: animation '{}' channel {} has a bad node or key count", sceneName,
                         animation.name, c);
    }
  return okStatus();
}

}  // namespace

void Aabb::extend(glm::vec3 p) {
  min = glm::min(min, p);
  max = glm::max(max, p);
}

bool Aabb::valid() const { return min.x <= max.x && min.y <= max.y && min.z <= max.z; }

Aabb Scene::bounds() const {
  Aabb box;
  for (const Instance& instance : instances) {
    if (instance.mesh >= meshes.size()) continue;
    if (instance.skin >= 0) {  // in world space only once posed
      for (const Primitive& prim : meshes[instance.mesh].primitives)
        for (const glm::vec3& p : deformPrimitive(*this, instance, prim).positions) box.extend(p);
      continue;
    }
    for (const Primitive& prim : meshes[instance.mesh].primitives)
      for (const glm::vec3& p : prim.positions) box.extend(glm::vec3(instance.worldFromObject * glm::vec4(p, 1.0f)));
    for (const Sphere& s : meshes[instance.mesh].spheres)
      for (int corner = 0; corner < 8; ++corner) {
        glm::vec3 c = s.center + s.radius * glm::vec3(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1);
        box.extend(glm::vec3(instance.worldFromObject * glm::vec4(c, 1.0f)));
      }
  }
  return box;
}

size_t Scene::triangleCount() const {
  size_t count = 0;
  for (const Instance& instance : instances) {
    if (instance.mesh >= meshes.size()) continue;
    for (const Primitive& prim : meshes[instance.mesh].primitives) count += prim.indices.size() / 3;
  }
  return count;
}

Status validate(const Scene& scene) {
  const std::string sceneName = scene.name.empty() ? std::string("scene") : scene.name;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    if (!mesh.primitives.empty() && !mesh.spheres.empty())
      return makeError(ExitCode::BadInput, "{}: holds both triangles and spheres", meshLabel(mesh, m));
    for (const Sphere& s : mesh.spheres)
      if (!finite(s.center) || !std::isfinite(s.radius) || s.radius <= 0.0f || s.material >= scene.materials.size())
        return makeError(ExitCode::BadInput, "{}: a sphere has a bad centre, radius or material", meshLabel(mesh, m));
  }
  for (size_t i = 0; i < scene.textures.size(); ++i)
    if (scene.textures[i].image >= scene.images.size() || scene.textures[i].sampler >= scene.samplers.size())
      return makeError(ExitCode::BadInput, "{}: texture {} refers to a missing image or sampler", sceneName, i);
  for (size_t i = 0; i < scene.images.size(); ++i) {
    const ImageData& img = scene.images[i];
    if (img.width <= 0 || img.height <= 0 || img.rgba.size() != size_t(img.width) * size_t(img.height) * 4)
      return makeError(ExitCode::BadInput, "{}: image {} '{}' has inconsistent size", sceneName, i, img.name);
  }
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& mat = scene.materials[i];
    for (const TextureRef* t : mat.textureRefs())
      if (t->valid() && (size_t(t->texture) >= scene.textures.size() || t->texCoord > 1))
        return makeError(ExitCode::BadInput, "{}: material {} '{}' uses a missing texture or UV set", sceneName, i,
                         mat.name);
  }
  if (scene.environment.kind == Environment::Kind::Map &&
      scene.environment.rgb.size() != size_t(scene.environment.width) * size_t(scene.environment.height) * 3)
    return makeError(ExitCode::BadInput, "{}: environment map has inconsistent size", sceneName);
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    for (size_t p = 0; p < scene.meshes[m].primitives.size(); ++p)
      RAYSTER_TRY(validatePrimitive(scene, scene.meshes[m], m, scene.meshes[m].primitives[p], p));
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& instance = scene.instances[i];
    if (instance.mesh >= scene.meshes.size())
      return makeError(ExitCode::BadInput, "{}: instance {} '{}' uses mesh {} ({} meshes)", sceneName, i, instance.name,
                       instance.mesh, scene.meshes.size());
    if (!finite(instance.worldFromObject))
      return makeError(ExitCode::BadInput, "{}: instance {} '{}' has a non-finite transform", sceneName, i,
                       instance.name);
    RAYSTER_TRY(validateSkin(scene, instance, i, sceneName));
  }
  RAYSTER_TRY(validateAnimation(scene, sceneName));
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& light = scene.lights[i];
    if (!finite(light.position) || !finite(light.direction) || !finite(light.color) ||
        !std::isfinite(light.intensity) || !std::isfinite(light.radius))
      return makeError(ExitCode::BadInput, "{}: light {} '{}' has a non-finite parameter", sceneName, i, light.name);
  }
  if (scene.cameras.empty()) return makeError(ExitCode::BadInput, "{}: no camera", sceneName);
  for (size_t i = 0; i < scene.cameras.size(); ++i) {
    const Camera& camera = scene.cameras[i];
    if (!finite(camera.position) || !finite(camera.target) || !finite(camera.up) ||
        glm::dot(camera.target - camera.position, camera.target - camera.position) == 0.0f)
      return makeError(ExitCode::BadInput, "{}: camera {} '{}' has a degenerate view", sceneName, i, camera.name);
  }
  return okStatus();
}

Status selectVariant(Scene& scene, const std::string& name) {
  uint32_t variant = 0;
  if (!name.empty()) {
    auto it = std::find(scene.variants.begin(), scene.variants.end(), name);
    if (it == scene.variants.end()) {
      std::string names;
      for (const std::string& v : scene.variants) names += (names.empty() ? "'" : ", '") + v + "'";
      return makeError(ExitCode::BadInput, "{}: no material variant '{}' ({})",
                       scene.name.empty() ? std::string("scene") : scene.name, name,
                       names.empty() ? std::string("the scene has no variants") : "variants: " + names);
    }
    variant = uint32_t(it - scene.variants.begin());
  }
  for (Mesh& mesh : scene.meshes)
    for (Primitive& prim : mesh.primitives) {
      if (prim.variantMaterials.empty()) continue;  // defaultMaterial is only kept where variants exist
      prim.material = prim.defaultMaterial;
      if (name.empty()) continue;
      for (const auto& [v, material] : prim.variantMaterials)
        if (v == variant) prim.material = material;
    }
  return okStatus();
}

}  // namespace rayster::scene
