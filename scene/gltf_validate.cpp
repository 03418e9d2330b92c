// What the glTF 2.0 specification forbids and tinygltf lets through: the loader refuses it with one
// line naming the property (as the Khronos glTF-Validator reports it as an error), rather than
// drawing something the file does not say. The JSON types here, then the schema and its links
// (gltf_schema*.cpp) on the raw JSON; after parsing, the checks on the data.

#include <nlohmann/json.hpp>

#include "core/log.h"
#include "scene/gltf_schema.h"

namespace rayster::scene::gltf {
namespace {

// Values the schema allows (any integer or string, for forward compatibility) but glTF 2.0 does not
// define: the validator only warns, so the file loads, with the default the converters use.
void warnUnknownEnums(const tinygltf::Model& model, const std::string& file) {
  auto filter = [](int f, bool min) { return f == -1 || f == 9728 || f == 9729 || (min && f >= 9984 && f <= 9987); };
  auto wrap = [](int w) { return w == -1 || w == 33071 || w == 33648 || w == 10497; };
  for (size_t i = 0; i < model.samplers.size(); ++i) {
    const tinygltf::Sampler& s = model.samplers[i];
    if (!filter(s.magFilter, false))
      log::warn("{}: samplers[{}].magFilter {} is not 9728 or 9729; filtering linearly", file, i, s.magFilter);
    if (!filter(s.minFilter, true))
      log::warn("{}: samplers[{}].minFilter {} is not one of 9728, 9729, 9984-9987; filtering linearly with mipmaps",
                file, i, s.minFilter);
    if (!wrap(s.wrapS))
      log::warn("{}: samplers[{}].wrapS {} is not 33071, 33648 or 10497; repeating", file, i, s.wrapS);
    if (!wrap(s.wrapT))
      log::warn("{}: samplers[{}].wrapT {} is not 33071, 33648 or 10497; repeating", file, i, s.wrapT);
  }
  for (size_t i = 0; i < model.cameras.size(); ++i)
    if (model.cameras[i].type != "perspective" && model.cameras[i].type != "orthographic")
      log::warn("{}: cameras[{}].type '{}' is neither perspective nor orthographic; read as perspective", file, i,
                model.cameras[i].type);
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const std::string& mode = model.materials[i].alphaMode;
    if (mode != "OPAQUE" && mode != "MASK" && mode != "BLEND")
      log::warn("{}: materials[{}].alphaMode '{}' is not OPAQUE, MASK or BLEND; drawn opaque", file, i, mode);
  }
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
  return checkSchema(file, root);
}

Status explainGlbBuffer(const std::string& file, std::string_view json, int64_t binLength) {
  const Json root = Json::parse(json.begin(), json.end(), nullptr, false);
  const auto buffers = root.is_object() ? root.find("buffers") : root.end();
  if (!root.is_object() || buffers == root.end() || !buffers->is_array() || buffers->empty()) return okStatus();
  const Json& b = (*buffers)[0];
  if (!b.is_object() || b.contains("uri")) return okStatus();
  if (binLength < 0) return bad(file, "buffers[0]: has no uri, and the GLB has no BIN chunk to hold its bytes");
  const auto length = b.find("byteLength");
  if (length != b.end() && length->is_number_unsigned() && length->get<uint64_t>() > uint64_t(binLength))
    return bad(file, "buffers[0].byteLength: {}, but the GLB BIN chunk holds {} bytes", length->get<uint64_t>(),
               binLength);
  return okStatus();
}

Status validateModel(const tinygltf::Model& model, const std::string& file) {
  // The schema and the links were checked on the JSON (checkSchema); what is left is in the data.
  RAYSTER_TRY(checkAccessorData(model, file));
  warnUnknownEnums(model, file);
  return okStatus();
}

}  // namespace rayster::scene::gltf
