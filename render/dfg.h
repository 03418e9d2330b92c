#pragma once
// The split-sum DFG table (Karis 2013) for GGX with height-correlated Smith, integrated on the CPU at
// start-up with the same VNDF sampler the specular pass runs (shaders/shared/vndf.h). For a view
// cosine n·v and a perceptual roughness r it holds (A, B) with
//   F0·A + B = E[F(V·H)·G2(V,L)/G1(V)]  under VNDF sampling (Schlick F),
// i.e. the directional albedo of the specular lobe. The specular pass divides its sample by A + B
// (the mean of G2/G1) and lighting multiplies by F0·A + B (docs/techniques.md §13).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "shaders/shared/types.h"

namespace rayster::render {

struct GpuScene;

// Texels: n·v = i / (size − 1) along x, roughness = j / (size − 1) along y (texel centres), so the
// shader looks up uv = (x·(size − 1) + 0.5) / size.
inline constexpr uint32_t kDfgSize = gpu::kDfgSize;
inline constexpr uint32_t kDfgSamples = 1024;  // per texel; error well under the RG16F step

// (A, B) at one (n·v, roughness), with `samples` stratified VNDF samples.
glm::vec2 integrateDfg(float nv, float roughness, uint32_t samples);
// The whole table, row-major (roughness rows of n·v texels).
std::vector<glm::vec2> computeDfgTable(uint32_t size = kDfgSize, uint32_t samples = kDfgSamples);

}  // namespace rayster::render
