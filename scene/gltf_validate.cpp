// What the glTF 2.0 specification forbids and tinygltf lets through: the loader refuses it with one
// line naming the property (as the Khronos glTF-Validator reports it as an error), rather than
// drawing something the file does not say. Runs on the parsed model before anything is converted.
#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

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

// ---- JSON types, before tinygltf reads the file: tinygltf skips a property of the wrong type
// (a primitives object, a texture reference without its index) as if it were absent.
using Json = nlohmann::json;

bool isIndex(const Json& v) { return v.is_number_integer() && v.get<int64_t>() >= 0; }

class TypeCheck {
 public:
  explicit TypeCheck(const std::string& file) : file_(file) {}
  Status object(const Json& v, const std::string& path) const { return expect(v.is_object(), path, "an object"); }
  Status index(const Json& v, const std::string& path) const {
    return expect(isIndex(v), path, "a non-negative integer index");
  }
  Status string(const Json& v, const std::string& path) const { return expect(v.is_string(), path, "a string"); }
  Status numbers(const Json& v, const std::string& path) const {
    bool ok = v.is_array();
    if (ok)
      for (const Json& x : v) ok = ok && x.is_number();
    return expect(ok, path, "an array of numbers");
  }
  Status indices(const Json& v, const std::string& path) const {
    bool ok = v.is_array();
    if (ok)
      for (const Json& x : v) ok = ok && isIndex(x);
    return expect(ok, path, "an array of non-negative integer indices");
  }
  // An array of objects, each with an optional string name and object extensions.
  Status objects(const Json& v, const std::string& path) const {
    if (!v.is_array()) return expect(false, path, "an array");
    for (size_t i = 0; i < v.size(); ++i) {
      const std::string at = fmt::format("{}[{}]", path, i);
      RAYSTER_TRY(object(v[i], at));
      RAYSTER_TRY(common(v[i], at));
    }
    return okStatus();
  }
  // name, extensions (each an object) and extras (anything) of any glTF object.
  Status common(const Json& o, const std::string& path) const {
    if (auto n = o.find("name"); n != o.end()) RAYSTER_TRY(string(*n, path + ".name"));
    if (auto e = o.find("extensions"); e != o.end()) {
      RAYSTER_TRY(object(*e, path + ".extensions"));
      for (auto it = e->begin(); it != e->end(); ++it)
        RAYSTER_TRY(object(it.value(), path + ".extensions." + it.key()));
    }
    return okStatus();
  }
  // A textureInfo: an object with a required index.
  Status textureInfo(const Json& v, const std::string& path) const {
    RAYSTER_TRY(object(v, path));
    RAYSTER_TRY(common(v, path));
    const auto i = v.find("index");
    if (i == v.end()) return Error{ExitCode::BadInput, fmt::format("{}: {}.index is required", file_, path)};
    RAYSTER_TRY(index(*i, path + ".index"));
    if (auto t = v.find("texCoord"); t != v.end()) RAYSTER_TRY(index(*t, path + ".texCoord"));
    return okStatus();
  }

 private:
  Status expect(bool ok, const std::string& path, const char* what) const {
    if (ok) return okStatus();
    return Error{ExitCode::BadInput, fmt::format("{}: {} is not {}", file_, path, what)};
  }
  const std::string& file_;
};

template <class F>
Status eachMember(const Json& o, const char* key, F&& f) {
  if (auto v = o.find(key); v != o.end()) return f(*v);
  return okStatus();
}

}  // namespace

Status checkJsonTypes(const std::string& file, const nlohmann::json& root) {
  const TypeCheck t(file);
  RAYSTER_TRY(t.common(root, "glTF"));
  RAYSTER_TRY(eachMember(root, "asset", [&](const Json& a) { return t.object(a, "asset"); }));
  RAYSTER_TRY(eachMember(root, "scene", [&](const Json& s) { return t.index(s, "scene"); }));
  for (const char* key : {"accessors", "animations", "buffers", "bufferViews", "cameras", "images", "materials",
                          "meshes", "nodes", "samplers", "scenes", "skins", "textures"})
    RAYSTER_TRY(eachMember(root, key, [&](const Json& a) { return t.objects(a, key); }));
  if (auto meshes = root.find("meshes"); meshes != root.end())
    for (size_t m = 0; m < meshes->size(); ++m) {
      const std::string at = fmt::format("meshes[{}].primitives", m);
      const auto prims = (*meshes)[m].find("primitives");
      if (prims == (*meshes)[m].end()) return Error{ExitCode::BadInput, fmt::format("{}: {} is required", file, at)};
      RAYSTER_TRY(t.objects(*prims, at));
      for (size_t p = 0; p < prims->size(); ++p) {
        const Json& prim = (*prims)[p];
        const std::string pat = fmt::format("{}[{}]", at, p);
        RAYSTER_TRY(eachMember(prim, "attributes", [&](const Json& a) -> Status {
          RAYSTER_TRY(t.object(a, pat + ".attributes"));
          for (auto it = a.begin(); it != a.end(); ++it)
            RAYSTER_TRY(t.index(it.value(), pat + ".attributes." + it.key()));
          return okStatus();
        }));
        for (const char* key : {"indices", "material"})
          RAYSTER_TRY(eachMember(prim, key, [&](const Json& v) { return t.index(v, pat + "." + key); }));
      }
    }
  if (auto materials = root.find("materials"); materials != root.end())
    for (size_t m = 0; m < materials->size(); ++m) {
      const Json& mat = (*materials)[m];
      const std::string at = fmt::format("materials[{}]", m);
      RAYSTER_TRY(eachMember(mat, "pbrMetallicRoughness", [&](const Json& pbr) -> Status {
        RAYSTER_TRY(t.object(pbr, at + ".pbrMetallicRoughness"));
        for (const char* key : {"baseColorTexture", "metallicRoughnessTexture"})
          RAYSTER_TRY(eachMember(pbr, key,
                                 [&](const Json& v) { return t.textureInfo(v, at + ".pbrMetallicRoughness." + key); }));
        return okStatus();
      }));
      for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"})
        RAYSTER_TRY(eachMember(mat, key, [&](const Json& v) { return t.textureInfo(v, at + "." + key); }));
    }
  if (auto nodes = root.find("nodes"); nodes != root.end())
    for (size_t n = 0; n < nodes->size(); ++n) {
      const Json& node = (*nodes)[n];
      const std::string at = fmt::format("nodes[{}]", n);
      RAYSTER_TRY(eachMember(node, "children", [&](const Json& v) { return t.indices(v, at + ".children"); }));
      for (const char* key : {"mesh", "camera", "skin"})
        RAYSTER_TRY(eachMember(node, key, [&](const Json& v) { return t.index(v, at + "." + key); }));
      for (const char* key : {"matrix", "translation", "rotation", "scale", "weights"})
        RAYSTER_TRY(eachMember(node, key, [&](const Json& v) { return t.numbers(v, at + "." + key); }));
    }
  if (auto scenes = root.find("scenes"); scenes != root.end())
    for (size_t s = 0; s < scenes->size(); ++s)
      RAYSTER_TRY(eachMember((*scenes)[s], "nodes",
                             [&](const Json& v) { return t.indices(v, fmt::format("scenes[{}].nodes", s)); }));
  if (auto textures = root.find("textures"); textures != root.end())
    for (size_t i = 0; i < textures->size(); ++i)
      for (const char* key : {"source", "sampler"})
        RAYSTER_TRY(eachMember((*textures)[i], key,
                               [&](const Json& v) { return t.index(v, fmt::format("textures[{}].{}", i, key)); }));
  return okStatus();
}

Status validateModel(const tinygltf::Model& model, const std::string& file) {
  RAYSTER_TRY(checkAsset(model.asset, file));
  if (model.defaultScene != -1 && !inRange(model.defaultScene, model.scenes.size()))
    return bad(file, "scene {} does not exist ({} scenes)", model.defaultScene, model.scenes.size());
  RAYSTER_TRY(checkNodes(model, file));
  RAYSTER_TRY(checkTextures(model, file));
  RAYSTER_TRY(checkCameras(model, file));
  RAYSTER_TRY(checkLights(model, file));
  return okStatus();
}

}  // namespace rayster::scene::gltf
