#pragma once
// The tonemap operators of shaders/tonemap.comp.glsl, mirrored in C++ so unit tests can pin their
// curves (0 → 0, monotonic, known points) and check the GPU pass against them (docs/techniques.md §19).
// The shader is the product; keep both in step.
#include <cstdint>
#include <optional>
#include <string_view>

#include <glm/glm.hpp>

#include "shaders/shared/types.h"

namespace rayster::render {

enum class Tonemapper : uint32_t {
  Aces = gpu::kTonemapAces,        // Hill's fit of the ACES RRT+ODT (filmic, desaturates highlights)
  Neutral = gpu::kTonemapNeutral,  // Khronos PBR Neutral (base colours reproduced, hue kept)
};
const char* tonemapperName(Tonemapper t);
std::optional<Tonemapper> parseTonemapper(std::string_view name);

// Linear HDR (after exposure, non-negative) → linear display [0, 1].
glm::vec3 acesFitted(glm::vec3 c);
glm::vec3 pbrNeutral(glm::vec3 c);
glm::vec3 applyTonemapper(Tonemapper t, glm::vec3 c);

// The Khronos PBR Neutral parameters (its specification: F90, Ks = 0.8 − F90, Kd).
inline constexpr float kNeutralF90 = 0.04f;
inline constexpr float kNeutralStartCompression = 0.8f - kNeutralF90;
inline constexpr float kNeutralDesaturation = 0.15f;

}  // namespace rayster::render
