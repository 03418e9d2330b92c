// Quarter-rate one-bounce indirect diffuse (--indirect-rate quarter, FrameConstants::effectFlags
// kEffectIndirectQuarter): which pixel of each 2×2 block indirect.rgen and its raw twin trace this
// frame, and so which ones indirect_fill.comp fills. Needs lib/frame.glsl.
#ifndef RAYSTER_INDIRECT_RATE_GLSL
#define RAYSTER_INDIRECT_RATE_GLSL

bool indirectQuarterRate() {
  const uint kQuarter = kEffectIndirect | kEffectIndirectQuarter;
  return (frame.effectFlags & kQuarter) == kQuarter;
}

// The offset within its 2×2 block of the pixel traced this frame. Every aligned run of 4 frames
// visits the 4 positions (so SVGF's temporal accumulation sees every pixel traced once in 4 frames),
// the two diagonals one after the other. The order is XORed with the run's index, so over the
// 16-frame TAA jitter period each position is traced under each of the 4 classes of frameIndex mod 4
// (the Halton(2,3) jitter's low base-2 digits) instead of always the same sub-pixel quadrant.
ivec2 indirectBlockOffset(uint frameIndex) {
  const ivec2 kOrder[4] = ivec2[](ivec2(0, 0), ivec2(1, 1), ivec2(1, 0), ivec2(0, 1));
  return kOrder[(frameIndex ^ (frameIndex >> 2u)) & 3u];
}

// The pixel traced this frame in 2×2 block `block` (clamped into the image on a partial last block).
ivec2 indirectTracedPixel(ivec2 block) {
  return min(2 * block + indirectBlockOffset(frame.frameIndex), ivec2(frame.size) - 1);
}

// The pixel of launch invocation `id`: itself at full rate, its block's traced pixel at quarter rate.
ivec2 indirectPixel(uvec2 id) { return indirectQuarterRate() ? indirectTracedPixel(ivec2(id)) : ivec2(id); }

#endif
