#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "shared/probes.h"

// The probes' debug view (gi-probe-view, render/passes/gi_probe_view.cpp): the lit image with every
// probe drawn as a sphere of radius kProbeViewRadius × its cascade's smallest spacing at its relocated
// position, in front of the G-buffer's surface only. An active probe's sphere shows the probe's
// irradiance E in the direction of the sphere's normal, over π (a white Lambert ball lit by it); an
// inactive one is dark red. Output (RGBA16F): linear HDR, pre-exposed like its input.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D depthTex;
layout(set = 0, binding = 2) uniform sampler2D hdrTex;
layout(set = 0, binding = 3) uniform sampler2D probeIrradianceTex;
layout(set = 0, binding = 4) uniform sampler2D probeDataTex;
layout(set = 0, binding = 5, rgba16f) uniform writeonly image2D outColor;
layout(push_constant, scalar) uniform Push { ProbeGrid grid; };

#define PROBES_NO_LOOKUP
#include "lib/probes.glsl"

const float kProbeViewRadius = 0.1;

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), frame.size))) return;
  vec2 uv = (vec2(px) + 0.5) / vec2(frame.size);
  vec3 origin = frame.cameraPosition.xyz;
  vec3 dir = cameraRayDirection(frame.worldFromClip, uv, origin);
  float depth = texelFetch(depthTex, px, 0).r;
  float tSurface = isBackground(depth) ? 1e30 : distance(origin, worldFromDepth(frame.worldFromClip, uv, depth));
  float tBest = tSurface;
  uint best = 0xffffffffu;
  vec3 bestCentre = vec3(0.0);
  for (uint i = 0u; i < probeCount(grid); ++i) {
    vec3 centre = probeWorldPosition(grid, i) + texelFetch(probeDataTex, ivec2(i, 0), 0).xyz;
    float radius = kProbeViewRadius * probeMinSpacing(grid, probeCascade(grid, i));
    vec3 oc = origin - centre;
    float b = dot(oc, dir), c = dot(oc, oc) - radius * radius, disc = b * b - c;
    if (disc < 0.0) continue;
    float t = -b - sqrt(disc);
    if (t > 0.0 && t < tBest) {
      tBest = t;
      best = i;
      bestCentre = centre;
    }
  }
  vec3 color = texelFetch(hdrTex, px, 0).rgb;
  if (best != 0xffffffffu) {
    vec3 n = normalize(origin + tBest * dir - bestCentre);
    bool isActive = texelFetch(probeDataTex, ivec2(best, 0), 0).w > 0.5;
    vec2 atlasSize = vec2(textureSize(probeIrradianceTex, 0));
    color = isActive ? texture(probeIrradianceTex, probeAtlasUv(grid, best, n, kProbeIrradianceTexels, atlasSize)).rgb / kPi
                   : vec3(0.3, 0.0, 0.0);  // pre-exposed: a dark red on any exposure
  }
  imageStore(outColor, px, vec4(color, 1.0));
}
