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
// [kExposureMinLog2, kExposureMaxLog2] evenly (0.16 EV each), the last also taking everything
// brighter (and inf).
RAYSTER_CONST uint kExposureBins = 256u;
// The buffer holds two histograms: the scene's surfaces first, then the background (pixels where
// the camera ray escapes: sky, environment). The meter exposes for the surfaces, as a photographer
// meters the subject and not the sky, unless they cover less than kExposureMinSurface of the frame.
RAYSTER_CONST uint kExposureHistograms = 2u;
RAYSTER_CONST float kExposureMinSurface = 0.05;
RAYSTER_CONST float kExposureMinLog2 = -16.0;  // 1.5e-5 cd/m²: far below starlight
RAYSTER_CONST float kExposureMaxLog2 = 24.0;   // 1.7e7 cd/m²: past the sun's disc at 120 000 lux

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
