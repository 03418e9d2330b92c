#pragma once
// The denoisers of the hybrid frame (docs/architecture.md §3, passes 3 and 5): reusable compute passes over
// the G-buffer, with temporal history in the caller's graph histories (RenderGraph::history).
//   writeSurface       the denoisers' compact view of the G-buffer (kept a frame longer)
//   denoiseShadows     per-light visibility: temporal running mean + 3 à-trous iterations (docs/techniques.md §11)
//   denoiseRadiance    SVGF for a radiance signal (reflections; later indirect diffuse) (docs/techniques.md §14)
// Each is also available step by step (the tests compare every kernel with a CPU reference).
// Parameters and push constants: shaders/shared/denoise.h. Pass names carry the à-trous step
// ("shadow-atrous-2"), so per-pass timings keep the iterations apart.
//
// Cost: every pass is 8×8 workgroups of texelFetch from L1/L2-resident neighbourhoods, so each
// is bound by its fetches per pixel; the guide every tap reads is 8 B (an RG32UI surface texel,
// one full-rate fetch) and also carries SVGF's sharp flag. Shadows: temporal (reprojection once per
// pixel, all layers in one invocation) + 3 à-trous (geometry weights once per tap for all layers)
// = 4 dispatches; the hybrid gives AO as one more layer, so lights and AO share these 4 (8 before).
// SVGF: temporal with the variance estimate + 5 à-trous = 6 dispatches (7 before the variance pass
// was folded into the temporal one); its à-trous tile loads guide + signal per texel (2; the
// material image was a third before the sharp flag moved into the guide). Measured on an H200 at 1080p before
// these changes (16 B guide, separate variance pass, AO its own shadow-denoiser run): 0.79 ms a
// shadow denoiser, 0.79 ms the AO one, 0.73–0.97 ms an SVGF.
#include <string>

#include <volk.h>

#include "graph/graph.h"
#include "rhi/pipeline_library.h"

namespace rayster::render {

// Surface texel: linear view depth (float bits; 0 for sky), oct shading normal (2 × snorm10) and
// the id's low 12 bits. 8 B/px; the depth slope is recomputed from the neighbours by its readers.
// See shaders/lib/denoise.glsl for the precision each field needs.
inline constexpr VkFormat kSurfaceFormat = VK_FORMAT_R32G32_UINT;
// Shadow history: layers 0..L−1 the running mean per light, layer L the history length n. fp32:
// the static running mean is exact (1/(1+n) steps far above the ulp; 16 bits freeze it, docs/techniques.md §11).
inline constexpr VkFormat kShadowHistoryFormat = VK_FORMAT_R32_SFLOAT;
inline constexpr VkFormat kShadowDenoisedFormat = VK_FORMAT_R16_SFLOAT;  // per light, for lighting
// SVGF: colour history (rgb the running mean, a the history length n; fp32: the static exact
// running mean, and n exact up to its cap), moments history (μ1, μ2; fp32: μ2 − μ1² cancels, and
// μ2 of bright pixels overflows half floats), working images rgb colour + a variance.
inline constexpr VkFormat kSvgfColorHistoryFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kSvgfMomentsHistoryFormat = VK_FORMAT_R32G32_SFLOAT;
inline constexpr VkFormat kSvgfWorkingFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

// Image descriptions for the caller's histories (RenderGraph::history).
rhi::ImageDesc surfaceDesc(VkExtent2D size);
rhi::ImageDesc shadowHistoryDesc(VkExtent2D size, uint32_t lights);
rhi::ImageDesc svgfColorHistoryDesc(VkExtent2D size);
rhi::ImageDesc svgfMomentsHistoryDesc(VkExtent2D size);

// Layer counts up to this use the small shadow à-trous pipeline (shadow_atrous_2.comp, a variant of
// shaders/shadow_atrous.comp.glsl).
inline constexpr uint32_t kShadowAtrousSmallLayers = 2;

// What every denoise pass needs besides its images (no scene, so tests can run them alone);
// copied into the passes, so a temporary will do.
struct DenoiseInputs {
  rhi::PipelineLibrary& pipelines;  // the passes create their compute pipelines on first use
  VkSampler nearest;                // inputs are read with texelFetch only
  VkExtent2D size;
};

// What happened since the previous frame.
struct TemporalState {
  bool moving = false;  // camera or objects moved: αmin 0.2, clamping, capped history (docs/techniques.md §11, §14)
  bool reset = false;   // first frame of a run or a camera cut: every history is dropped
  // Radiance histories: this frame's exposure over the one they were written at (render/exposure.h).
  float historyScale = 1.0f;
};

struct SurfacePair {
  graph::ImageHandle current, previous;  // kSurfaceFormat, this frame's and the last frame's
};
struct HistoryPair {
  graph::ImageHandle previous, next;  // read, written (never the same image)
};

// A. The surface image from the G-buffer (depth D32 or R32F reversed Z, normals, id, material: .r
// perceptual roughness, ≤ kSharpRoughness marks the texel sharp for SVGF), written into `out`
// (kSurfaceFormat, usually a history's next image). zNear/zFar: the camera's planes.
graph::ImageHandle writeSurface(graph::RenderGraph& graph, const DenoiseInputs& in, graph::ImageHandle depth,
                                graph::ImageHandle normals, graph::ImageHandle id, graph::ImageHandle material,
                                graph::ImageHandle out, float zNear, float zFar);

// C. Shadow denoiser, also for AO (any 0/1 visibility). raw: R16F array, one layer per light (the
// hybrid adds AO as the last layer; at most gpu::kMaxShadowDenoiseLayers); history:
// shadowHistoryDesc images. name: prefix of its passes and images.
struct ShadowDenoised {
  graph::ImageHandle temporal;  // = history.next (running means; layer L holds n)
  graph::ImageHandle variance;  // R16F array: per-light variance for the à-trous value weight
  graph::ImageHandle denoised;  // R16F array, one layer per light
};
ShadowDenoised denoiseShadows(graph::RenderGraph& graph, const DenoiseInputs& in, SurfacePair surface,
                              graph::ImageHandle motion, graph::ImageHandle raw, HistoryPair history,
                              TemporalState state, const std::string& name = "shadow");
// The temporal step alone: fills .temporal and .variance.
ShadowDenoised shadowTemporal(graph::RenderGraph& graph, const DenoiseInputs& in, SurfacePair surface,
                              graph::ImageHandle motion, graph::ImageHandle raw, HistoryPair history, uint32_t lights,
                              TemporalState state, const std::string& name = "shadow");
// One à-trous iteration over the first `lights` layers of `input`, into `output` (returned), an
// image from createShadowImage; ping-pong between two of them, never in place.
graph::ImageHandle createShadowImage(graph::RenderGraph& graph, VkExtent2D size, uint32_t lights,
                                     const std::string& name);
graph::ImageHandle shadowAtrous(graph::RenderGraph& graph, const DenoiseInputs& in, graph::ImageHandle surface,
                                graph::ImageHandle input, graph::ImageHandle variance, graph::ImageHandle output,
                                uint32_t lights, uint32_t step, const std::string& name = "shadow");

// D. SVGF for a radiance signal (RGBA16F). name: prefix of its passes and images ("reflection").
// Sharp surface texels (mirrors, glass: writeSurface's material test) stay unfiltered.
struct RadianceDenoised {
  graph::ImageHandle temporal;  // = color.next after the temporal pass (rgb the running mean when static, a n)
  graph::ImageHandle moments;   // = moments.next (μ1, μ2)
  graph::ImageHandle variance;  // working image after the temporal pass (rgb colour, a variance); à-trous
                                // iterations 2 and 4 reuse it, so it holds iteration 4's output at the end
  graph::ImageHandle denoised;  // RGBA16F, rgb denoised radiance (a: its variance)
};
RadianceDenoised denoiseRadiance(graph::RenderGraph& graph, const DenoiseInputs& in, const std::string& name,
                                 SurfacePair surface, graph::ImageHandle motion, graph::ImageHandle raw,
                                 HistoryPair color, HistoryPair moments, TemporalState state);
// The temporal pass with the variance estimate: writes color.next, moments.next and `out` (an
// image from createSvgfImage: rgb colour, a variance; returned).
graph::ImageHandle svgfTemporal(graph::RenderGraph& graph, const DenoiseInputs& in, const std::string& name,
                                SurfacePair surface, graph::ImageHandle motion, graph::ImageHandle raw,
                                HistoryPair color, HistoryPair moments, graph::ImageHandle out, TemporalState state);
// One iteration from `input` into `output` (returned; both from createSvgfImage, never the same);
// a valid `history` receives the output too (iteration 1 while moving).
graph::ImageHandle createSvgfImage(graph::RenderGraph& graph, VkExtent2D size, const std::string& name);
graph::ImageHandle svgfAtrous(graph::RenderGraph& graph, const DenoiseInputs& in, const std::string& name,
                              graph::ImageHandle surface, graph::ImageHandle input, graph::ImageHandle output,
                              uint32_t step, graph::ImageHandle history = {});

}  // namespace rayster::render
