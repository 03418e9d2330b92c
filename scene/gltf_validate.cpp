// What the glTF 2.0 specification forbids and tinygltf lets through: the loader refuses it with one
// line naming the property (as the Khronos glTF-Validator reports it as an error), rather than
// drawing something the file does not say. Runs on the parsed model before anything is converted.
#include <cmath>
#include <numbers>

#include "scene/gltf_internal.h"

namespace rayster::scene::gltf {
namespace {

bool inRange(int index, size_t count) { return index >= 0 && size_t(index) < count; }

Status checkAsset(const tinygltf::Asset& asset, const std::string& file) {
  // asset.version is "major.minor"; a loader for 2.x must not guess at another major version.
  auto major = [](const std::string& v) -> int {
    const size_t dot = v.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 >= v.size()) return -1;
    for (size_t i = 0; i < v.size(); ++i)
      if (i != dot && (v[i] < '0' || v[i] > '9')) return -1;
    return std::stoi(v.substr(0, std::min<size_t>(dot, 6)));
  };
  if (major(asset.version) != 2)
    return bad(file, "asset.version '{}' is not a glTF 2.x version (this loader reads glTF 2.0)", asset.version);
  if (!asset.minVersion.empty()) {
    const int m = major(asset.minVersion);
    if (m != 2 || asset.minVersion != "2.0")
      return bad(file, "asset.minVersion '{}' asks for more than glTF 2.0", asset.minVersion);
  }
  return okStatus();
}

Status checkNodes(const tinygltf::Model& model, const std::string& file) {
  for (size_t i = 0; i < model.nodes.size(); ++i) {
    const tinygltf::Node& n = model.nodes[i];
    if (!n.matrix.empty() && n.matrix.size() != 16)
      return bad(file, "nodes[{}].matrix has {} numbers, not 16", i, n.matrix.size());
    if (!n.translation.empty() && n.translation.size() != 3)
      return bad(file, "nodes[{}].translation has {} numbers, not 3", i, n.translation.size());
    if (!n.rotation.empty() && n.rotation.size() != 4)
      return bad(file, "nodes[{}].rotation has {} numbers, not 4", i, n.rotation.size());
    if (!n.scale.empty() && n.scale.size() != 3)
      return bad(file, "nodes[{}].scale has {} numbers, not 3", i, n.scale.size());
    if (n.mesh != -1 && !inRange(n.mesh, model.meshes.size()))
      return bad(file, "nodes[{}].mesh {} does not exist", i, n.mesh);
    if (n.camera != -1 && !inRange(n.camera, model.cameras.size()))
      return bad(file, "nodes[{}].camera {} does not exist", i, n.camera);
  }
  return okStatus();
}

Status checkTextures(const tinygltf::Model& model, const std::string& file) {
  for (size_t i = 0; i < model.textures.size(); ++i) {
    const tinygltf::Texture& t = model.textures[i];
    // No source is allowed (an extension may supply the image); one that is given must exist.
    if (t.source != -1 && !inRange(t.source, model.images.size()))
      return bad(file, "textures[{}].source {} does not exist ({} images)", i, t.source, model.images.size());
    if (t.sampler != -1 && !inRange(t.sampler, model.samplers.size()))
      return bad(file, "textures[{}].sampler {} does not exist ({} samplers)", i, t.sampler, model.samplers.size());
  }
  for (size_t i = 0; i < model.images.size(); ++i) {
    const tinygltf::Image& im = model.images[i];
    if (im.bufferView != -1 && !inRange(im.bufferView, model.bufferViews.size()))
      return bad(file, "images[{}].bufferView {} does not exist", i, im.bufferView);
  }
  auto filter = [](int f, bool min) { return f == -1 || f == 9728 || f == 9729 || (min && f >= 9984 && f <= 9987); };
  auto wrap = [](int w) { return w == -1 || w == 33071 || w == 33648 || w == 10497; };
  for (size_t i = 0; i < model.samplers.size(); ++i) {
    const tinygltf::Sampler& s = model.samplers[i];
    if (!filter(s.magFilter, false)) return bad(file, "samplers[{}].magFilter {} is not 9728 or 9729", i, s.magFilter);
    if (!filter(s.minFilter, true))
      return bad(file, "samplers[{}].minFilter {} is not one of 9728, 9729, 9984-9987", i, s.minFilter);
    if (!wrap(s.wrapS)) return bad(file, "samplers[{}].wrapS {} is not 33071, 33648 or 10497", i, s.wrapS);
    if (!wrap(s.wrapT)) return bad(file, "samplers[{}].wrapT {} is not 33071, 33648 or 10497", i, s.wrapT);
  }
  // The core material textures; an index must name a texture.
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const tinygltf::Material& m = model.materials[i];
    const std::pair<const char*, int> refs[] = {
        {"pbrMetallicRoughness.baseColorTexture", m.pbrMetallicRoughness.baseColorTexture.index},
        {"pbrMetallicRoughness.metallicRoughnessTexture", m.pbrMetallicRoughness.metallicRoughnessTexture.index},
        {"normalTexture", m.normalTexture.index},
        {"occlusionTexture", m.occlusionTexture.index},
        {"emissiveTexture", m.emissiveTexture.index}};
    for (const auto& [name, index] : refs)
      if (index != -1 && !inRange(index, model.textures.size()))
        return bad(file, "materials[{}].{} uses texture {}, which does not exist ({} textures)", i, name, index,
                   model.textures.size());
  }
  return okStatus();
}

Status checkCameras(const tinygltf::Model& model, const std::string& file) {
  for (size_t i = 0; i < model.cameras.size(); ++i) {
    const tinygltf::Camera& c = model.cameras[i];
    if (c.type == "perspective") {
      const tinygltf::PerspectiveCamera& p = c.perspective;
      if (!(p.yfov > 0.0)) return bad(file, "cameras[{}].perspective.yfov {} is not above 0", i, p.yfov);
      if (!(p.znear > 0.0)) return bad(file, "cameras[{}].perspective.znear {} is not above 0", i, p.znear);
      if (p.zfar != 0.0 && !(p.zfar > p.znear))  // 0: absent (an infinite projection)
        return bad(file, "cameras[{}].perspective.zfar {} is not beyond znear {}", i, p.zfar, p.znear);
      if (p.aspectRatio != 0.0 && !(p.aspectRatio > 0.0))
        return bad(file, "cameras[{}].perspective.aspectRatio {} is not above 0", i, p.aspectRatio);
    } else if (c.type == "orthographic") {
      const tinygltf::OrthographicCamera& o = c.orthographic;
      if (o.xmag == 0.0 || o.ymag == 0.0) return bad(file, "cameras[{}].orthographic xmag or ymag is 0", i);
      if (!(o.znear >= 0.0)) return bad(file, "cameras[{}].orthographic.znear {} is negative", i, o.znear);
      if (!(o.zfar > o.znear))
        return bad(file, "cameras[{}].orthographic.zfar {} is not beyond znear {}", i, o.zfar, o.znear);
    } else {
      return bad(file, "cameras[{}].type '{}' is neither perspective nor orthographic", i, c.type);
    }
  }
  return okStatus();
}

Status checkLights(const tinygltf::Model& model, const std::string& file) {
  constexpr double kHalfPi = std::numbers::pi / 2.0;
  for (size_t i = 0; i < model.lights.size(); ++i) {
    const tinygltf::Light& l = model.lights[i];
    if (!(l.intensity >= 0.0))
      return bad(file, "KHR_lights_punctual light {} has negative intensity {}", i, l.intensity);
    if (l.range != 0.0 && !(l.range > 0.0))  // 0: absent (no range)
      return bad(file, "KHR_lights_punctual light {} has range {}, not above 0", i, l.range);
    if (l.type == "spot") {
      const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
      if (!(outer > 0.0 && outer <= kHalfPi))
        return bad(file, "KHR_lights_punctual light {}: spot.outerConeAngle {} is not in (0, pi/2]", i, outer);
      if (!(inner >= 0.0 && inner < outer))
        return bad(file, "KHR_lights_punctual light {}: spot.innerConeAngle {} is not in [0, outerConeAngle {})", i,
                   inner, outer);
    }
  }
  return okStatus();
}

}  // namespace

Status validateModel(const tinygltf::Model& model, const std::string& file) {
  RAYSTER_TRY(checkAsset(model.asset, file));
  RAYSTER_TRY(checkNodes(model, file));
  RAYSTER_TRY(checkTextures(model, file));
  RAYSTER_TRY(checkCameras(model, file));
  RAYSTER_TRY(checkLights(model, file));
  return okStatus();
}

}  // namespace rayster::scene::gltf
