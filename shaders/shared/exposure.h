// Automatic exposure (render/exposure.h, render/passes/exposure.cpp, docs/techniques.md §20): the
// luminance histogram's layout, shared by C++ (the host reads the histogram and the path tracer
// bins its mean the same way) and GLSL (exposure_histogram.comp).
#ifndef RAYSTER_SHARED_EXPOSURE_H
#define RAYSTER_SHARED_EXPOSURE_H

#include "types.h"  // relative: C++ includes shaders/shared/, GLSL shared/

#ifdef __cplusplus
#include <algorithm>
#include <cmath>
#endif

#ifdef __cplusplus
namespace rayster::gpu {
#endif

// Bin 0 counts pixels darker than 2^kExposureMinLog2 cd/m² (black: sky-less backgrounds, unlit
// corners; the meter leaves them out); bins 1 .. kExposureBins-1 split log2 luminance
// [kExposureMinLog2, kExposureMaxLog2] evenly (0.23 EV each), the last also taking everything
// brighter (and inf).
RAYSTER_CONST uint kExposureBins = 256u;
// The buffer holds two histograms: the scene's surfaces first, then the background (pixels where
// the camera ray escapes: sky, environment). The meter exposes for the surfaces, as a photographer
// meters the subject and not the sky, unless they cover less than kExposureMinSurface of the frame.
RAYSTER_CONST uint kExposureHistograms = 2u;
RAYSTER_CONST float kExposureMinSurface = 0.05;
// 6e-8 cd/m²: far below starlight, and below the shadows of a scene lit by 1 lux (at 2^-16 they
// fell into bin 0, which the meter leaves out, and a 1 lux scene metered 0.4 EV brighter than the
// same scene at 100 000 lux).
RAYSTER_CONST float kExposureMinLog2 = -24.0;
// 1.7e10 cd/m²: the sun's disc at 120 000 lux is 1.8e9, and a highlight on a dark surface counts
// up to 4.5× its luminance (the meter's albedo normalisation). A range that clipped the highlights
// of a bright sun (2^24 did) made the reading of a scene depend on its scale: a 100 000 lux scene
// metered 0.35 EV darker than the same scene at 1 lux.
RAYSTER_CONST float kExposureMaxLog2 = 34.0;

struct ExposurePush {
  uvec2 size;
  float invExposure;  // 1 / the frame's pre-exposure: the histogram is of the scene's own luminance
  uint pad;
};

// The histogram bin of a luminance in the scene's units (cd/m²); NaN counts as black. One body
// for both languages: the GPU histogram and the host's (the path tracer's mean) bin alike.
#ifdef __cplusplus
#define RAYSTER_EXPOSURE_FN inline
#define RAYSTER_EXPOSURE_MATH \
  using std::exp2;            \
  using std::log2;            \
  using std::min;
#else
#define RAYSTER_EXPOSURE_FN
#define RAYSTER_EXPOSURE_MATH
#endif
RAYSTER_EXPOSURE_FN uint exposureBin(float luminance) {
  RAYSTER_EXPOSURE_MATH
  if (!(luminance >= exp2(kExposureMinLog2))) return 0u;
  const float t = (log2(luminance) - kExposureMinLog2) / (kExposureMaxLog2 - kExposureMinLog2);
  return 1u + uint(min(t, 1.0f) * float(kExposureBins - 2u) + 0.5);
}

#ifdef __cplusplus
static_assert(sizeof(ExposurePush) == 16);
}  // namespace rayster::gpu
#endif

#endif
