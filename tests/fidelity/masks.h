#pragma once
// The per-effect masks of the fidelity tests and report, built from the hybrid frame's own G-buffer
// AOVs (raw EXR values): every covered pixel belongs to exactly one effect, the first that matches:
//   refractive  material transmission > 0
//   reflective  roughness <= 0.5 and (metallic > 0.5 or roughness <= kMirrorRoughness)
//   shadowed    shadow-denoised (light 0) < 0.5
//   rest        any other surface
// and "all" is every pixel, background (reversed-Z depth 0: no surface) included.
#include <map>
#include <string>
#include <vector>

#include "core/image.h"

namespace rayster::fidelity {

// A dielectric this smooth reflects sharply enough to count as a reflector.
inline constexpr float kMirrorRoughness = 0.1f;
inline const std::vector<std::string> kMaskNames = {"all", "shadowed", "reflective", "refractive", "rest"};

inline std::string effectOf(float depth, const float* material, float shadow) {
  const float roughness = material[0], metallic = material[1], transmission = material[2];
  if (depth <= 0.0f) return "";
  if (transmission > 0.5f / 255.0f) return "refractive";
  if (roughness <= 0.5f && (metallic > 0.5f || roughness <= kMirrorRoughness)) return "reflective";
  if (shadow < 0.5f) return "shadowed";
  return "rest";
}

// White (255) where the mask covers, black elsewhere: what `rayster compare --mask` reads.
inline std::map<std::string, Image8> buildMasks(const ImageF& depth, const ImageF& material, const ImageF& shadow) {
  std::map<std::string, Image8> masks;
  for (const auto& name : kMaskNames) masks[name] = Image8::make(depth.width, depth.height);
  for (int y = 0; y < depth.height; ++y)
    for (int x = 0; x < depth.width; ++x) {
      const std::string effect = effectOf(depth.pixel(x, y)[0], material.pixel(x, y), shadow.pixel(x, y)[0]);
      for (const std::string& name : {std::string("all"), effect}) {
        if (name.empty()) continue;
        uint8_t* p = masks[name].pixel(x, y);
        p[0] = p[1] = p[2] = p[3] = 255;
      }
    }
  return masks;
}

}  // namespace rayster::fidelity
