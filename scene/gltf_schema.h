#pragma once
// The glTF 2.0 schema and the Khronos glTF-Validator's link checks, on the raw JSON (tinygltf takes
// a wrong type or an absent property for its default, so only the JSON still says what the file
// says). Shared by scene/gltf_schema*.cpp; include only from the glTF loader's files.
//
// Every check here is one the validator reports as an ERROR; what it only warns about (an unknown
// enum value: the schema allows any integer or string there for forward compatibility) is loaded,
// with a default, by the converters. Each failure names the JSON path: "nodes[3].matrix: 15
// numbers, need 16".
#include <initializer_list>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "scene/gltf_internal.h"

namespace rayster::scene::gltf::schema {

using Json = nlohmann::json;

// A closed or half-open interval of allowed numbers.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool loOpen = false, hiOpen = false;
  bool contains(double v) const { return (loOpen ? v > lo : v >= lo) && (hiOpen ? v < hi : v <= hi); }
  std::string describe() const;
};
inline constexpr Range kAny{};
inline constexpr Range kUnit{0.0, 1.0};
inline constexpr Range kNonNegative{0.0, std::numeric_limits<double>::infinity()};
inline constexpr Range kPositive{0.0, std::numeric_limits<double>::infinity(), true};

// One document being checked: its root, the file name every message starts with, and readers of
// optional properties that fail with "<path>: <cause>" when a property has the wrong type or range.
class Checker {
 public:
  Checker(const std::string& file, const Json& root) : file_(file), root_(root) {}
  const Json& root() const { return root_; }

  template <class... A>
  Error fail(const std::string& path, fmt::format_string<A...> f, A&&... args) const {
    return Error{ExitCode::BadInput, fmt::format("{}: {}: {}", file_, path, fmt::format(f, std::forward<A>(args)...))};
  }

  // The property, or nullptr when absent (or `o` is not an object).
  static const Json* find(const Json& o, const char* key);
  // Elements in the top-level array `name` (0 when absent).
  size_t count(const char* name) const;
  // The top-level array's element `i` (which the caller knows exists).
  const Json& element(const char* name, size_t i) const { return root_.at(name).at(i); }

  // Optional (or required) property `key` of `o` at `path`: an index into top-level `array`.
  Status ref(const Json& o, const char* key, const std::string& path, const char* array, bool required = false) const;
  // An integer index property into a count known to the caller (e.g. a light in an extension).
  Status indexInto(const Json& o, const char* key, const std::string& path, size_t count, const char* what,
                   bool required = false) const;
  // Optional (or required) number in `range`.
  Status number(const Json& o, const char* key, const std::string& path, Range range, bool required = false) const;
  // Optional (or required) integer in `range`.
  Status integer(const Json& o, const char* key, const std::string& path, Range range, bool required = false) const;
  // Optional array of numbers with one of `lengths` and every element in `range`.
  Status numbers(const Json& o, const char* key, const std::string& path, std::initializer_list<size_t> lengths,
                 Range range = kAny) const;
  // Optional array of indices into top-level `array`: non-empty, unique, each in range.
  Status refs(const Json& o, const char* key, const std::string& path, const char* array) const;
  // Optional string (or required).
  Status string(const Json& o, const char* key, const std::string& path, bool required = false) const;
  // Optional boolean.
  Status boolean(const Json& o, const char* key, const std::string& path) const;
  // A textureInfo (index required, in range; texCoord >= 0), plus the extra numeric property of
  // normal (scale) and occlusion (strength) textures, when `extra` is set. `texCoords` learns the
  // texCoord it uses (KHR_texture_transform may override it).
  Status textureInfo(const Json& o, const char* key, const std::string& path, const char* extra = nullptr,
                     Range extraRange = kAny, std::vector<std::pair<std::string, int64_t>>* texCoords = nullptr) const;

  double numberOr(const Json& o, const char* key, double fallback) const;
  static std::string at(const std::string& path, const char* key) { return path.empty() ? key : path + "." + key; }
  static std::string at(const std::string& path, size_t i) { return path + "[" + std::to_string(i) + "]"; }

 private:
  const std::string& file_;
  const Json& root_;
};

// gltf_schema.cpp: asset, extensions, buffers, buffer views, accessors.
Status checkBuffersAndAccessors(const Checker& c);
// gltf_schema_nodes.cpp: meshes, nodes, scenes, skins, animations, cameras.
Status checkMeshes(const Checker& c);
Status checkNodesAndScenes(const Checker& c);
Status checkSkinsAndAnimations(const Checker& c);
Status checkCameras(const Checker& c);
// gltf_schema_materials.cpp: images, samplers, textures, materials, KHR_lights_punctual.
Status checkImagesAndTextures(const Checker& c);
Status checkMaterials(const Checker& c);
Status checkLights(const Checker& c);

// The accessor's component count for its type, 0 for an unknown type.
size_t componentCount(const std::string& type);
// Bytes per component, 0 for an unknown component type.
size_t componentBytes(int64_t componentType);

}  // namespace rayster::scene::gltf::schema

namespace rayster::scene::gltf {
// The whole schema, in document order; called by checkJsonTypes() (gltf_validate.cpp).
Status checkSchema(const std::string& file, const nlohmann::json& root);
// The checks on the data (gltf_schema_data.cpp), after tinygltf has read the buffers: accessor
// min/max against the values, sparse indices, animation key times, vertex indices.
Status checkAccessorData(const tinygltf::Model& model, const std::string& file);
}  // namespace rayster::scene::gltf
