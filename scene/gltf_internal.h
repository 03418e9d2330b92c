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

// An EXT_meshopt_compression fallback buffer without data: its index and declared byteLength.
struct FallbackBuffer {
  int buffer = -1;
  uint64_t byteLength = 0;
};

// A primitive's indices accessor that tinygltf must not see (detachViewlessIndices).
struct DetachedIndices {
  size_t mesh = 0, primitive = 0;
  int accessor = -1;
};

// What the loader learns from the raw JSON before tinygltf reads any image.
struct VettedJson {
  // Per glTF image: the first material that shows it through a texture, -1 for none. Only images
  // a material shows are decoded and required (gltf_materials.cpp says why).
  std::vector<int> imageMaterial;
  // EXT_meshopt_compression fallback buffers given stand-in bytes, and the JSON that says so
  // (empty: parse the file's own JSON).
  std::vector<FallbackBuffer> fallbackBuffers;
  std::vector<DetachedIndices> detachedIndices;
  std::string rewrittenJson;
};

// Parses the JSON on its own first so that nothing tinygltf does can be steered by the file:
// bounded nesting (tinygltf converts extras recursively), URIs confined to the folder, data URIs
// with valid base64, image buffer views inside their buffers, and extensionsRequired supported.
Result<VettedJson> vetJson(const std::string& file, std::string_view json, bool binary);

// A second line of defence behind vetJson: tinygltf's file access, confined to baseDir. Paths
// outside it are refused and remembered in `violation`.
struct ConfinedFs {
  std::string baseDir;  // absolute, no trailing slash
  std::string violation;
};
tinygltf::FsCallbacks makeConfinedFsCallbacks(ConfinedFs* fs);

// tinygltf image loader: keeps the encoded bytes of the images a material shows (imageMaterial >=
// 0); the others are passed over undecoded. decodeImages() then decodes them to RGBA8 in parallel
// once tinygltf is done, refusing absurd dimensions before decoding.
struct ImageDecodeState {
  std::vector<int> imageMaterial;  // from VettedJson
  std::vector<bool> reached;       // per image: its bytes reached the loader (it is not missing)
  std::string error;               // the first failure (lowest image index), without the file name
  // Per image: why its KTX2 data could not be decoded ("" for none). Not a failure by itself: a
  // KHR_texture_basisu texture falls back to its `source` (convertMaterials decides).
  std::vector<std::string> ktxError;
  struct Encoded {
    size_t image = 0;
    std::vector<uint8_t> bytes;
  };
  std::vector<Encoded> pending;  // in image order, waiting for decodeImages()
};
bool decodeImage(tinygltf::Image* image, int imageIndex, std::string* err, std::string* warn, int reqWidth,
                 int reqHeight, const unsigned char* bytes, int size, void* user);
// Decodes state.pending into model.images (parallelFor), with progress for `file`. Sets
// state.error to the failure of the lowest-numbered image, as decoding them in order would have
// stopped at; false when there is one.
bool decodeImages(tinygltf::Model& model, const std::string& file, ImageDecodeState& state);

// ---- gltf_accessor.cpp: bounds-checked accessor reads ----

Result<std::vector<float>> readScalars(const tinygltf::Model& model, int accessor, const std::string& file);
Result<std::vector<glm::vec2>> readVec2(const tinygltf::Model& model, int accessor, const std::string& file);
Result<std::vector<glm::vec3>> readVec3(const tinygltf::Model& model, int accessor, const std::string& file);
Result<std::vector<glm::vec4>> readVec4(const tinygltf::Model& model, int accessor, const std::string& file);
Result<std::vector<glm::mat4>> readMat4(const tinygltf::Model& model, int accessor, const std::string& file);
Result<std::vector<uint32_t>> readIndices(const tinygltf::Model& model, int accessor, const std::string& file);

// ---- gltf_meshopt.cpp, gltf_draco.cpp: compressed geometry, decoded before validation ----

// Gives each fallback buffer without data a one-byte data URI (tinygltf refuses a buffer it cannot
// fill) and lists them; refuses uncompressed views into them. True when `root` changed.
Result<bool> stubFallbackBuffers(const std::string& file, nlohmann::json& root, bool binary,
                                 std::vector<FallbackBuffer>& fallbacks);
// tinygltf 2.7 refuses a primitive whose indices accessor has no buffer view, which is valid glTF
// and what every Draco primitive has: such indices are taken out of the JSON tinygltf parses and
// put back into the model afterwards (reattachIndices). True when `root` changed.
bool detachViewlessIndices(nlohmann::json& root, std::vector<DetachedIndices>& detached);
Status reattachIndices(tinygltf::Model& model, const std::string& file, const std::vector<DetachedIndices>& detached);
// The GLB `glb` (checked by glbJsonChunk) with its JSON chunk replaced by `json`.
std::vector<uint8_t> glbWithJson(const std::vector<uint8_t>& glb, std::string_view json);
// Decodes every EXT_meshopt_compression buffer view into its own buffer range.
Status decodeMeshopt(tinygltf::Model& model, const std::string& file, const std::vector<FallbackBuffer>& fallbacks);
// Decodes every KHR_draco_mesh_compression primitive into new accessors the primitive then uses.
Status decodeDraco(tinygltf::Model& model, const std::string& file);

// ---- gltf_instancing.cpp ----

// EXT_mesh_gpu_instancing of node `index`: one local transform per instance (its TRS relative to
// the node), or none when the node has no such extension.
Result<std::vector<SceneNode>> gpuInstances(const tinygltf::Model& model, const tinygltf::Node& node, size_t index,
                                            const std::string& file);

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

// Moves the decoded pixels out of model.images.
Status convertMaterials(tinygltf::Model& model, const std::string& file, const ImageDecodeState& images, Scene& scene);

// What converting a material needs: `textureMap` maps glTF texture indices to scene textures (-1
// where unusable).
struct MaterialContext {
  const tinygltf::Model& model;
  const std::string& file;
  const std::vector<int32_t>& textureMap;
};
// A textureInfo inside a material extension (tinygltf parses only the core ones): index, texCoord
// and its own KHR_texture_transform; none when `key` is absent.
TextureRef extensionTexture(const MaterialContext& ctx, const tinygltf::Value& ext, const char* key,
                            const std::string& material);
// The extension object `name` of an extension map, or null.
const tinygltf::Value* extension(const tinygltf::ExtensionMap& extensions, const char* name);
// A finite float from a number, else `fallback`.
float finiteOr(double value, float fallback);
// An array of N numbers from a tinygltf Value, `fallback` when absent or of another length (and
// per element where one is not a finite number).
template <int N>
glm::vec<N, float> valueVectorOr(const tinygltf::Value& object, const char* key, glm::vec<N, float> fallback) {
  if (!object.IsObject() || !object.Has(key)) return fallback;
  const tinygltf::Value& array = object.Get(key);
  if (!array.IsArray() || array.ArrayLen() != size_t(N)) return fallback;
  glm::vec<N, float> v;
  for (int i = 0; i < N; ++i) {
    const tinygltf::Value& e = array.Get(i);
    v[i] = e.IsNumber() ? finiteOr(e.GetNumberAsDouble(), fallback[i]) : fallback[i];
  }
  return v;
}

// ---- gltf_material_layers.cpp: the KHR_materials_* layers and KHR_materials_variants ----

// The texture slots of the material extensions Rayster reads, by extension: the images they show
// are decoded (gltf_document.cpp), the rest skipped.
struct ExtensionTextureSlot {
  const char* extension;
  const char* slot;
};
extern const std::vector<ExtensionTextureSlot> kExtensionTextureSlots;

// Transmission and thickness textures, clearcoat, sheen, iridescence, anisotropy and dispersion.
void readMaterialLayers(const MaterialContext& ctx, const tinygltf::Material& src, Material& m);
// KHR_materials_variants: the root's variant names into scene.variants.
Status readVariantNames(const tinygltf::Model& model, const std::string& file, Scene& scene);
// A primitive's KHR_materials_variants mappings into prim.variantMaterials (prim.material is set).
// `where` names the primitive's JSON path for messages.
Status readVariantMappings(const tinygltf::Primitive& src, const Scene& scene, size_t materialCount,
                           const std::string& file, const std::string& where, Primitive& prim);

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
