// À-trous iterations read their 5×5 taps from shared memory (TECHNIQUES.md §9, §12): the taps of
// pixel p at step s are p + s·(i, j), so pixels of one residue class p mod s share every tap. A
// workgroup takes an 8×8 block of one residue class's lattice (pixels r + s·u), loads the block
// and its 2-point apron (12×12 lattice points) once, and every pixel filters from that tile:
// 144 loads per 64 pixels instead of 25 per pixel, at every step. Groups: per axis, s residues ×
// ceil(ceil(size / s) / 8) blocks (render/passes/denoise.h atrousGroups()).
#ifndef RAYSTER_ATROUS_TILE_GLSL
#define RAYSTER_ATROUS_TILE_GLSL

const int kAtrousBlock = 8;
const int kAtrousApron = 2;
const int kAtrousSpan = kAtrousBlock + 2 * kAtrousApron;  // 12
const int kAtrousTexels = kAtrousSpan * kAtrousSpan;       // 144

struct AtrousLattice {
  ivec2 residue;  // p mod step of every pixel of the group
  ivec2 origin;   // lattice coordinate of tile texel (0, 0)
  int step;
};

AtrousLattice atrousLattice(uvec2 size, uint step) {
  uvec2 blocks = ((size + step - 1u) / step + uvec2(kAtrousBlock - 1)) / uvec2(kAtrousBlock);
  AtrousLattice a;
  a.residue = ivec2(gl_WorkGroupID.xy / blocks);
  a.origin = ivec2(gl_WorkGroupID.xy % blocks) * kAtrousBlock - kAtrousApron;
  a.step = int(step);
  return a;
}
// The pixel of tile texel t (0 ≤ t < kAtrousSpan).
ivec2 atrousTexelPixel(AtrousLattice a, ivec2 t) { return a.residue + a.step * (a.origin + t); }
// This invocation's pixel and its tile texel.
ivec2 atrousTexel() { return ivec2(gl_LocalInvocationID.xy) + kAtrousApron; }
int atrousIndex(ivec2 t) { return t.y * kAtrousSpan + t.x; }

#endif
