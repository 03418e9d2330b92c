// The glTF 2.0 schema for images, samplers, textures and materials (core and the KHR_materials_*
// extensions' ranges), and KHR_lights_punctual lights.
#include <numbers>

#include "scene/gltf_schema.h"

namespace rayster::scene::gltf::schema {
namespace {

Status checkImage(const Checker& c, size_t i) {
  const Json& im = c.element("images", i);
  const std::string p = fmt::format("images[{}]", i);
  RAYSTER_TRY(c.string(im, "uri", p));
  RAYSTER_TRY(c.string(im, "mimeType", p));  // an unknown type is only a warning
  RAYSTER_TRY(c.ref(im, "bufferView", p, "bufferViews"));
  const bool uri = im.contains("uri"), view = im.contains("bufferView");
  if (uri == view) return c.fail(p, "needs exactly one of uri and bufferView, has {}", uri ? "both" : "neither");
  if (view && !im.contains("mimeType")) return c.fail(Checker::at(p, "bufferView"), "is set but mimeType is not");
  if (view && Checker::find(c.element("bufferViews", im["bufferView"].get<size_t>()), "byteStride"))
    return c.fail(Checker::at(p, "bufferView"), "buffer view {} has a byteStride, which image data must not",
                  im["bufferView"].get<uint64_t>());
  return okStatus();
}

Status checkSampler(const Checker& c, size_t i) {
  const Json& s = c.element("samplers", i);
  const std::string p = fmt::format("samplers[{}]", i);
  // Values outside the enums are only a warning (the schema allows any integer); the material
  // conversion uses the defaults for them.
  for (const char* key : {"magFilter", "minFilter", "wrapS", "wrapT"}) RAYSTER_TRY(c.integer(s, key, p, kAny));
  return okStatus();
}

// KHR_materials_* number ranges, as their schemas give them.
struct ExtensionRange {
  const char* extension;
  const char* property;
  Range range;
  size_t length = 0;  // 0: a number; otherwise an array of that many numbers
};
constexpr double kInf = std::numeric_limits<double>::infinity();
const ExtensionRange kExtensionRanges[] = {
    {"KHR_materials_emissive_strength", "emissiveStrength", kNonNegative},
    {"KHR_materials_transmission", "transmissionFactor", kUnit},
    {"KHR_materials_volume", "thicknessFactor", kNonNegative},
    {"KHR_materials_volume", "attenuationDistance", kPositive},
    {"KHR_materials_volume", "attenuationColor", kUnit, 3},
    {"KHR_materials_specular", "specularFactor", kUnit},
    {"KHR_materials_specular", "specularColorFactor", kNonNegative, 3},
    {"KHR_materials_clearcoat", "clearcoatFactor", kUnit},
    {"KHR_materials_clearcoat", "clearcoatRoughnessFactor", kUnit},
    {"KHR_materials_sheen", "sheenColorFactor", kUnit, 3},
    {"KHR_materials_sheen", "sheenRoughnessFactor", kUnit},
    {"KHR_materials_iridescence", "iridescenceFactor", kUnit},
    {"KHR_materials_iridescence", "iridescenceIor", {1.0, kInf}},
    {"KHR_materials_iridescence", "iridescenceThicknessMinimum", kNonNegative},
    {"KHR_materials_iridescence", "iridescenceThicknessMaximum", kNonNegative},
    {"KHR_materials_anisotropy", "anisotropyStrength", kUnit},
    {"KHR_materials_anisotropy", "anisotropyRotation", kAny},
    {"KHR_materials_dispersion", "dispersion", kNonNegative},
};

Status checkMaterialExtensions(const Checker& c, const Json& m, const std::string& p) {
  const Json* ext = Checker::find(m, "extensions");
  if (!ext) return okStatus();
  const std::string ep = Checker::at(p, "extensions");
  for (const ExtensionRange& r : kExtensionRanges)
    if (const Json* e = Checker::find(*ext, r.extension)) {
      const std::string xp = Checker::at(ep, r.extension);
      if (r.length)
        RAYSTER_TRY(c.numbers(*e, r.property, xp, {r.length}, r.range));
      else
        RAYSTER_TRY(c.number(*e, r.property, xp, r.range));
    }
  // ior is 0 (a special value: the material is not a dielectric) or at least 1.
  if (const Json* ior = Checker::find(*ext, "KHR_materials_ior")) {
    const std::string ip = Checker::at(ep, "KHR_materials_ior");
    RAYSTER_TRY(c.number(*ior, "ior", ip, kNonNegative));
    const double v = c.numberOr(*ior, "ior", 1.5);
    if (v != 0.0 && v < 1.0) return c.fail(Checker::at(ip, "ior"), "{} is neither 0 nor at least 1", v);
  }
  // Every texture a KHR_materials_* extension names: its index exists, texCoord >= 0.
  for (auto it = ext->begin(); it != ext->end(); ++it) {
    if (!it.value().is_object() || it.key().rfind("KHR_materials_", 0) != 0) continue;
    const std::string xp = Checker::at(ep, it.key().c_str());
    for (auto t = it.value().begin(); t != it.value().end(); ++t) {
      const std::string& key = t.key();
      if (key.size() > 7 && key.compare(key.size() - 7, 7, "Texture") == 0)
        RAYSTER_TRY(c.textureInfo(it.value(), key.c_str(), xp, key == "clearcoatNormalTexture" ? "scale" : nullptr));
    }
  }
  return okStatus();
}

Status checkMaterial(const Checker& c, size_t i) {
  const Json& m = c.element("materials", i);
  const std::string p = fmt::format("materials[{}]", i);
  if (const Json* pbr = Checker::find(m, "pbrMetallicRoughness")) {
    const std::string pp = Checker::at(p, "pbrMetallicRoughness");
    RAYSTER_TRY(c.numbers(*pbr, "baseColorFactor", pp, {4}, kUnit));
    RAYSTER_TRY(c.number(*pbr, "metallicFactor", pp, kUnit));
    RAYSTER_TRY(c.number(*pbr, "roughnessFactor", pp, kUnit));
    RAYSTER_TRY(c.textureInfo(*pbr, "baseColorTexture", pp));
    RAYSTER_TRY(c.textureInfo(*pbr, "metallicRoughnessTexture", pp));
  }
  RAYSTER_TRY(c.textureInfo(m, "normalTexture", p, "scale", kAny));
  RAYSTER_TRY(c.textureInfo(m, "occlusionTexture", p, "strength", kUnit));
  RAYSTER_TRY(c.textureInfo(m, "emissiveTexture", p));
  RAYSTER_TRY(c.numbers(m, "emissiveFactor", p, {3}, kUnit));
  RAYSTER_TRY(c.string(m, "alphaMode", p));  // an unknown mode is only a warning: drawn opaque
  RAYSTER_TRY(c.number(m, "alphaCutoff", p, kNonNegative));
  RAYSTER_TRY(c.boolean(m, "doubleSided", p));
  return checkMaterialExtensions(c, m, p);
}

}  // namespace

Status checkImagesAndTextures(const Checker& c) {
  for (size_t i = 0; i < c.count("images"); ++i) RAYSTER_TRY(checkImage(c, i));
  for (size_t i = 0; i < c.count("samplers"); ++i) RAYSTER_TRY(checkSampler(c, i));
  for (size_t i = 0; i < c.count("textures"); ++i) {
    const Json& t = c.element("textures", i);
    const std::string p = fmt::format("textures[{}]", i);
    // No source is valid: an extension (KHR_texture_basisu, EXT_texture_webp) may supply the image.
    RAYSTER_TRY(c.ref(t, "source", p, "images"));
    RAYSTER_TRY(c.ref(t, "sampler", p, "samplers"));
  }
  return okStatus();
}

Status checkMaterials(const Checker& c) {
  for (size_t i = 0; i < c.count("materials"); ++i) RAYSTER_TRY(checkMaterial(c, i));
  return okStatus();
}

Status checkLights(const Checker& c) {
  const Json* ext = Checker::find(c.root(), "extensions");
  const Json* punctual = ext ? Checker::find(*ext, "KHR_lights_punctual") : nullptr;
  if (!punctual) return okStatus();
  const std::string root = "extensions.KHR_lights_punctual";
  const Json* lights = Checker::find(*punctual, "lights");
  if (!lights) return c.fail(root, "lights is required");
  if (!lights->is_array() || lights->empty()) return c.fail(Checker::at(root, "lights"), "is not a non-empty array");
  constexpr double kHalfPi = std::numbers::pi / 2.0;
  for (size_t i = 0; i < lights->size(); ++i) {
    const Json& l = (*lights)[i];
    const std::string p = Checker::at(Checker::at(root, "lights"), i);
    if (!l.is_object()) return c.fail(p, "is not an object");
    RAYSTER_TRY(c.string(l, "type", p, true));  // an unknown type is only a warning: not drawn
    RAYSTER_TRY(c.numbers(l, "color", p, {3}, kUnit));
    RAYSTER_TRY(c.number(l, "intensity", p, kNonNegative));
    RAYSTER_TRY(c.number(l, "range", p, kPositive));
    if (l["type"] == "spot" && !l.contains("spot")) return c.fail(p, "spot is required for type spot");
    if (const Json* spot = Checker::find(l, "spot")) {
      const std::string sp = Checker::at(p, "spot");
      if (!spot->is_object()) return c.fail(sp, "is not an object");
      RAYSTER_TRY(c.number(*spot, "innerConeAngle", sp, {0.0, kHalfPi, false, true}));
      RAYSTER_TRY(c.number(*spot, "outerConeAngle", sp, {0.0, kHalfPi, true, false}));
      const double inner = c.numberOr(*spot, "innerConeAngle", 0.0);
      const double outer = c.numberOr(*spot, "outerConeAngle", std::numbers::pi / 4.0);
      if (!(outer > inner))
        return c.fail(Checker::at(sp, "outerConeAngle"), "{} is not above innerConeAngle {}", outer, inner);
    }
  }
  return okStatus();
}

}  // namespace rayster::scene::gltf::schema
