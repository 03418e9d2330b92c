// The layers glTF puts on top of metallic-roughness (KHR_materials_clearcoat, _sheen,
// _iridescence, _anisotropy, _dispersion), the transmission and thickness textures, and
// KHR_materials_variants. Values outside the schema's ranges were refused by the validation
// (gltf_validate.cpp); the clamps here only keep numbers a shader relies on inside them.
#include <algorithm>
#include <cmath>

#include "core/log.h"
#include "scene/gltf_internal.h"

namespace rayster::scene::gltf {
namespace {

float number01(const tinygltf::Value& ext, const char* key, float fallback) {
  return std::clamp(finiteOr(numberOr(ext, key, fallback), fallback), 0.0f, 1.0f);
}

glm::vec3 color(const tinygltf::Value& ext, const char* key, glm::vec3 fallback) {
  return glm::clamp(valueVectorOr<3>(ext, key, fallback), glm::vec3(0.0f), glm::vec3(1.0f));
}

}  // namespace

const std::vector<ExtensionTextureSlot> kExtensionTextureSlots = {
    {"KHR_materials_specular", "specularTexture"},
    {"KHR_materials_specular", "specularColorTexture"},
    {"KHR_materials_transmission", "transmissionTexture"},
    {"KHR_materials_volume", "thicknessTexture"},
    {"KHR_materials_clearcoat", "clearcoatTexture"},
    {"KHR_materials_clearcoat", "clearcoatRoughnessTexture"},
    {"KHR_materials_clearcoat", "clearcoatNormalTexture"},
    {"KHR_materials_sheen", "sheenColorTexture"},
    {"KHR_materials_sheen", "sheenRoughnessTexture"},
    {"KHR_materials_iridescence", "iridescenceTexture"},
    {"KHR_materials_iridescence", "iridescenceThicknessTexture"},
    {"KHR_materials_anisotropy", "anisotropyTexture"},
};

void readMaterialLayers(const MaterialContext& ctx, const tinygltf::Material& src, Material& m) {
  if (const tinygltf::Value* e = extension(src.extensions, "KHR_materials_transmission"))
    m.transmissionTexture = extensionTexture(ctx, *e, "transmissionTexture", m.name);
  if (const tinygltf::Value* e = extension(src.extensions, "KHR_materials_volume"))
    m.thicknessTexture = extensionTexture(ctx, *e, "thicknessTexture", m.name);

  if (const tinygltf::Value* e = extension(src.extensions, "KHR_materials_clearcoat")) {
    m.clearcoat = number01(*e, "clearcoatFactor", 0.0f);
    m.clearcoatRoughness = number01(*e, "clearcoatRoughnessFactor", 0.0f);
    m.clearcoatTexture = extensionTexture(ctx, *e, "clearcoatTexture", m.name);
    m.clearcoatRoughnessTexture = extensionTexture(ctx, *e, "clearcoatRoughnessTexture", m.name);
    m.clearcoatNormalTexture = extensionTexture(ctx, *e, "clearcoatNormalTexture", m.name);
    if (e->Has("clearcoatNormalTexture"))
      m.clearcoatNormalScale = finiteOr(numberOr(e->Get("clearcoatNormalTexture"), "scale", 1.0), 1.0f);
  }
  if (const tinygltf::Value* e = extension(src.extensions, "KHR_materials_sheen")) {
    m.sheenColor = color(*e, "sheenColorFactor", glm::vec3(0.0f));
    m.sheenRoughness = number01(*e, "sheenRoughnessFactor", 0.0f);
    m.sheenColorTexture = extensionTexture(ctx, *e, "sheenColorTexture", m.name);
    m.sheenRoughnessTexture = extensionTexture(ctx, *e, "sheenRoughnessTexture", m.name);
  }
  if (const tinygltf::Value* e = extension(src.extensions, "KHR_materials_iridescence")) {
    m.iridescence = number01(*e, "iridescenceFactor", 0.0f);
    m.iridescenceIor = std::max(finiteOr(numberOr(*e, "iridescenceIor", 1.3), 1.3f), 1.0f);
    m.iridescenceThicknessMin = std::max(finiteOr(numberOr(*e, "iridescenceThicknessMinimum", 100.0), 100.0f), 0.0f);
    m.iridescenceThicknessMax = std::max(finiteOr(numberOr(*e, "iridescenceThicknessMaximum", 400.0), 400.0f), 0.0f);
    m.iridescenceTexture = extensionTexture(ctx, *e, "iridescenceTexture", m.name);
    m.iridescenceThicknessTexture = extensionTexture(ctx, *e, "iridescenceThicknessTexture", m.name);
  }
  if (const tinygltf::Value* e = extension(src.extensions, "KHR_materials_anisotropy")) {
    m.anisotropyStrength = number01(*e, "anisotropyStrength", 0.0f);
    m.anisotropyRotation = finiteOr(numberOr(*e, "anisotropyRotation", 0.0), 0.0f);
    m.anisotropyTexture = extensionTexture(ctx, *e, "anisotropyTexture", m.name);
  }
  if (const tinygltf::Value* e = extension(src.extensions, "KHR_materials_dispersion"))
    m.dispersion = std::max(finiteOr(numberOr(*e, "dispersion", 0.0), 0.0f), 0.0f);
}

Status readVariantNames(const tinygltf::Model& model, const std::string& file, Scene& scene) {
  const tinygltf::Value* e = extension(model.extensions, "KHR_materials_variants");
  if (!e) return okStatus();
  if (!e->Has("variants") || !e->Get("variants").IsArray() || e->Get("variants").ArrayLen() == 0)
    return bad(file, "extensions.KHR_materials_variants.variants: need an array of at least one variant");
  const tinygltf::Value& variants = e->Get("variants");
  for (size_t i = 0; i < variants.ArrayLen(); ++i) {
    const tinygltf::Value& v = variants.Get(int(i));
    if (!v.IsObject() || !v.Has("name") || !v.Get("name").IsString())
      return bad(file, "extensions.KHR_materials_variants.variants[{}].name: need a string", i);
    scene.variants.push_back(v.Get("name").Get<std::string>());
  }
  return okStatus();
}

Status readVariantMappings(const tinygltf::Primitive& src, const Scene& scene, size_t materialCount,
                           const std::string& file, const std::string& where, Primitive& prim) {
  prim.defaultMaterial = prim.material;
  const tinygltf::Value* e = extension(src.extensions, "KHR_materials_variants");
  if (!e) return okStatus();
  const std::string path = where + ".extensions.KHR_materials_variants.mappings";
  if (!e->Has("mappings") || !e->Get("mappings").IsArray() || e->Get("mappings").ArrayLen() == 0)
    return bad(file, "{}: need an array of at least one mapping", path);
  if (scene.variants.empty())
    return bad(file, "{}: the file declares no variants (extensions.KHR_materials_variants)", path);
  const tinygltf::Value& mappings = e->Get("mappings");
  for (size_t i = 0; i < mappings.ArrayLen(); ++i) {
    const tinygltf::Value& mapping = mappings.Get(int(i));
    const double material = numberOr(mapping, "material", -1.0);
    if (!(material >= 0.0 && material < double(materialCount)) || material != std::floor(material))
      return bad(file, "{}[{}].material: need a material index below {}", path, i, materialCount);
    if (!mapping.Has("variants") || !mapping.Get("variants").IsArray() || mapping.Get("variants").ArrayLen() == 0)
      return bad(file, "{}[{}].variants: need an array of at least one variant index", path, i);
    const tinygltf::Value& list = mapping.Get("variants");
    for (size_t k = 0; k < list.ArrayLen(); ++k) {
      const double v = list.Get(int(k)).IsNumber() ? list.Get(int(k)).GetNumberAsDouble() : -1.0;
      if (!(v >= 0.0 && v < double(scene.variants.size())) || v != std::floor(v))
        return bad(file, "{}[{}].variants[{}]: need a variant index below {}", path, i, k, scene.variants.size());
      for (const auto& [seen, unused] : prim.variantMaterials)
        if (seen == uint32_t(v))
          return bad(file, "{}[{}].variants[{}]: variant {} is mapped twice in this primitive", path, i, k, seen);
      prim.variantMaterials.emplace_back(uint32_t(v), uint32_t(material));
    }
  }
  return okStatus();
}

}  // namespace rayster::scene::gltf
