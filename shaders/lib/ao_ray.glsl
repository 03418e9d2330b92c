// The ambient-occlusion ray of pixel `px` (docs/techniques.md §15), shared by ao.rgen and its raw-rate
// twin raw_ao.rgen so both trace exactly the same rays: cosine-weighted about the shading normal,
// from P offset along the geometric normal, frame.aoRadius long. The includer declares depthTex and
// normalTex. Returns false when no ray is traced; `value` is then the pixel's AO: 1 on the
// background and with AO off, 0 when the direction is under the geometric surface.
#ifndef RAYSTER_AO_RAY_GLSL
#define RAYSTER_AO_RAY_GLSL

// --ao-rate half (kEffectAoHalf): the checkerboard half traced this frame; ao_fill.comp fills the
// other, whose 4-neighbours are all in this half.
bool aoHalfRate() { return (frame.effectFlags & (kEffectAo | kEffectAoHalf)) == (kEffectAo | kEffectAoHalf); }
bool aoTurn(ivec2 px) { return ((px.x + px.y + int(frame.frameIndex)) & 1) == 0; }
// The pixel of launch invocation `id`: itself, or at half rate the id.x-th pixel of row id.y on this
// frame's turn (outside the image past the last one of an odd row).
ivec2 aoPixel(uvec2 id) {
  if (!aoHalfRate()) return ivec2(id);
  int y = int(id.y);
  return ivec2(2 * int(id.x) + ((y + int(frame.frameIndex)) & 1), y);
}

bool aoRay(ivec2 px, out vec3 origin, out vec3 dir, out float value) {
  origin = vec3(0.0);
  dir = vec3(0.0, 1.0, 0.0);
  value = 1.0;
  float depth = texelFetch(depthTex, px, 0).r;
  if (isBackground(depth) || (frame.effectFlags & kEffectAo) == 0u) return false;
  vec2 uv = (vec2(px) + 0.5) / vec2(frame.size);
  vec3 p = worldFromDepth(frame.worldFromClip, uv, depth);
  vec4 nn = texelFetch(normalTex, px, 0);
  vec3 n = octDecode(nn.xy), ng = octDecode(nn.zw);
  uint rng = rngInit(uvec2(px), frame.frameIndex, frame.seed ^ kAoStream);
  dir = cosineSampleHemisphere(n, vec2(rnd(rng), rnd(rng)));
  if (dot(dir, ng) <= 0.0) {
    value = 0.0;
    return false;
  }
  origin = p + ng * gbufferRayOffset(frame.worldFromClip, uv, depth, p);
  return true;
}

#endif
