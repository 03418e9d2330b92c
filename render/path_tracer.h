#pragma once
// The reference renderer (--mode pathtrace, docs/architecture.md §4): progressive path tracing of the same
// GPU scene, materials, lights, environment and camera as the hybrid frame, one sample per pixel
// per frame, accumulated in fp32. Deterministic: the seed and the sample count fix the image.
// The image is the accumulated mean (no TAA); the "variance" AOV is the per-pixel variance of
// that mean (sample variance / samples).
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "render/renderer.h"
#include "rhi/rt_pipeline.h"

namespace rayster::rhi {
class Buffer;
class CommandList;
class PipelineLibrary;
class Sampler;
class TimestampPool;
}  // namespace rayster::rhi

namespace rayster::graph {
class HistoryStore;
class TransientPool;
}  // namespace rayster::graph

namespace rayster::render {

struct GpuScene;

// What the path tracer borrows from the renderer for a render.
struct PathTraceResources {
  rhi::Context& ctx;
  GpuScene& scene;
  rhi::PipelineLibrary& pipelines;
  const rhi::Buffer& constants;
  const rhi::Sampler& nearest;
  const rhi::Sampler& linear;
  graph::TransientPool& transients;
  graph::HistoryStore& histories;  // the running means: "pt-mean", "pt-moments"
  rhi::CommandList& commands;
  rhi::TimestampPool& timers;
};

class PathTracer {
 public:
  // `writeConstants(f)` fills the FrameConstants of sample f (frameIndex f, no jitter), with the
  // (pre-)exposure `exposure` that the HDR outputs are divided back by.
  Result<RenderOutput> render(const RenderSettings& s, const PathTraceResources& r, float exposure,
                              const std::function<void(uint32_t)>& writeConstants);
};

// Per-pass GPU time statistics (median, min, p95, the samples) from each frame's timings, in
// first-seen order, with what each pass declared (`infos`); adds each frame pass's median (not the
// raw-rate twins') to out.frameMedianMs (render/renderer_output.cpp).
void summarisePasses(const std::vector<std::string>& order, const std::map<std::string, std::vector<double>>& times,
                     const std::map<std::string, graph::PassInfo>& infos, RenderOutput& out);

// Divides an image of pre-exposed light (lib/frame.glsl) by the exposure, back to the scene's units:
// HDR outputs do not depend on --exposure.
void unexpose(ImageF& image, float exposure);

}  // namespace rayster::render
