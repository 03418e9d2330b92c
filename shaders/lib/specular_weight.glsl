// Which surfaces the specular pass traces (docs/techniques.md §12, §13): shared by the lighting pass
// (lib/shading.glsl), the specular pass, its half-rate fill and its raw-rate twin. Needs lib/frame.glsl.
#ifndef RAYSTER_SPECULAR_WEIGHT_GLSL
#define RAYSTER_SPECULAR_WEIGHT_GLSL

// Hits of the bounce loop this smooth, and all transmissive ones, continue the specular path;
// rougher hits end it, shaded here.
const float kMirrorRoughness = 0.1;
// First surfaces rougher than FrameConstants::glossyThreshold fade from traced glossy reflections to
// the environment approximation over kGlossyBlend (shared/types.h), so no seam shows (docs/techniques.md §13).

bool tracedSpecular(float roughness, float transmission) {
  return roughness <= kMirrorRoughness || transmission > 0.0;
}

// How much of a G-buffer surface's specular light the specular pass traces (mirror, glass, glossy:
// 1; past the glossy threshold it fades to 0; 0 everywhere with --reflections off); the rest comes from light sources and the
// environment approximation.
float tracedSpecularWeight(float roughness, float transmission) {
  if ((frame.effectFlags & kEffectReflections) == 0u) return 0.0;  // --reflections off: nothing is traced
  if (transmission > 0.0 || roughness <= frame.mirrorRoughness) return 1.0;
  return 1.0 - clamp((roughness - frame.glossyThreshold) / kGlossyBlend, 0.0, 1.0);
}

// Glossy first reflections at least kHalfRateRoughness rough (shared/types.h) are traced on half
// the pixels each frame, in a checkerboard that alternates with the frame (docs/techniques.md §13);
// the specular fill pass gives the other half the mean of their traced neighbours. Their lobe
// already blurs the reflection over more than the pixel's footprint at the distances that matter,
// and SVGF's temporal accumulation sees every pixel traced every other frame. Smoother lobes (and
// mirrors, glass) trace at every pixel.

// A G-buffer surface whose glossy reflection is traced at half rate.
bool halfRateGlossy(float depth, vec4 mat) {
  return !isBackground(depth) && mat.b <= 0.0 && mat.r > max(frame.mirrorRoughness, kHalfRateRoughness) &&
         tracedSpecularWeight(mat.r, mat.b) > 0.0;
}

// This frame's half of the checkerboard.
bool halfRateTurn(ivec2 px) { return ((px.x + px.y + int(frame.frameIndex)) & 1) == 0; }

// The specular image's alpha at a pixel whose glossy ray waits for the fill pass (exact in fp16).
const float kHalfRateSkipped = 0.5;

#endif
