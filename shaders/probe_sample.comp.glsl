#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "shared/probes.h"

// Probe lookup for the G-buffer (gi-probe-sample, docs/techniques.md §16b): the irradiance E of the
// diffuse indirect light at every pixel from the probes around it (lib/probes.glsl), in the slot
// of the one-bounce path's image: lighting takes it as the diffuse indirect light (kEffectIndirect).
// Output (RGBA16F): rgb E (pre-exposed), 0 on the background; outSpecularIrradiance the same about
// the mirror direction reflect(−v, n), which lighting divides by π for the untraced (rough) share
// of the specular light (kEffectIndirectSpecular): the room and the sky a rough metal reflects.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D depthTex;
layout(set = 0, binding = 2) uniform sampler2D normalTex;
layout(set = 0, binding = 3) uniform sampler2D probeIrradianceTex;
layout(set = 0, binding = 4) uniform sampler2D probeVisibilityTex;
layout(set = 0, binding = 6) uniform sampler2D probeDataTex;
layout(set = 0, binding = 5, rgba16f) uniform writeonly image2D outIrradiance;
layout(set = 0, binding = 7, rgba16f) uniform writeonly image2D outSpecularIrradiance;
layout(push_constant, scalar) uniform Push { ProbeGrid grid; };

#include "lib/probes.glsl"

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), frame.size))) return;
  float depth = texelFetch(depthTex, px, 0).r;
  vec3 e = vec3(0.0), es = vec3(0.0);
  if (!isBackground(depth)) {
    vec2 uv = (vec2(px) + 0.5) / vec2(frame.size);
    vec3 p = worldFromDepth(frame.worldFromClip, uv, depth);
    vec3 n = octDecode(texelFetch(normalTex, px, 0).xy);
    vec3 v = normalize(frame.cameraPosition.xyz - p);
    // The mirror direction's lookup shares the eight probes' weights (the point's, not the
    // direction's: the same visibility test).
    probeIrradiance2(grid, p, n, v, true, reflect(-v, n), e, es);
  }
  imageStore(outIrradiance, px, vec4(e, 1.0));
  imageStore(outSpecularIrradiance, px, vec4(es, 1.0));
}
