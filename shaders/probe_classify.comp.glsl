#version 460
#include "lib/common.glsl"
#include "shared/probes.h"

// Probe relocation and classification (gi-probe-classify, docs/techniques.md §16b), one invocation
// per probe, from this frame's rays (probe_trace.rgen: a negative distance marks a back-face hit):
// - more than kProbeBackfaceFraction back-face hits: the probe is inside geometry; it moves
//   towards (and through) the nearest back face, a step per frame;
// - else a surface nearer than kProbeMinFrontDistance × spacing: it moves away from it;
// the offset stays within kProbeMaxOffset of the spacing per axis (a probe keeps its cell); spacings
// are the probe's cascade's.
// A probe is inactive (left out of every lookup) while it is still inside geometry, or when no
// surface is within a cell diagonal of it (no shaded point can be near it).
// Output (RGBA16F, texel (probe, 0)): xyz the offset, w 1 active / 0 inactive.
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2D raysTex;       // (ray, probe): rgb radiance, a distance
layout(set = 0, binding = 1) uniform sampler2D previousData;  // the frame before's (kProbeDataValid)
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D outData;
layout(push_constant, scalar) uniform Push { ProbeGrid grid; };

#define PROBES_NO_LOOKUP
#include "lib/probes.glsl"

void main() {
  uint probe = gl_GlobalInvocationID.x;
  if (probe >= probeCount(grid)) return;
  // A probe that just entered its cascade's window (shared/probes.h) starts at its lattice point.
  bool known = (grid.flags & kProbeDataValid) != 0u && !probeFresh(grid, probe);
  vec3 offset = known ? texelFetch(previousData, ivec2(probe, 0), 0).xyz : vec3(0.0);
  uint backfaces = 0u;
  float closestBack = 1e30, closestFront = 1e30;
  vec3 backDir = vec3(0.0), frontDir = vec3(0.0);
  for (uint r = 0u; r < grid.raysPerProbe; ++r) {
    float d = texelFetch(raysTex, ivec2(r, probe), 0).a;
    vec3 dir = probeRayDirection(grid, r);
    if (d < 0.0) {
      ++backfaces;
      float t = -5.0 * d;  // stored as −0.2 t
      if (t < closestBack) {
        closestBack = t;
        backDir = dir;
      }
    } else if (d < closestFront) {
      closestFront = d;
      frontDir = dir;
    }
  }
  uint k = probeCascade(grid, probe);
  vec3 cellSize = probeSpacing(grid, k);
  float spacing = probeMinSpacing(grid, k);
  bool inside = float(backfaces) > kProbeBackfaceFraction * float(grid.raysPerProbe);
  if (inside)
    offset += backDir * (closestBack + kProbeMinFrontDistance * spacing);
  else if (closestFront < kProbeMinFrontDistance * spacing)
    offset -= frontDir * (kProbeMinFrontDistance * spacing - closestFront);
  offset = clamp(offset, -kProbeMaxOffset * cellSize, kProbeMaxOffset * cellSize);
  bool nearSurface = min(closestFront, closestBack) <= length(cellSize);
  imageStore(outData, ivec2(probe, 0), vec4(offset, !inside && nearSurface ? 1.0 : 0.0));
}
