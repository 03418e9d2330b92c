#pragma once
// Shared by the glTF loader's files (gltf_*.cpp); not part of the scene API. Include only from
// those files: it pulls in tiny_gltf.h.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <tiny_gltf.h>
#include <nlohmann/json_fwd.hpp>

#include "core/error.h"
#include "scene/scene.h"

namespace rayster::scene::gltf {

// Every glTF failure is BadInput with the file name first: "box.gltf: <cause>".
template <class... A>
Error bad(const std::string& file, fmt::format_string<A...> f, A&&... args) {
  return Error{ExitCode::BadInput, fmt::format("{}: {}", file, fmt::format(f, std::forward<A>(args)...))};
}

// Error text from tinygltf or nlohmann can span lines; our messages must not.
std::string oneLine(std::string_view text);

// ---- gltf_document.cpp: vetting the raw file before tinygltf parses it ----

// Checks the GLB container (header, chunk lengths and alignment) more strictly than tinygltf 2.7
// does (it lets the BIN chunk run 8 bytes past the end) and returns the JSON chunk.
Result<std::string_view> glbJsonChunk(const std::string& file, const std::vector<uint8_t>& bytes);

// What the loader learns from the raw JSON before tinygltf reads any image.
struct VettedJson {
  // Per glTF image: the first material that shows it through a texture, -1 for none. Only images
  // a material shows are decoded and required (gltf_materials.cpp says why).
  std::vector<int> imageMaterial;
};

// Parses the JSON on its own first so that nothing tinygltf does can be steered by the file:
// bounded nesting (tinygltf converts extras recursively), URIs confined to the folder, data URIs
// with valid base64, image buffer views inside their buffers, and extensionsRequired supported.
Result<VettedJson> vetJson(const std::string& file, std::string_view json);

// A second line of defence behind vetJson: tinygltf's file access, confined to baseDir. Paths
// outside it are refused and remembered in `violation`.
struct ConfinedFs {
  std::string baseDir;  // absolute, no trailing slash
  std::string violation;
};
tinygltf::FsCallbacks makeConfinedFsCallbacks(ConfinedFs* fs);

// tinygltf image loader: decodes to RGBA8 the images a material shows (imageMaterial >= 0),
// refusing absurd dimensions before decoding; the others are passed over undecoded.
struct ImageDecodeState {
  std::vector<int> imageMaterial;  // from VettedJson
  std::vector<bool> reached;       // per image: its bytes reached the loader (it is not missing)
  std::string error;               // the first failure, without the file name
};
bool decodeImage(tinygltf::Image* image, int imageIndex, std::string* err, std::string* warn, int reqWidth,
                 int reqHeight, const unsigned char* bytes, int size, void* user);

// ---- gltf_accessor.cpp: bounds-checked accessor reads ----

Result<std::vector<float>> readScalars(const tinygltf::Model& model, int accessor, const std::string& file);
Result<std::vector<glm::vec2>> readVec2(const tinygltf::Model& model, int accessor, const std::string& file);
Result<std::vector<glm::vec3>> readVec3(const tinygltf::Model& model, int accessor, const std::string& file);
Result<std::vector<glm::vec4>> readVec4(const tinygltf::Model& model, int accessor, const std::string& file);
Result<std::vector<glm::mat4>> readMat4(const tinygltf::Model& model, int accessor, const std::string& file);
Result<std::vector<uint32_t>> readIndices(const tinygltf::Model& model, int accessor, const std::string& file);

// ---- gltf_meshes.cpp ----

struct MeshBuilder {
  const tinygltf::Model& model;
  const std::string& file;
  Scene& scene;
  std::optional<uint32_t> defaultMaterial;  // appended on first use
};
Result<Mesh> convertMesh(MeshBuilder& builder, int meshIndex);

// ---- gltf_validate.cpp: what the specification forbids and tinygltf accepts ----
// The JSON types of the core properties (on the raw JSON: tinygltf takes a wrong type for absent),
// then the model's ranges and references.
Status checkJsonTypes(const std::string& file, const nlohmann::json& root);
// Why buffer 0 of a GLB does not get its bytes from the BIN chunk (`binLength`, -1 for none), for a
// file tinygltf refused; okStatus() when that is not the reason.
Status explainGlbBuffer(const std::string& file, std::string_view json, int64_t binLength);
Status validateModel(const tinygltf::Model& model, const std::string& file);

// ---- gltf_materials.cpp: images, samplers, textures and materials, in glTF order ----

Status convertMaterials(const tinygltf::Model& model, const std::string& file, const ImageDecodeState& images,
                        Scene& scene);

// ---- gltf_skins.cpp ----

// Reads the skins the displayed scene's instances use into scene.skins (glTF skin i becomes
// scene skin i; Instance::skin holds the glTF index until then). A skin whose joints are not all in
// the displayed scene cannot be posed: its instances are drawn in the bind pose, with a warning.
Status convertSkins(const tinygltf::Model& model, const std::string& file, const std::vector<int>& sceneNodeOf,
                    Scene& scene);

// ---- gltf_animations.cpp ----

// Reads model.animations into scene.animations. `sceneNodeOf` maps glTF node indices to
// Scene::nodes (-1: not in the displayed scene; channels on those are dropped). Afterwards only
// instances under an animated node keep their Instance::node.
Status convertAnimations(const tinygltf::Model& model, const std::string& file, const std::vector<int>& sceneNodeOf,
                         Scene& scene);

// A number from a tinygltf Value (extras, extensions), or `fallback` when absent or not a number.
double numberOr(const tinygltf::Value& object, const char* key, double fallback);

}  // namespace rayster::scene::gltf
