#include "scene/skinning.h"

#include <cmath>

#include <glm/gtc/matrix_inverse.hpp>

#include "scene/tangents.h"

namespace rayster::scene {
namespace {

bool hasTargets(const Mesh& mesh) {
  for (const Primitive& p : mesh.primitives)
    if (!p.targets.empty()) return true;
  return false;
}

glm::vec3 safeNormalize(glm::vec3 v, glm::vec3 fallback) {
  const float length = glm::length(v);
  return length > 0.0f && std::isfinite(length) ? v / length : fallback;
}

}  // namespace

bool deforms(const Scene& scene, const Instance& instance) {
  if (instance.mesh >= scene.meshes.size()) return false;
  return instance.skin >= 0 || hasTargets(scene.meshes[instance.mesh]);
}

bool anyDeforms(const Scene& scene) {
  for (const Instance& instance : scene.instances)
    if (deforms(scene, instance)) return true;
  return false;
}

std::vector<glm::mat4> jointMatrices(const Scene& scene, const Skin& skin) {
  std::vector<glm::mat4> out(skin.joints.size(), glm::mat4(1.0f));
  for (size_t j = 0; j < skin.joints.size(); ++j) {
    const glm::mat4 world =
        skin.joints[j] < scene.nodes.size() ? scene.nodes[skin.joints[j]].worldFromNode : glm::mat4(1.0f);
    out[j] = world * (j < skin.inverseBindMatrices.size() ? skin.inverseBindMatrices[j] : glm::mat4(1.0f));
  }
  return out;
}

std::vector<float> morphWeights(const Scene& scene, const Instance& instance, size_t targets) {
  std::vector<float> w = !instance.morphWeights.empty()        ? instance.morphWeights
                         : instance.mesh < scene.meshes.size() ? scene.meshes[instance.mesh].weights
                                                               : std::vector<float>{};
  w.resize(targets, 0.0f);
  return w;
}

Primitive deformPrimitive(const Scene& scene, const Instance& instance, const Primitive& primitive) {
  Primitive out = primitive;
  if (out.tangents.size() != out.positions.size()) generateTangents(out);  // as the upload does, on the rest shape
  const size_t n = out.positions.size();
  const std::vector<float> weights = morphWeights(scene, instance, primitive.targets.size());
  for (size_t t = 0; t < primitive.targets.size(); ++t) {
    const MorphTarget& target = primitive.targets[t];
    const float w = weights[t];
    if (w == 0.0f) continue;
    for (size_t i = 0; i < n; ++i) {
      if (i < target.positions.size()) out.positions[i] += w * target.positions[i];
      if (i < target.normals.size() && i < out.normals.size()) out.normals[i] += w * target.normals[i];
      if (i < target.tangents.size()) out.tangents[i] += glm::vec4(w * target.tangents[i], 0.0f);
    }
  }
  std::vector<glm::mat4> joints;
  if (instance.skin >= 0 && size_t(instance.skin) < scene.skins.size())
    joints = jointMatrices(scene, scene.skins[size_t(instance.skin)]);
  for (size_t i = 0; i < n; ++i) {
    glm::mat4 m(1.0f);
    if (!joints.empty() && !primitive.influences.empty()) {
      glm::mat4 sum(0.0f);
      float total = 0.0f;
      for (const SkinInfluences& set : primitive.influences)
        for (int k = 0; k < 4; ++k) {
          const float w = set.weights[i][k];
          if (w == 0.0f) continue;
          const uint32_t j = set.joints[i][k];
          sum += w * (j < joints.size() ? joints[j] : glm::mat4(1.0f));
          total += w;
        }
      // Weights sum to 1 up to their quantisation; a vertex with none stays in bind space.
      if (total > 0.0f) m = sum / total;
    }
    out.positions[i] = glm::vec3(m * glm::vec4(out.positions[i], 1.0f));
    const glm::mat3 linear(m);
    if (i < out.normals.size())
      out.normals[i] = safeNormalize(glm::inverseTranspose(linear) * out.normals[i], glm::vec3(0, 0, 1));
    out.tangents[i] =
        glm::vec4(safeNormalize(linear * glm::vec3(out.tangents[i]), glm::vec3(1, 0, 0)), out.tangents[i].w);
  }
  out.influences.clear();
  out.targets.clear();
  return out;
}

Scene bakePose(const Scene& scene) {
  Scene baked = scene;
  baked.animations.clear();
  baked.skins.clear();
  for (Mesh& mesh : baked.meshes) {
    mesh.weights.clear();
    for (Primitive& p : mesh.primitives) p.influences.clear(), p.targets.clear();
  }
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& src = scene.instances[i];
    Instance& dst = baked.instances[i];
    dst.node = -1;
    dst.skin = -1;
    dst.morphWeights.clear();
    if (!deforms(scene, src)) continue;
    Mesh mesh;
    mesh.name = scene.meshes[src.mesh].name + "@" + src.name;
    for (const Primitive& p : scene.meshes[src.mesh].primitives)
      mesh.primitives.push_back(deformPrimitive(scene, src, p));
    dst.mesh = uint32_t(baked.meshes.size());
    baked.meshes.push_back(std::move(mesh));
  }
  for (Light& light : baked.lights) light.node = -1;
  for (Camera& camera : baked.cameras) camera.node = -1;
  return baked;
}

}  // namespace rayster::scene
