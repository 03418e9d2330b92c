// glTF skins -> scene::Skin: joints mapped to Scene::nodes, inverse bind matrices read through the
// bounds-checked accessors (identity where the file has none, as glTF 2.0 §5.28 says).
#include <cmath>

#include "core/log.h"
#include "scene/gltf_internal.h"

namespace rayster::scene::gltf {
namespace {

bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// The skin's joints in Scene::nodes, or an empty list (with the reason in `why`) where it cannot
// be posed.
Result<Skin> convertSkin(const tinygltf::Model& model, size_t index, const std::string& file,
                         const std::vector<int>& sceneNodeOf, std::string& why) {
  const tinygltf::Skin& src = model.skins[index];
  Skin skin;
  skin.name = src.name.empty() ? fmt::format("skin{}", index) : src.name;
  if (src.joints.empty()) return bad(file, "skins[{}].joints: empty, need at least 1 joint", index);
  for (size_t j = 0; j < src.joints.size(); ++j) {
    const int joint = src.joints[j];
    if (joint < 0 || size_t(joint) >= model.nodes.size())
      return bad(file, "skins[{}].joints[{}]: node {} does not exist", index, j, joint);
    if (sceneNodeOf[size_t(joint)] < 0 && why.empty())
      why = fmt::format("joint node {} is not in the displayed scene", joint);
    skin.joints.push_back(uint32_t(std::max(sceneNodeOf[size_t(joint)], 0)));
  }
  if (src.inverseBindMatrices >= 0) {
    Result<std::vector<glm::mat4>> matrices = readMat4(model, src.inverseBindMatrices, file);
    if (!matrices) return matrices.error();
    if (matrices->size() < skin.joints.size())
      return bad(file, "skins[{}].inverseBindMatrices: {} matrices for {} joints", index, matrices->size(),
                 skin.joints.size());
    matrices->resize(skin.joints.size());
    for (size_t j = 0; j < matrices->size(); ++j)
      if (!finite((*matrices)[j])) return bad(file, "skins[{}].inverseBindMatrices[{}]: not finite", index, j);
    skin.inverseBindMatrices = std::move(*matrices);
  } else {
    skin.inverseBindMatrices.assign(skin.joints.size(), glm::mat4(1.0f));
  }
  return skin;
}

}  // namespace

Status convertSkins(const tinygltf::Model& model, const std::string& file, const std::vector<int>& sceneNodeOf,
                    Scene& scene) {
  std::vector<bool> used(model.skins.size(), false);
  for (const Instance& instance : scene.instances)
    if (instance.skin >= 0) {
      if (size_t(instance.skin) >= model.skins.size())
        return bad(file, "node '{}' uses skin {}, which does not exist", instance.name, instance.skin);
      used[size_t(instance.skin)] = true;
    }
  std::vector<bool> posable(model.skins.size(), true);
  for (size_t s = 0; s < model.skins.size(); ++s) {
    Skin skin;
    if (used[s]) {
      std::string why;
      Result<Skin> converted = convertSkin(model, s, file, sceneNodeOf, why);
      if (!converted) return converted.error();
      skin = std::move(*converted);
      if (!why.empty()) {
        log::warn("{}: skin '{}' cannot be posed ({}); its meshes are drawn in the bind pose", file, skin.name, why);
        posable[s] = false;
      }
    }
    scene.skins.push_back(std::move(skin));  // every glTF skin keeps its index
  }
  for (Instance& instance : scene.instances)
    if (instance.skin >= 0 && !posable[size_t(instance.skin)]) instance.skin = -1;
  return okStatus();
}

}  // namespace rayster::scene::gltf
