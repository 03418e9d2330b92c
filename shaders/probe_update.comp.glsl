#version 460
// variant: probe_update_visibility.comp PROBE_VISIBILITY
#include "lib/common.glsl"
#include "shared/probes.h"

// Probe atlas update (gi-probe-update-irradiance, and as its PROBE_VISIBILITY variant
// gi-probe-update-visibility; docs/techniques.md §16b): one workgroup per probe, one invocation
// per texel of its tile including the border (whose octahedral direction folds back onto the
// interior, so border texels repeat their neighbours). Each texel integrates this frame's rays of
// its probe around its direction and blends the result with the previous atlas:
//   irradiance: E = π Σ L max(0, d·ω) / Σ max(0, d·ω)   (cosine-weighted mean radiance × π)
//   visibility: (mean, mean²) of the hit distance, weights max(0, d·ω)^50 (a narrow lobe)
// blend = hysteresis × previous + (1 − hysteresis) × this frame (previous ignored while the
// history is empty). The irradiance is blended in two shares: the light that came through the
// probes (bounceAtlas, the frame before's probes seen at the rays' hits) with bounceHysteresis, the
// rest (emission, direct light, the environment: total − bounce) with hysteresis. The bounce share
// lags (it is built from older atlases) and is smooth; a low hysteresis there lets multiple
// bounces converge in tens of frames (docs/techniques.md §16b).
#ifdef PROBE_VISIBILITY
#define TEXELS kProbeVisibilityTexels
#define TILE 18
layout(set = 0, binding = 2, rg32f) uniform writeonly image2D outAtlas;
#else
#define TEXELS kProbeIrradianceTexels
#define TILE 10
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D outAtlas;
layout(set = 0, binding = 3) uniform sampler2D bounceRaysTex;    // (ray, probe): rgb the share through probes
layout(set = 0, binding = 4) uniform sampler2D previousBounce;   // the bounce atlas, the frame before
layout(set = 0, binding = 5, rgba16f) uniform writeonly image2D outBounce;
#endif
layout(local_size_x = TILE, local_size_y = TILE) in;
layout(set = 0, binding = 0) uniform sampler2D raysTex;       // (ray, probe): rgb radiance, a distance
layout(set = 0, binding = 1) uniform sampler2D previousAtlas;  // the same atlas, the frame before
layout(push_constant, scalar) uniform Push { ProbeGrid grid; };

#define PROBES_NO_LOOKUP
#include "lib/probes.glsl"

shared vec4 sRays[kProbeRaysPerProbe];
shared vec3 sDirs[kProbeRaysPerProbe];
#ifndef PROBE_VISIBILITY
shared vec3 sBounce[kProbeRaysPerProbe];
#endif

void main() {
  uint probe = gl_WorkGroupID.x;
  uint local = gl_LocalInvocationIndex;
  for (uint r = local; r < grid.raysPerProbe; r += uint(TILE * TILE)) {
    sRays[r] = texelFetch(raysTex, ivec2(r, probe), 0);
    sDirs[r] = probeRayDirection(grid, r);
#ifndef PROBE_VISIBILITY
    sBounce[r] = texelFetch(bounceRaysTex, ivec2(r, probe), 0).rgb;
#endif
  }
  barrier();
  ivec2 texel = ivec2(gl_LocalInvocationID.xy);
  vec3 d = octDecode(probeTexelOct(texel, TEXELS));
  vec4 sum = vec4(0.0);
  vec3 bounceSum = vec3(0.0);
  float weightSum = 0.0;
  for (uint r = 0u; r < grid.raysPerProbe; ++r) {
    float c = max(0.0, dot(d, sDirs[r]));
#ifdef PROBE_VISIBILITY
    if (c < 0.75) continue;  // 0.75^50 < 1e-6: no weight worth a pow()
    float w = pow(c, 50.0);
    float dist = min(abs(sRays[r].a), grid.maxDistance);
    sum.xy += w * vec2(dist, dist * dist);
#else
    float w = c;
    sum.rgb += w * sRays[r].rgb;
    bounceSum += w * sBounce[r];
#endif
    weightSum += w;
  }
  vec4 value = weightSum > 1e-6 ? sum / weightSum : vec4(0.0);
  ivec2 at = probeTileOrigin(grid, probe, TEXELS) + texel;
  // A probe that just entered its cascade's window: the previous tile is another place's light.
  bool history = (grid.flags & kProbeHistoryValid) != 0u && !probeFresh(grid, probe);
#ifdef PROBE_VISIBILITY
  if (history) value = mix(value, texelFetch(previousAtlas, at, 0), grid.hysteresis);
#else
  value.rgb *= kPi;
  vec3 bounce = weightSum > 1e-6 ? kPi * bounceSum / weightSum : vec3(0.0);
  if (history) {
    // exposed with last frame's exposure
    vec3 previous = texelFetch(previousAtlas, at, 0).rgb * grid.historyScale;
    vec3 previousBounceE = texelFetch(previousBounce, at, 0).rgb * grid.historyScale;
    vec3 direct = mix(value.rgb - bounce, previous - previousBounceE, grid.hysteresis);
    bounce = mix(bounce, previousBounceE, grid.bounceHysteresis);
    value.rgb = max(direct, vec3(0.0)) + bounce;
  }
  imageStore(outBounce, at, vec4(bounce, 1.0));
#endif
  imageStore(outAtlas, at, vec4(value.rgb, 1.0));
}
