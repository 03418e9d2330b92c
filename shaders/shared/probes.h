// Irradiance probes (DDGI: render/passes/gi_probes.cpp, docs/techniques.md §16b): the probe grid
// and the layout of its atlases, shared by C++ and GLSL (push constants of every probe pass).
#ifndef RAYSTER_SHARED_PROBES_H
#define RAYSTER_SHARED_PROBES_H

#include "types.h"  // relative: C++ includes shaders/shared/, GLSL shared/

#ifdef __cplusplus
namespace rayster::gpu {
#endif

// Octahedral tiles per probe: interior texels per side; each tile has a one-texel border that
// repeats the octahedral neighbours, so bilinear filtering never reads another probe.
RAYSTER_CONST uint kProbeIrradianceTexels = 8u;   // RGBA16F: rgb irradiance E (= π × cosine-weighted mean L)
                                                  // (and the bounce atlas: its share that came through probes)
RAYSTER_CONST uint kProbeVisibilityTexels = 16u;  // RG32F: mean and mean square of the hit distance
RAYSTER_CONST uint kProbeRaysPerProbe = 128u;     // rays traced per probe and frame
// ProbeGrid::flags
RAYSTER_CONST uint kProbeHistoryValid = 1u;  // the atlases of the frame before hold light: bounce through them
RAYSTER_CONST uint kProbeLookup = 2u;        // passes outside the probe passes (rt-specular): use the probes
RAYSTER_CONST uint kProbeDataValid = 4u;     // probeDataTex holds each probe's offset and state (else 0, active)
// Relocation and classification (probe_classify.comp), in units of the grid's smallest spacing.
RAYSTER_CONST float kProbeBackfaceFraction = 0.25;  // more back-face hits than this: the probe is inside geometry
RAYSTER_CONST float kProbeMinFrontDistance = 0.2;   // nearer a surface than this: pushed away from it
RAYSTER_CONST float kProbeMaxOffset = 0.45;         // of the spacing per axis: a probe stays in its cell
// Cascades (docs/techniques.md §16b): cascade cascades−1 is the grid fitted to the scene; each finer
// one halves the spacing of the next on the axes still coarser than the target, keeps the counts,
// and follows the camera.
RAYSTER_CONST uint kMaxProbeCascades = 4u;
RAYSTER_CONST uint kProbeWindowMoved = 1u << 30;  // ProbeGrid::cascadeCells[k].x

struct ProbeGrid {
  vec3 origin;  // world position of the coarsest cascade's probe (0, 0, 0): the lattices' origin
  uint raysPerProbe;
  vec3 spacing;      // between neighbouring probes, per axis, in the coarsest cascade (probeSpacing(): cascade k's)
  uint tilesPerRow;  // atlas columns (both atlases): probe i's tile is (i % tilesPerRow, i / tilesPerRow)
  uvec3 counts;      // probes per axis and cascade (≥ 2 each)
  uint flags;        // kProbe*
  vec4 rotation;     // this frame's random rotation of the ray directions (unit quaternion)
  float hysteresis;  // weight of the previous atlas in the blend (0: this frame only): direct light
  float bounceHysteresis;  // the same for the light that bounced through the probes (lower: see §16b)
  float normalBias;        // lookup point offset along the normal, × the smallest spacing
  float viewBias;          // and towards the viewer
  float maxDistance;       // what a ray that misses records as its distance
  float historyScale;  // the exposure ratio (FrameConstants::exposureRatio) the previous irradiance atlas is read × by
  uint cascades;       // 1..kMaxProbeCascades; probe index = cascade × probes per cascade + slot
  // Per cascade k, where its window of counts probes lies on its lattice (in its own spacings from
  // origin): .x = cell x | y << 8 | z << 16 | the lattice's log2 cells per coarsest cell on each
  // axis (2 bits each, x first) << 24 | kProbeWindowMoved when the window moved since the update
  // before; .y = the window's cells modulo counts (3 bits each, x first: the slot of its first
  // probe) | when it moved, by how many cells on each axis (cell − previous cell, clamped to ±8,
  // + 8, 5 bits each from bit 9). A probe's slot in its cascade is its lattice coordinate modulo
  // counts (toroidal): when the window scrolls, only the probes that entered it start without
  // history (probeFresh()).
  uvec2 cascadeCells[kMaxProbeCascades];
};

#ifdef __cplusplus
static_assert(sizeof(ProbeGrid) == 124);  // ≤ 128: push constants every device has
}  // namespace rayster::gpu
#endif

#endif
