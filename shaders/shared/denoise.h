// Denoiser parameters and push constants shared by C++ and GLSL (docs/style.md §5): the compute passes
// of render/passes/denoise.h and the CPU reference in tests/render/test_denoise.cpp read the same
// numbers. Every tunable is here, with its reason.
#ifndef RAYSTER_SHARED_DENOISE_H
#define RAYSTER_SHARED_DENOISE_H

#include "types.h"  // beside this file, for C++ and glslc alike

#ifdef __cplusplus
namespace rayster::gpu {
#endif

// Flags in the push constants of the temporal passes.
RAYSTER_CONST uint kDenoiseMoving = 1u;  // camera or objects move: αmin, clamping, length cap
RAYSTER_CONST uint kDenoiseReset = 2u;   // camera cut / first frame: ignore every history

// Reprojection (docs/techniques.md §2). A bilinear tap of the previous frame is kept when it shows the
// same id, a normal within ~25° (dot ≥ 0.9, the book ch. 15) and a depth within 1 % of the distance
// plus two pixels' worth of the depth slope (taps lie up to ~1.5 px from the reprojected centre).
RAYSTER_CONST float kReprojectNormalDot = 0.9;
RAYSTER_CONST float kReprojectDepthRelative = 0.01;
RAYSTER_CONST float kReprojectDepthSlopes = 2.0;
// Taps whose bilinear weights sum below this count as no history (avoids dividing by ~0).
RAYSTER_CONST float kReprojectMinWeight = 1.0e-3;

// Shadow temporal (docs/techniques.md §11): α = max(1/(1+n), αmin). Static: αmin = 0, the exact running
// mean; n is kept in fp32, so the cap only bounds it (1/(1+n) stays far above fp32's resolution).
RAYSTER_CONST float kShadowAlphaMinMoving = 0.2;
RAYSTER_CONST float kShadowMaxLength = 65536.0;
// Shadow variance, for the à-trous value weight (as SVGF's luminance weight): visibility samples
// are 0 or 1, so μ2 = μ1 and the per-sample variance is m(1 − m) of the running mean m: no
// moments to store. Below this history length it comes from the 3×3 bilateral mean of the new
// samples instead (one sample is always 0 or 1). Static camera: divided by n, the variance of
// the mean, so a converged hard shadow edge is not blurred. Differences below the epsilon are
// half-float noise, never edges.
RAYSTER_CONST float kShadowMinTemporalVarianceLength = 4.0;
RAYSTER_CONST float kShadowValueEpsilon = 0.01;

// SVGF temporal (docs/techniques.md §14): n = min(n+1, cap), α = max(αmin, 1/n). Moving: cap 32 and
// αmin 0.2 (SVGF paper). Static: α = 1/n, the exact running mean, up to the large cap.
RAYSTER_CONST float kSvgfMaxLengthMoving = 32.0;
RAYSTER_CONST float kSvgfMaxLengthStatic = 65536.0;
RAYSTER_CONST float kSvgfAlphaMinMoving = 0.2;
// Below this history length the variance comes from a 7×7 bilateral estimate (SVGF paper).
RAYSTER_CONST float kSvgfMinTemporalVarianceLength = 4.0;
RAYSTER_CONST int kSvgfVarianceRadius = 3;
// The working images are RGBA16F: a variance above half's range would turn into Inf, then NaN.
RAYSTER_CONST float kSvgfMaxVariance = 65000.0;

// À-trous edge-stopping weights (SVGF paper; the book's code has the same defaults).
RAYSTER_CONST float kSigmaDepth = 1.0;
RAYSTER_CONST float kSigmaNormal = 128.0;
RAYSTER_CONST int kSigmaNormalLog2 = 7;  // the à-trous loops square 7 times (lib/denoise.glsl)
RAYSTER_CONST float kSigmaLuminance = 4.0;
RAYSTER_CONST float kDepthEpsilon = 1.0e-4;      // keeps w_z finite on planes facing the camera
RAYSTER_CONST float kLuminanceEpsilon = 1.0e-6;  // keeps w_l finite where the variance is 0
// The shadow denoiser's layers per invocation: one per shadowed light plus the AO layer (the hybrid
// denoises AO as one more visibility layer: one guide fetch per tap serves all of them).
RAYSTER_CONST uint kMaxShadowDenoiseLayers = kMaxShadowLights + 1u;
RAYSTER_CONST uint kShadowAtrousIterations = 3u;  // steps 1, 2, 4 (FidelityFX shadow denoiser)
RAYSTER_CONST uint kSvgfAtrousIterations = 5u;    // steps 1 .. 16 (SVGF paper)
// Mirrors and glass (perceptual roughness ≤ this) keep their sharp reflections: the spatial filter
// skips them and never takes them as neighbours of rougher pixels; only temporal accumulation
// applies (their traced radiance is nearly noise-free anyway: one deterministic bounce path).
// Half a step of the RGBA8 material target above 0.05: a roughness of exactly 0.05 (the chrome of
// the Whitted scene) is stored as 13/255 = 0.051.
RAYSTER_CONST float kSharpRoughness = 0.05 + 0.5 / 255.0;

struct SurfacePush {
  uvec2 size;
  float zNear;  // the camera's planes: reversed-Z depth d gives z = n·f / (n + d·(f − n))
  float zFar;
};

struct TemporalPush {
  uvec2 size;
  uint layers;         // shadow: visibility layers (lights); SVGF: unused
  uint flags;          // kDenoise* bits
  float historyScale;  // SVGF: the exposure ratio (FrameConstants::exposureRatio) the radiance history is read × by
  uint pad;
};

struct AtrousPush {
  uvec2 size;
  uint layers;  // shadow: visibility layers; SVGF: unused
  uint step;    // 1, 2, 4, ...: taps at p + step·(i, j)
  uint pad3;
  uint pad0;
  uint pad1;
  uint pad2;
};

#ifdef __cplusplus
static_assert(sizeof(SurfacePush) == 16);
static_assert(sizeof(TemporalPush) == 24);
static_assert(sizeof(AtrousPush) == 32);
static_assert(kSigmaNormal == float(1 << kSigmaNormalLog2), "the à-trous normal weight squares kSigmaNormalLog2 times");
}  // namespace rayster::gpu
#endif

#endif
