// KHR_materials_sheen's lobe: the "Charlie" distribution (Estevez and Kulla, "Production Friendly
// Microfacet Sheen BRDF", 2017) with Ashikhmin's visibility term, and its directional albedo E(n·v,
// roughness) as a table, which scales the layers below (albedo scaling, as the extension's
// specification describes). Compiled as GLSL by the path tracer and as C++ by the table's test
// (tests/unit/test_sheen.cpp recomputes the table from these functions). GLSL includers need
// lib/frame.glsl and lib/textures.glsl first (sheenAlbedo() reads the table's texture).
#ifndef RAYSTER_SHARED_SHEEN_H
#define RAYSTER_SHARED_SHEEN_H

#ifdef __cplusplus
#include <cmath>

#include "shaders/shared/types.h"
namespace rayster::gpu {
using glm::clamp;
using glm::max;
using glm::min;
using glm::mix;
using std::pow;
using std::sqrt;
#define RAYSTER_FN inline
#else
#include "shared/types.h"
#define RAYSTER_FN
#endif

RAYSTER_CONST float kSheenPi = 3.14159265358979f;
// Below this the distribution's exponent 1/α overflows single precision at grazing angles.
RAYSTER_CONST float kMinSheenRoughness = 0.07f;
RAYSTER_CONST uint kSheenTableSize = 16u;

RAYSTER_FN float sheenAlpha(float roughness) {
  float r = clamp(roughness, kMinSheenRoughness, 1.0f);
  return r * r;
}

// D(h) for cosθ_h = nh: (2 + 1/α)·sin^(1/α)θ_h / 2π.
RAYSTER_FN float charlieDistribution(float nh, float alpha) {
  float sin2 = max(1.0f - nh * nh, 0.0f);
  return (2.0f + 1.0f / alpha) * pow(sin2, 0.5f / alpha) / (2.0f * kSheenPi);
}

// Ashikhmin's visibility, 1 / (4 (n·l + n·v − n·l n·v)): already divided by the 4 n·l n·v of the
// microfacet model.
RAYSTER_FN float ashikhminVisibility(float nl, float nv) { return 1.0f / (4.0f * (nl + nv - nl * nv)); }

// E(n·v, roughness) = ∫ D(h)·V(n·l, n·v)·n·l dω_l for a white sheen: row = roughness (0..1 in
// kSheenTableSize steps, clamped to kMinSheenRoughness), column = n·v (0..1; 0 is 1e-3). Written by
// integrating the functions above (midpoint rule, 512 × 1024 directions); test_sheen.cpp checks it.
// Near grazing Ashikhmin's term reflects more than arrives (E > 1): sheenLobeScale() normalises it.
#ifdef __cplusplus
RAYSTER_CONST float kSheenAlbedo[kSheenTableSize * kSheenTableSize] = {
    5.45817f, 1.34279f, 0.38027f, 0.09779f, 0.02153f, 0.00389f, 0.00055f, 0.00006f, 0.00000f, 0.00000f, 0.00000f,
    0.00000f, 0.00000f, 0.00000f, 0.00000f, 0.00000f, 5.45817f, 1.34279f, 0.38027f, 0.09779f, 0.02153f, 0.00389f,
    0.00055f, 0.00006f, 0.00000f, 0.00000f, 0.00000f, 0.00000f, 0.00000f, 0.00000f, 0.00000f, 0.00000f, 2.95021f,
    1.32504f, 0.68778f, 0.35783f, 0.18114f, 0.08773f, 0.04006f, 0.01698f, 0.00656f, 0.00225f, 0.00066f, 0.00016f,
    0.00003f, 0.00000f, 0.00000f, 0.00000f, 2.01432f, 1.14352f, 0.73316f, 0.47786f, 0.30996f, 0.19788f, 0.12330f,
    0.07437f, 0.04301f, 0.02356f, 0.01202f, 0.00557f, 0.00224f, 0.00072f, 0.00015f, 0.00001f, 1.55014f, 0.99364f,
    0.70759f, 0.51376f, 0.37381f, 0.27022f, 0.19289f, 0.13520f, 0.09248f, 0.06126f, 0.03890f, 0.02332f, 0.01287f,
    0.00624f, 0.00237f, 0.00042f, 1.27678f, 0.88137f, 0.66836f, 0.51705f, 0.40200f, 0.31186f, 0.24020f, 0.18290f,
    0.13705f, 0.10052f, 0.07166f, 0.04913f, 0.03187f, 0.01898f, 0.00970f, 0.00340f, 1.09919f, 0.79728f, 0.63029f,
    0.50829f, 0.41256f, 0.33490f, 0.27075f, 0.21722f, 0.17232f, 0.13463f, 0.10303f, 0.07667f, 0.05484f, 0.03696f,
    0.02255f, 0.01118f, 0.97623f, 0.73335f, 0.59702f, 0.49568f, 0.41457f, 0.34727f, 0.29027f, 0.24136f, 0.19907f,
    0.16232f, 0.13032f, 0.10245f, 0.07822f, 0.05723f, 0.03915f, 0.02370f, 0.88722f, 0.68391f, 0.56895f, 0.48257f,
    0.41255f, 0.35358f, 0.30278f, 0.25837f, 0.21916f, 0.18429f, 0.15313f, 0.12521f, 0.10015f, 0.07764f, 0.05744f,
    0.03934f, 0.82059f, 0.64508f, 0.54554f, 0.47028f, 0.40876f, 0.35644f, 0.31086f, 0.27049f, 0.23432f, 0.20164f,
    0.17192f, 0.14476f, 0.11985f, 0.09693f, 0.07582f, 0.05634f, 0.76941f, 0.61414f, 0.52607f, 0.45926f, 0.40436f,
    0.35737f, 0.31612f, 0.27925f, 0.24589f, 0.21541f, 0.18735f, 0.16136f, 0.13716f, 0.11454f, 0.09332f, 0.07336f,
    0.72925f, 0.58917f, 0.50984f, 0.44958f, 0.39992f, 0.35723f, 0.31956f, 0.28570f, 0.25485f, 0.22644f, 0.20006f,
    0.17539f, 0.15219f, 0.13026f, 0.10944f, 0.08959f, 0.69718f, 0.56878f, 0.49626f, 0.44116f, 0.39570f, 0.35652f,
    0.32183f, 0.29053f, 0.26188f, 0.23536f, 0.21059f, 0.18727f, 0.16518f, 0.14414f, 0.12399f, 0.10460f, 0.67119f,
    0.55196f, 0.48484f, 0.43388f, 0.39181f, 0.35553f, 0.32334f, 0.29422f, 0.26748f, 0.24265f, 0.21936f, 0.19734f,
    0.17638f, 0.15630f, 0.13696f, 0.11824f, 0.64985f, 0.53794f, 0.47517f, 0.42758f, 0.38831f, 0.35442f, 0.32433f,
    0.29708f, 0.27201f, 0.24867f, 0.22673f, 0.20592f, 0.18604f, 0.16694f, 0.14846f, 0.13049f, 0.63213f, 0.52616f,
    0.46695f, 0.42213f, 0.38517f, 0.35329f, 0.32498f, 0.29932f, 0.27570f, 0.25369f, 0.23295f, 0.21326f, 0.19440f,
    0.17623f, 0.15861f, 0.14142f};
#endif

// E at (n·v, roughness), bilinear between the table's entries. On the GPU the table is a bindless
// R16F texture (FrameConstants::sheenSlot) whose linear filter does the same: a constant array
// indexed per lane made lavapipe's LLVM take minutes over the path tracer.
#ifdef __cplusplus
RAYSTER_FN float sheenAlbedo(float nv, float roughness) {
  float n = float(kSheenTableSize - 1u);
  float x = clamp(nv, 0.0f, 1.0f) * n, y = clamp(roughness, 0.0f, 1.0f) * n;
  uint x0 = min(uint(x), kSheenTableSize - 2u), y0 = min(uint(y), kSheenTableSize - 2u);
  float fx = x - float(x0), fy = y - float(y0);
  uint i = y0 * kSheenTableSize + x0;
  float top = mix(kSheenAlbedo[i], kSheenAlbedo[i + 1u], fx);
  float bottom = mix(kSheenAlbedo[i + kSheenTableSize], kSheenAlbedo[i + kSheenTableSize + 1u], fx);
  return mix(top, bottom, fy);
}
#else
float sheenAlbedo(float nv, float roughness) {
  const float n = float(kSheenTableSize);
  vec2 uv = (clamp(vec2(nv, roughness), 0.0, 1.0) * (n - 1.0) + 0.5) / n;  // texel centres at the ends
  return textureLod(textures[nonuniformEXT(frame.sheenSlot)], uv, 0.0).r;
}
#endif

#ifdef __cplusplus
}  // namespace rayster::gpu
#endif

#endif
