#pragma once
// The passes of the hybrid frame (docs/architecture.md §3), one file each: functions from graph inputs to
// graph outputs. A pass declares what it reads and writes; the graph places the barriers.
#include <array>
#include <cstdint>
#include <string>

#include <volk.h>

#include "graph/graph.h"
#include "render/tonemap_curves.h"
#include "shaders/shared/probes.h"

namespace rayster::rhi {
class Buffer;
class PipelineLibrary;
class Sampler;
}  // namespace rayster::rhi

namespace rayster::render {

struct GpuScene;
struct RenderSettings;

// Graph image tags (graph::RenderGraph::createImage): the image holds pre-exposed light
// (lib/frame.glsl), which an AOV of it divides back to the scene's units.
inline constexpr uint32_t kRadianceImage = 1u;

// What every pass may use: immutable for the whole frame. The graph binds the frame constants
// ("FrameBlock"), the bindless textures (set 1) and the nearest sampler (the default for sampled
// images) wherever a pass's shaders declare them (beginFrameGraph).
struct FrameInputs {
  rhi::PipelineLibrary& pipelines;  // each pass creates its pipelines here on first use
  const GpuScene& scene;
  const rhi::Buffer& constants;  // FrameConstants, written by the host before submission
  const rhi::Sampler& nearest;
  const rhi::Sampler& linear;  // clamp to edge: filtered history fetches (TAA)
  VkExtent2D size;
  graph::AccelHandle tlas;  // the scene's TLAS (invalid without ray tracing): bind("tlas", in.tlas)
};

// Gives a frame's graph its globals (RenderGraph::setGlobals) and, on devices with ray tracing,
// imports the scene's TLAS; returns the TLAS handle for FrameInputs::tlas.
graph::AccelHandle beginFrameGraph(graph::RenderGraph& graph, GpuScene& scene, const rhi::Buffer& constants,
                                   const rhi::Sampler& nearest);
// TLAS refit or rebuild as the graph pass "tlas-update", which writes in.tlas: every ray-tracing
// pass after it waits for the build through the barriers the graph derives. Call before the passes
// that trace (the instances were written by Tlas::prepare).
void updateTlas(graph::RenderGraph& graph, const FrameInputs& in, bool refit);

struct GBuffer;
// Binds the G-buffer images a shading pass reads under their usual GLSL names (depthTex, normalTex,
// albedoTex, materialTex, emissiveTex, specularGbufTex, layersTex).
void bindSurface(graph::PassBuilder& b, const GBuffer& gb);

struct GBuffer {
  graph::ImageHandle depth;     // D32 (raster) or R32F (traced): sample .r either way
  graph::ImageHandle normals;   // RGBA16_SNORM: oct shading normal, oct geometric normal
  graph::ImageHandle albedo;    // RGBA8: sRGB-encoded base colour
  graph::ImageHandle material;  // RGBA8: roughness, metallic, transmission, flags
  graph::ImageHandle emissive;  // RGBA16F: emitted radiance; .a the exact ior
  // RGBA8: the dielectric lobe of KHR_materials_specular, encodeSpecular(F0 tint, strength)
  // (lib/common.glsl); with .a of `emissive` it gives F0 and F90 (lib/brdf.glsl).
  graph::ImageHandle specular;
  // RGBA32_UINT: clear coat (normal, factor, roughness) and sheen (colour, roughness), encodeLayers()
  // (lib/common.glsl); zero where a material has neither.
  graph::ImageHandle layers;
  // No material has a coat or sheen: `layers` is the caller's one-texel zero image, written by no pass.
  bool flatLayers = false;
  graph::ImageHandle id;  // R32_UINT instance row, kBackgroundId for sky
  // RG16F uvCurrent − uvPrevious (unjittered; docs/techniques.md §2): the history of a pixel is at
  // uv − motion. Camera and object motion for geometry; 0 on the background, whose (camera)
  // motion lib/motion.glsl computes from the matrices.
  graph::ImageHandle motion;
};

// zeroLayers (optional): a one-texel RGBA32UI image of zeros (NeutralImages::layers) that stands in
// for the layers target when no material of the scene has a clear coat or sheen.
GBuffer rasterGBuffer(graph::RenderGraph& graph, const FrameInputs& in, graph::ImageHandle zeroLayers = {});
GBuffer traceGBuffer(graph::RenderGraph& graph, const FrameInputs& in, graph::ImageHandle zeroLayers = {});

// One visibility layer per shadowed light (R16F array), 1 sample per pixel, and `extraLayers` more
// that other passes fill (the AO layer: traceAo into this image), so one denoiser run takes them all.
graph::ImageHandle traceShadows(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb, uint32_t lights,
                                uint32_t extraLayers = 0);

// Raw-rate twins (RenderSettings::rawRays, passes "raw-gbuffer-traced" and "raw-rt-shadows"): the
// rays of the traced G-buffer and of traceShadows() with trivial hit/miss shaders (raw_rays.cpp).
void traceRawPrimary(graph::RenderGraph& graph, const FrameInputs& in);
void traceRawShadows(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb, uint32_t lights);
// The raw-rate twins of rt-ao, rt-direct (many-light mode only), rt-indirect and rt-specular
// ("raw-rt-ao", ...; raw_rays.cpp says what each replays). Their R16F images mark what the rays did
// (AOVs "raw-ao", "raw-direct", "raw-indirect", "raw-specular"); `direct` is invalid without many lights.
struct RawTwinImages {
  graph::ImageHandle ao, direct, indirect, specular;
};
// The twins of the effects that record a pass this frame (AO on, many-light direct light, indirect
// on, specular surfaces in the scene).
struct RawTwinEffects {
  bool ao, direct, indirect, specular;
};
// `indirectQuarter`, `aoHalf`: as traceIndirect's `quarter` and traceAo's `half` (the twins launch
// the same grids).
RawTwinImages traceRawTwins(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb, RawTwinEffects effects,
                            bool indirectQuarter, bool aoHalf, uint32_t lightsPerHit);
// Denoised by denoiseShadows() (render/passes/denoise.h).

// Where the probe cascades' windows were at the last update (render/passes/gi_probes.cpp): the
// renderer keeps it across frames, so that a window that scrolls with the camera resets only the
// probes that entered it.
struct ProbeCascadeState {
  uint32_t cascades = 0;                                   // 0: no update yet
  std::array<uint32_t, gpu::kMaxProbeCascades> windows{};  // cascadeCells[k].x's cells (bits 0..23)
};
// What the probe passes need to know of the frame (render/passes/gi_probes.cpp).
struct ProbeFrame {
  uint32_t index = 0, seed = 0;        // the frame's number and the run's seed: the rays' random rotation
  float historyScale = 1.0f;           // the exposure ratio the previous atlases are read × by
  bool moving = false;                 // the camera or an object moves: lower hysteresis, to follow it
  glm::vec3 eye{0.0f};                 // the camera's position: the finer cascades are centred on it
  uint32_t cascades = 0;               // --probe-cascades: 1..4, 0 auto (probeCascadesSetting())
  ProbeCascadeState* state = nullptr;  // the renderer's, updated by traceProbeIrradiance()
};
// Probes in the grid's atlases: per cascade × cascades.
uint32_t probeCount(const gpu::ProbeGrid& grid);
// --probe-cascades of the settings: 0 for auto, else the number asked for.
uint32_t probeCascadesSetting(const RenderSettings& settings);
// The probe grid fitted to the scene's bounds with `cascades` cascades (0: as many as bring the
// finest spacing to 2.5 m, at most kMaxProbeCascades), the finer windows centred on `eye` and kept
// inside the coarsest one; cascadeCells hold the windows (none moved).
// An invalid box (min > max) stands for the unit cube.
gpu::ProbeGrid fitProbeGrid(glm::vec3 boundsMin, glm::vec3 boundsMax, glm::vec3 eye, uint32_t cascades);
// Reflections and refractions of mirror, metal and glass pixels (RGBA16F radiance, 0 elsewhere).
// `bounces` (FrameConstants::maxSpecularBounces) and `lightsPerHit` only count its rays (PassInfo::rays).
// Irradiance probes (render/passes/gi_probes.cpp, --gi probes): this frame's atlases and grid, for
// passes that light their hits from the probes (the reflection bounce loop).
struct ProbeLookup {
  graph::ImageHandle irradiance, visibility, data;  // invalid: no probes
  gpu::ProbeGrid grid{};                            // flags has kProbeLookup when valid
  graph::ImageHandle specularIrradiance;            // E about each G-buffer pixel's mirror direction
};
// The queue of specular paths that go on after their first segment (shaders/specular.rgen.glsl
// SPECULAR_QUEUE): the renderer keeps its buffers across frames; traceSpecular() sizes them.
struct SpecularQueue {
  rhi::Context* ctx = nullptr;
  rhi::Buffer paths;   // gpu::kSpecularQueuePathWords words per path, one path per kSpecularQueueDivisor pixels
  rhi::Buffer length;  // VkTraceRaysIndirectCommandKHR {paths queued, 1, 1}: the continuation's launch
  graph::ResourceState pathsState, lengthState;
  uint64_t pixels = 0;  // the frame size the buffers are for
};
// Whether the frame compacts its specular paths: --specular-queue on, and a device that can run the
// queue at this size (indirect ray launches; pixel indices that fit a path's tag).
bool useSpecularQueue(const rhi::Context& ctx, const RenderSettings& settings, VkExtent2D size);
// `probes`: the probes light the diffuse part of the loop's hits (else ambient and the SH environment).
// `halfRateFill`: some surface is glossy enough to be traced at half rate, so "rt-specular-fill"
// fills the untraced half (false: no surface is, and the fill is not recorded).
// `queue`: compact the paths that go on into it ("rt-specular-continue"); null: every pixel's loop
// runs in its own invocation of "rt-specular" (devices without indirect launches). The image is the
// same either way.
graph::ImageHandle traceSpecular(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb, uint32_t bounces,
                                 uint32_t lightsPerHit, bool halfRateFill, const ProbeLookup& probes = {},
                                 SpecularQueue* queue = nullptr);
// Denoised by denoiseRadiance() (render/passes/denoise.h).

// Ambient occlusion (R16F array, 1 unoccluded), 1 sample per pixel; 1 everywhere when
// FrameConstants::effectFlags lacks kEffectAo. Written into layer FrameConstants::aoLayer of
// `into` (the shadow visibility image, whose denoiser then takes AO as its last layer; returned),
// or without it into a new one-layer image ("ao-raw"; aoLayer must be 0 then).
// `half` (--ao-rate half; FrameConstants::effectFlags has kEffectAo | kEffectAoHalf): one pixel of
// each checkerboard pair traced per frame (a half-width launch), the others filled by "rt-ao-fill".
graph::ImageHandle traceAo(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                           graph::ImageHandle into = {}, bool half = false);
// --ao-rate: whether AO traces half the pixels per frame; rt-ao's launch for it.
bool aoHalfRate(const RenderSettings& settings);
VkExtent2D aoLaunchSize(VkExtent2D size, bool half);
// One-bounce indirect diffuse irradiance E (RGBA16F, demodulated), 1 sample per pixel; 0 when
// FrameConstants::effectFlags lacks kEffectIndirect. `quarter` (FrameConstants::effectFlags has
// kEffectIndirect | kEffectIndirectQuarter): one traced pixel per 2×2 block ((w+1)/2 × (h+1)/2
// launch), the rest filled by "rt-indirect-fill" guided by `surface` (the denoisers' surface image).
// `probes` (valid with --gi path too): the bounce's hits take the probes' irradiance for their
// diffuse light, so the one denoised bounce carries the later bounces as well.
graph::ImageHandle traceIndirect(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                                 graph::ImageHandle surface, bool quarter, const ProbeLookup& probes);
// rt-indirect's launch: the image, or at quarter rate one invocation per 2×2 block; and its size in invocations.
VkExtent2D indirectLaunchSize(VkExtent2D size, bool quarter);
uint64_t indirectLaunch(VkExtent2D size, bool quarter);

// Many lights: direct light from one importance-picked light per pixel, with its shadow ray
// (RGBA16F radiance).
graph::ImageHandle traceDirect(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb);

// The path tracer (render/path_tracer.h): one sample per pixel folded into fp32 running means of
// the radiance and its square (RGBA32F; moments .a = samples). `previous*` are read only after the
// first frame.
struct PathAccumulation {
  graph::ImageHandle previousMean, previousMoments;
  graph::ImageHandle mean, moments;
};
graph::ImageHandle tracePaths(graph::RenderGraph& graph, const FrameInputs& in, const PathAccumulation& acc);

// What the lighting pass combines with the G-buffer.
struct LightingInputs {
  graph::ImageHandle visibility;        // shadow layers (R16F array)
  graph::ImageHandle specular;          // traced reflections/refractions (RGBA16F)
  graph::ImageHandle ao;                // RT ambient occlusion (R16F array, one layer)
  graph::ImageHandle indirect;          // one-bounce indirect irradiance E (RGBA16F)
  graph::ImageHandle direct;            // many-light direct radiance; invalid when every light has a layer
  graph::ImageHandle indirectSpecular;  // probes: E about the mirror direction (kEffectIndirectSpecular)
};
// `name`: the pass's name; its output image is "hdr" for "lighting", else "<name>-hdr" (the raster
// mode lights twice: a first image for screen-space reflections to read, then the final one).
graph::ImageHandle shadeLighting(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                                 const LightingInputs& inputs, const std::string& name = "lighting");
// TAA resolve: blends `current` with the reprojected `history` and writes `next` (the output).
inline constexpr float kTaaCurrentWeight = 0.1f;  // steady-state weight of the current frame (the book)
struct TaaInputs {
  graph::ImageHandle current;  // linear HDR (RGBA16F)
  graph::ImageHandle depth;    // G-buffer depth, for the closest texel and camera motion
  graph::ImageHandle history;  // previous output; read only when historyFrames > 0
  graph::ImageHandle next;     // RGBA16F, storage + sampled
  graph::ImageHandle motion;   // optional RG16F uvCur − uvPrev; without it: camera motion from depth
  uint32_t historyFrames = 0;  // frames in the history since the last reset; 0: output current
  // Frames in a row (this one included) in which neither the camera nor any instance moved: a still
  // view. The history is then a running mean (no anti-firefly weights, no clip), so the image
  // converges to the supersampled mean instead of one biased towards dark samples.
  uint32_t stillFrames = 0;
};
// A still view's running mean counts at most this many frames (then an exponential mean of that
// window): the fp16 history would stop taking smaller steps.
inline constexpr uint32_t kTaaMaxStillFrames = 256;
graph::ImageHandle resolveTaa(graph::RenderGraph& graph, const FrameInputs& in, const TaaInputs& taa);

// The HDR input is already exposed (sources are pre-exposed, lib/frame.glsl): no exposure here.
struct ToneSettings {
  Tonemapper op = Tonemapper::Aces;
  uint32_t seed = 0;   // of the ±0.5 LSB dither
  bool dither = true;  // off only where tests compare exact 8-bit values
};
graph::ImageHandle tonemap(graph::RenderGraph& graph, const FrameInputs& in, graph::ImageHandle hdr,
                           const ToneSettings& tone);
// Copies an image into a host-visible buffer and makes it visible to the host.
void readback(graph::RenderGraph& graph, graph::ImageHandle image, graph::BufferHandle buffer);
// Makes what earlier passes copied into the host-visible `buffer` visible to the host, which reads
// it after the frame's timeline value (a pass named `name`, never culled).
void makeHostVisible(graph::RenderGraph& graph, const char* name, graph::BufferHandle buffer);

// Auto exposure's meter (render/passes/exposure.cpp): the luminance histograms of `hdr` (rendered at
// pre-exposure `exposure`) into `histogram` (shared/exposure.h: surfaces, normalised by the
// G-buffer's albedo, and background; cleared first), copied into the host-visible `readback` for the
// host's ExposureControl (render/exposure.h).
void meterExposure(graph::RenderGraph& graph, const FrameInputs& in, graph::ImageHandle hdr, const GBuffer& gb,
                   float exposure, graph::BufferHandle histogram, graph::BufferHandle readback);

}  // namespace rayster::render
