// glTF images, samplers, textures and materials -> scene::ImageData, Sampler, Texture, Material.
#include <cfloat>
#include <cmath>
#include <exception>

#include <stb/stb_image.h>  // declarations only: the implementation lives in core/image_io.cpp

#include "core/image_io.h"
#include "core/ktx2.h"
#include "core/load_progress.h"
#include "core/log.h"
#include "core/parallel.h"
#include "scene/gltf_internal.h"

namespace rayster::scene::gltf {
namespace {

// Textures beyond these are refused before decoding: larger ones are either hostile headers that
// would make stb_image allocate gigabytes, or more than any GPU texture limit allows.
constexpr int kMaxImageSide = 16384;
constexpr uint64_t kMaxImagePixels = uint64_t(1) << 28;

template <int N>
glm::vec<N, float> vectorOr(const std::vector<double>& values, glm::vec<N, float> fallback) {
  if (values.size() != size_t(N)) return fallback;
  glm::vec<N, float> v;
  for (int i = 0; i < N; ++i) v[i] = finiteOr(values[size_t(i)], fallback[i]);
  return v;
}

Sampler convertSampler(const tinygltf::Sampler& src) {
  auto wrap = [](int mode) {
    switch (mode) {
      case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
        return Wrap::ClampToEdge;
      case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
        return Wrap::MirroredRepeat;
      default:
        return Wrap::Repeat;
    }
  };
  Sampler s;
  s.wrapS = wrap(src.wrapS);
  s.wrapT = wrap(src.wrapT);
  s.magFilter = src.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ? Filter::Nearest : Filter::Linear;
  const int min = src.minFilter;
  s.minFilter = (min == TINYGLTF_TEXTURE_FILTER_NEAREST || min == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
                 min == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR)
                    ? Filter::Nearest
                    : Filter::Linear;
  // An unset minFilter leaves the choice to us, and mipmaps are what a renderer wants by default.
  s.mipmaps = min == -1 || (min != TINYGLTF_TEXTURE_FILTER_NEAREST && min != TINYGLTF_TEXTURE_FILTER_LINEAR);
  return s;
}

TextureRef textureRef(const MaterialContext& ctx, int index, int texCoord, const tinygltf::ExtensionMap& extensions,
                      const std::string& material) {
  TextureRef ref;
  if (index < 0) return ref;
  if (size_t(index) >= ctx.textureMap.size()) {
    log::warn("{}: material '{}' uses texture {}, which does not exist; ignored", ctx.file, material, index);
    return ref;
  }
  ref.texture = ctx.textureMap[size_t(index)];
  int uvSet = texCoord;
  if (const tinygltf::Value* t = extension(extensions, "KHR_texture_transform")) {
    ref.offset = valueVectorOr<2>(*t, "offset", glm::vec2(0.0f));
    ref.scale = valueVectorOr<2>(*t, "scale", glm::vec2(1.0f));
    ref.rotation = finiteOr(numberOr(*t, "rotation", 0.0), 0.0f);
    if (t->Has("texCoord")) uvSet = int(numberOr(*t, "texCoord", texCoord));  // the extension overrides
  }
  if (uvSet < 0 || uvSet > 1) {
    log::warn("{}: material '{}' uses UV set {}; Rayster reads sets 0 and 1, using 0", ctx.file, material, uvSet);
    uvSet = 0;
  }
  ref.texCoord = uint32_t(uvSet);
  return ref;
}

Material convertMaterial(const MaterialContext& ctx, const tinygltf::Material& src, size_t index) {
  Material m;
  m.name = src.name.empty() ? fmt::format("material{}", index) : src.name;
  const tinygltf::PbrMetallicRoughness& pbr = src.pbrMetallicRoughness;
  m.baseColor = vectorOr<4>(pbr.baseColorFactor, glm::vec4(1.0f));
  m.metallic = glm::clamp(finiteOr(pbr.metallicFactor, 1.0f), 0.0f, 1.0f);
  m.roughness = glm::clamp(finiteOr(pbr.roughnessFactor, 1.0f), 0.0f, 1.0f);
  m.baseColorTexture = textureRef(ctx, pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                  pbr.baseColorTexture.extensions, m.name);
  m.metallicRoughnessTexture =
      textureRef(ctx, pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                 pbr.metallicRoughnessTexture.extensions, m.name);
  m.normalTexture =
      textureRef(ctx, src.normalTexture.index, src.normalTexture.texCoord, src.normalTexture.extensions, m.name);
  m.normalScale = finiteOr(src.normalTexture.scale, 1.0f);
  m.occlusionTexture = textureRef(ctx, src.occlusionTexture.index, src.occlusionTexture.texCoord,
                                  src.occlusionTexture.extensions, m.name);
  m.occlusionStrength = glm::clamp(finiteOr(src.occlusionTexture.strength, 1.0f), 0.0f, 1.0f);
  m.emissiveTexture =
      textureRef(ctx, src.emissiveTexture.index, src.emissiveTexture.texCoord, src.emissiveTexture.extensions, m.name);
  m.emissive = vectorOr<3>(src.emissiveFactor, glm::vec3(0.0f));
  if (const tinygltf::Value* e = extension(src.extensions, "KHR_materials_emissive_strength"))
    m.emissive *= finiteOr(numberOr(*e, "emissiveStrength", 1.0), 1.0f);
  m.doubleSided = src.doubleSided;
  if (src.alphaMode == "MASK")
    m.alphaMode = AlphaMode::Mask;
  else if (src.alphaMode == "BLEND")
    m.alphaMode = AlphaMode::Blend;
  m.alphaCutoff = finiteOr(src.alphaCutoff, 0.5f);

  if (const tinygltf::Value* e = extension(src.extensions, "KHR_materials_transmission"))
    m.transmission = glm::clamp(finiteOr(numberOr(*e, "transmissionFactor", 0.0), 0.0f), 0.0f, 1.0f);
  if (const tinygltf::Value* e = extension(src.extensions, "KHR_materials_ior"))
    m.ior = finiteOr(numberOr(*e, "ior", 1.5), 1.5f);
  if (const tinygltf::Value* e = extension(src.extensions, "KHR_materials_volume")) {
    m.thickness = std::max(finiteOr(numberOr(*e, "thicknessFactor", 0.0), 0.0f), 0.0f);
    m.attenuationColor = valueVectorOr<3>(*e, "attenuationColor", glm::vec3(1.0f));
    // Absent means infinite, i.e. no absorption; +inf from a huge number means the same.
    const double distance = numberOr(*e, "attenuationDistance", DBL_MAX);
    m.attenuationDistance = distance > 0.0 && distance < FLT_MAX ? float(distance) : FLT_MAX;
  }
  if (const tinygltf::Value* e = extension(src.extensions, "KHR_materials_specular")) {
    // The schema's ranges: specularFactor in [0, 1], specularColorFactor >= 0 (unbounded above:
    // F0(η) × colour is clamped to 1 where it is used).
    m.specular = glm::clamp(finiteOr(numberOr(*e, "specularFactor", 1.0), 1.0f), 0.0f, 1.0f);
    m.specularColor = glm::max(valueVectorOr<3>(*e, "specularColorFactor", glm::vec3(1.0f)), glm::vec3(0.0f));
    m.specularTexture = extensionTexture(ctx, *e, "specularTexture", m.name);
    m.specularColorTexture = extensionTexture(ctx, *e, "specularColorTexture", m.name);
  }
  // Unlit ignores every other property but the base colour (and alpha): the renderer reads only
  // those when the flag is set.
  m.unlit = extension(src.extensions, "KHR_materials_unlit") != nullptr;
  readMaterialLayers(ctx, src, m);
  return m;
}

// An image a material shows. Missing, it refuses the file: glTF viewers differ (some draw the
// material untextured), but Rayster's images are compared against references and goldens, where a
// render without its base colour or normal map is a wrong result that looks like a right one. The
// one-line cause names the image and the material, so the fix (supply it, or drop it from the
// material) is quick.
Result<ImageData> convertImage(tinygltf::Image& src, size_t index, const std::string& file,
                               const std::string& material) {
  ImageData img;
  img.name = !src.name.empty() ? src.name : !src.uri.empty() ? src.uri : fmt::format("image{}", index);
  if (src.image.empty()) {
    // tinygltf only warns when an external image is missing.
    if (!src.uri.empty())
      return bad(file, "image {} '{}' is missing or unreadable; material '{}' uses it", index, src.uri, material);
    return bad(file, "image {} has no data; material '{}' uses it", index, material);
  }
  // decodeImage produced RGBA8, but a file could still arrive here through another path: check.
  if (src.width <= 0 || src.height <= 0 || src.component != 4 || src.bits != 8 ||
      src.image.size() != size_t(src.width) * size_t(src.height) * 4)
    return bad(file, "image {} '{}' has inconsistent pixel data", index, img.name);
  img.width = src.width;
  img.height = src.height;
  img.rgba = std::move(src.image);  // the model's copy is not read again (hundreds of MB in big files)
  return img;
}

}  // namespace

float finiteOr(double value, float fallback) {
  const float f = float(value);
  return std::isfinite(f) ? f : fallback;
}

const tinygltf::Value* extension(const tinygltf::ExtensionMap& extensions, const char* name) {
  auto it = extensions.find(name);
  return it != extensions.end() && it->second.IsObject() ? &it->second : nullptr;
}

TextureRef extensionTexture(const MaterialContext& ctx, const tinygltf::Value& ext, const char* key,
                            const std::string& material) {
  if (!ext.Has(key) || !ext.Get(key).IsObject()) return {};
  const tinygltf::Value& info = ext.Get(key);
  tinygltf::ExtensionMap extensions;
  if (info.Has("extensions") && info.Get("extensions").IsObject()) {
    const tinygltf::Value& e = info.Get("extensions");
    for (const std::string& name : e.Keys()) extensions[name] = e.Get(name);
  }
  // Numbers from the file, kept in int range before the conversion (textureRef checks the rest).
  auto integer = [&](const char* name, double fallback) {
    const double v = numberOr(info, name, fallback);
    return v >= -1.0 && v < 1e9 ? int(v) : int(1e9);
  };
  return textureRef(ctx, integer("index", -1), integer("texCoord", 0), extensions, material);
}

double numberOr(const tinygltf::Value& object, const char* key, double fallback) {
  if (!object.IsObject() || !object.Has(key)) return fallback;
  const tinygltf::Value& v = object.Get(key);
  return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

bool decodeImage(tinygltf::Image*, int imageIndex, std::string*, std::string*, int, int, const unsigned char* bytes,
                 int size, void* user) {
  auto* state = static_cast<ImageDecodeState*>(user);
  const size_t index = size_t(imageIndex);
  if (index < state->reached.size()) state->reached[index] = true;
  // Images no material shows are not decoded: nothing needs them, so a broken one costs nothing.
  if (index >= state->imageMaterial.size() || state->imageMaterial[index] < 0) return true;
  // The bytes are tinygltf's (a buffer, or a file it frees on return): kept for decodeImages().
  std::vector<uint8_t> copy;
  if (bytes && size > 0) copy.assign(bytes, bytes + size);
  state->pending.push_back({index, std::move(copy)});
  return true;
}

namespace {

// One image to RGBA8; an error message (without the file name) when it cannot be; `ktxError` gets
// a KTX2 failure, which is not an error by itself.
std::string decodeOne(tinygltf::Image& image, size_t index, const std::vector<uint8_t>& encoded,
                      std::string& ktxError) {
  const uint8_t* bytes = encoded.data();
  const int size = int(encoded.size());
  auto fill = [&](int width, int height, const uint8_t* rgba) {
    image.width = width;
    image.height = height;
    image.component = 4;
    image.bits = 8;
    image.pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image.image.assign(rgba, rgba + size_t(width) * size_t(height) * 4);
  };
  if (size > 0 && isKtx2({bytes, size_t(size)})) {
    Result<Image8> ktx = decodeKtx2({bytes, size_t(size)}, kMaxImageSide);
    if (!ktx) {
      ktxError = ktx.error().message;
      return {};  // left empty: convertMaterials uses a fallback image or says why it cannot
    }
    fill(ktx->width, ktx->height, ktx->rgba.data());
    return {};
  }
  // stb_image's failure reason is thread-local (STBI_THREAD_LOCAL), so workers do not mix them up.
  // The hazard check comes first: stb's header parse (stbi_info) already reads the Huffman tables.
  if (const std::string hazard = stbDecodeHazard(bytes, size_t(std::max(size, 0))); !hazard.empty())
    return fmt::format("image {} cannot be decoded ({})", index, hazard);
  int width = 0, height = 0, channels = 0;
  if (size <= 0 || !stbi_info_from_memory(bytes, size, &width, &height, &channels))
    return fmt::format("image {} cannot be decoded ({})", index,
                       stbi_failure_reason() ? stbi_failure_reason() : "not PNG or JPEG");
  if (width <= 0 || height <= 0 || width > kMaxImageSide || height > kMaxImageSide ||
      uint64_t(width) * uint64_t(height) > kMaxImagePixels)
    return fmt::format("image {} is {}x{}, larger than Rayster accepts ({} per side)", index, width, height,
                       kMaxImageSide);
  stbi_uc* pixels = stbi_load_from_memory(bytes, size, &width, &height, &channels, 4);
  if (!pixels)
    return fmt::format("image {} cannot be decoded ({})", index,
                       stbi_failure_reason() ? stbi_failure_reason() : "unknown error");
  fill(width, height, pixels);
  stbi_image_free(pixels);
  return {};
}

}  // namespace

bool decodeImages(tinygltf::Model& model, const std::string& file, ImageDecodeState& state) {
  std::vector<ImageDecodeState::Encoded> pending = std::move(state.pending);
  state.pending.clear();
  if (pending.empty()) return state.error.empty();
  std::vector<std::string> errors(pending.size()), ktxErrors(pending.size());
  LoadProgress progress("loading " + file, "textures decoded", pending.size());
  parallelFor(pending.size(), [&](size_t k) {
    const size_t index = pending[k].image;
    // tinygltf stops at a failing image, so an image past it may not be in the model (yet).
    // An exception must not leave a worker thread (std::terminate); it reads as it did when it
    // came out of tinygltf's callback (parse() catches those).
    try {
      if (index < model.images.size())
        errors[k] = decodeOne(model.images[index], index, pending[k].bytes, ktxErrors[k]);
    } catch (const std::exception& e) {
      errors[k] = "invalid glTF: " + oneLine(e.what());
    }
    std::vector<uint8_t>().swap(pending[k].bytes);  // the encoded copy is done with
    progress.advance();
  });
  progress.finish();
  state.ktxError.resize(std::max(state.ktxError.size(), state.imageMaterial.size()));
  for (size_t k = 0; k < pending.size(); ++k) {
    if (!ktxErrors[k].empty() && pending[k].image < state.ktxError.size())
      state.ktxError[pending[k].image] = ktxErrors[k];
    if (!errors[k].empty() && state.error.empty()) state.error = errors[k];  // pending is in image order
  }
  return state.error.empty();
}

// The images materials show, into scene.images; imageMap[glTF image] is the scene image, or -1
// for one no material shows (skipped, with a warning when it is missing: it may be a mistake).
Result<std::vector<int32_t>> convertImages(tinygltf::Model& model, const std::string& file,
                                           const ImageDecodeState& images, Scene& scene) {
  std::vector<int32_t> imageMap(model.images.size(), -1);
  for (size_t i = 0; i < model.images.size(); ++i) {
    tinygltf::Image& src = model.images[i];
    const int material = i < images.imageMaterial.size() ? images.imageMaterial[i] : -1;
    if (material < 0) {
      if (i < images.reached.size() && !images.reached[i])
        log::warn("{}: image {} '{}' is missing or unreadable; no material uses it, so it is skipped", file, i,
                  src.uri.empty() ? src.name : src.uri);
      continue;
    }
    // A KTX2 image that did not decode: the textures that show it decide (a fallback, or the cause).
    if (i < images.ktxError.size() && !images.ktxError[i].empty()) continue;
    // The index came from the raw JSON (vetJson); tinygltf's array is the same one, checked anyway.
    const bool named = size_t(material) < model.materials.size() && !model.materials[size_t(material)].name.empty();
    const std::string name = named ? model.materials[size_t(material)].name : fmt::format("material{}", material);
    Result<ImageData> img = convertImage(src, i, file, name);
    if (!img) return img.error();
    imageMap[i] = int32_t(scene.images.size());
    scene.images.push_back(std::move(*img));
  }
  return imageMap;
}

constexpr int kNoImage = -1, kNotShown = -2;

// The scene image texture `index` shows: its KHR_texture_basisu (KTX2) image where that decoded,
// else its `source`, the fallback the extension asks for (with a warning when the KTX2 one was
// refused). kNoImage: it names no image; kNotShown: no material shows it.
Result<int> textureSource(const tinygltf::Model& model, size_t index, const ImageDecodeState& images,
                          const std::vector<int32_t>& imageMap, const std::string& file) {
  const tinygltf::Texture& src = model.textures[index];
  int basisu = -1;
  if (auto it = src.extensions.find("KHR_texture_basisu"); it != src.extensions.end()) {
    const double v = numberOr(it->second, "source", -1.0);
    if (v < 0.0 || v >= double(model.images.size()) || v != double(int(v)))
      return bad(file, "textures[{}].extensions.KHR_texture_basisu.source does not name an image", index);
    basisu = int(v);
  }
  const bool hasSource = src.source >= 0 && size_t(src.source) < imageMap.size();
  if (basisu < 0 && !hasSource) return kNoImage;
  auto ktxError = [&](int image) -> std::string {
    return size_t(image) < images.ktxError.size() ? images.ktxError[size_t(image)] : std::string();
  };
  if (basisu >= 0 && imageMap[size_t(basisu)] >= 0) return int(imageMap[size_t(basisu)]);
  if (hasSource && imageMap[size_t(src.source)] >= 0) {
    if (basisu >= 0 && !ktxError(basisu).empty())
      log::warn("{}: textures[{}] KHR_texture_basisu image {}: {}; using its fallback image {}", file, index, basisu,
                ktxError(basisu), src.source);
    return int(imageMap[size_t(src.source)]);
  }
  for (int image : {basisu, hasSource ? src.source : -1})
    if (image >= 0 && !ktxError(image).empty())
      return bad(file, "textures[{}]{} image {}: {}", index, image == basisu ? " KHR_texture_basisu" : "", image,
                 ktxError(image));
  return kNotShown;
}

Status convertMaterials(tinygltf::Model& model, const std::string& file, const ImageDecodeState& images, Scene& scene) {
  Result<std::vector<int32_t>> imageMap = convertImages(model, file, images, scene);
  if (!imageMap) return imageMap.error();
  for (const tinygltf::Sampler& s : model.samplers) scene.samplers.push_back(convertSampler(s));

  std::optional<uint32_t> defaultSampler;
  std::vector<int32_t> textureMap(model.textures.size(), -1);
  for (size_t i = 0; i < model.textures.size(); ++i) {
    const tinygltf::Texture& src = model.textures[i];
    Result<int> source = textureSource(model, i, images, *imageMap, file);
    if (!source) return source.error();
    // A texture whose only source is an extension Rayster does not read (WebP) has no image.
    if (*source == kNoImage) {
      log::warn("{}: texture {} has no PNG, JPEG or KTX2 image; ignored", file, i);
      continue;
    }
    if (*source == kNotShown) continue;  // no material shows it, so nothing uses this texture
    Texture t;
    t.image = uint32_t(*source);
    if (src.sampler >= 0 && size_t(src.sampler) < model.samplers.size()) {
      t.sampler = uint32_t(src.sampler);
    } else {
      if (!defaultSampler) {
        defaultSampler = uint32_t(scene.samplers.size());
        scene.samplers.push_back(Sampler{});
      }
      t.sampler = *defaultSampler;
    }
    textureMap[i] = int32_t(scene.textures.size());
    scene.textures.push_back(t);
  }

  const MaterialContext ctx{model, file, textureMap};
  for (size_t i = 0; i < model.materials.size(); ++i)
    scene.materials.push_back(convertMaterial(ctx, model.materials[i], i));
  return okStatus();
}

}  // namespace rayster::scene::gltf
