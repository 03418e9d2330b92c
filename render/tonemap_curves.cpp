#include "render/tonemap_curves.h"

#include <algorithm>

namespace rayster::render {

const char* tonemapperName(Tonemapper t) { return t == Tonemapper::Neutral ? "neutral" : "aces"; }

std::optional<Tonemapper> parseTonemapper(std::string_view name) {
  if (name == "aces") return Tonemapper::Aces;
  if (name == "neutral") return Tonemapper::Neutral;
  return std::nullopt;
}

glm::vec3 acesFitted(glm::vec3 c) {
  // sRGB → RRT input (ACES AP1, with the RRT's saturation), the rational fit of RRT+ODT, then back
  // (Stephen Hill's fit). glm matrices are column-major: each glm::vec3 below is a column.
  const glm::mat3 in(glm::vec3(0.59719f, 0.07600f, 0.02840f), glm::vec3(0.35458f, 0.90834f, 0.13383f),
                     glm::vec3(0.04823f, 0.01566f, 0.83777f));
  const glm::mat3 out(glm::vec3(1.60475f, -0.10208f, -0.00327f), glm::vec3(-0.53108f, 1.10813f, -0.07276f),
                      glm::vec3(-0.07367f, -0.00605f, 1.07602f));
  c = in * c;
  c = (c * (c + 0.0245786f) - 0.000090537f) / (c * (0.983729f * c + 0.4329510f) + 0.238081f);
  return glm::clamp(out * c, 0.0f, 1.0f);
}

glm::vec3 pbrNeutral(glm::vec3 c) {
  // Khronos PBR Neutral specification (KhronosGroup/ToneMapping, PBR_Neutral/README.md).
  const float x = std::min({c.r, c.g, c.b});
  const float offset = x < 2.0f * kNeutralF90 ? x - x * x / (4.0f * kNeutralF90) : kNeutralF90;
  c -= offset;
  const float peak = std::max({c.r, c.g, c.b});
  if (peak < kNeutralStartCompression) return c;
  const float d = 1.0f - kNeutralStartCompression;
  const float newPeak = 1.0f - d * d / (peak + d - kNeutralStartCompression);
  c *= newPeak / peak;
  // Desaturate towards the compressed peak (grey of the same value), not towards white.
  const float g = 1.0f - 1.0f / (kNeutralDesaturation * (peak - newPeak) + 1.0f);
  return glm::mix(c, glm::vec3(newPeak), g);
}

glm::vec3 applyTonemapper(Tonemapper t, glm::vec3 c) {
  c = glm::max(c, glm::vec3(0.0f));
  return t == Tonemapper::Neutral ? pbrNeutral(c) : acesFitted(c);
}

}  // namespace rayster::render
