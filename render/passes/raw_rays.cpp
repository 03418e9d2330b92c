// Raw ray rates (rayster bench --raw-rays): the rays of the frame's ray-traced passes traced again
// with trivial shaders into scratch images, so each pass can report the share of the device's raw
// ray rate it reaches (its rays are the same; only shading and memory traffic differ). Exact
// replays: primary, shadow, AO and many-light direct rays, the indirect bounce ray and the specular
// path's first ray. Approximate: the shadow rays at those bounce hits (the twins know only the hit
// distance, not the hit's normal) and, for specular, no deeper bounces (specular.rgen's RAW_RATE variant). At
// quarter-rate indirect, raw-rt-indirect launches rt-indirect's quarter-size grid. Each twin's
// raygen is the RAW_RATE variant of its pass's shader (cmake/shaders.cmake).
#include <utility>
#include <vector>

#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

namespace {
// Results nobody reads: a side effect keeps the graph from culling the pass.
constexpr VkImageUsageFlags kScratchUsage = VK_IMAGE_USAGE_STORAGE_BIT;

// Opaque twins: no alpha any-hit. Shadow-like rays need no closest hit; bounce rays (indirect,
// specular) a closest hit that returns t and a miss that leaves the payload, shadow rays miss 1.
const rhi::RayTracingPipeline& twinPipeline(rhi::PipelineLibrary& lib, const char* raygen) {
  return lib.rayTracing(raygen, [raygen] {
    const std::string_view r = raygen;
    rhi::RayTracingPipelineDesc d;
    d.raygen = raygen;
    if (r == "raw_primary.rgen") {
      d.miss = {"shadow.rmiss"};  // marks the payload; any trivial miss would do
      d.hitGroups = {{"raw.rchit", "alpha.rahit", ""}, {"raw.rchit", "", "sphere.rint"}};
    } else if (r == "raw_indirect.rgen" || r == "raw_specular.rgen") {
      d.miss = {"raw.rmiss", "shadow.rmiss"};
      d.hitGroups = {{"raw_t.rchit", "", ""}, {"raw_t.rchit", "", "sphere.rint"}};
    } else {
      d.miss = {"shadow.rmiss"};
      d.hitGroups = {{"", "", ""}, {"", "", "sphere.rint"}};
    }
    return d;
  });
}

using Reads = std::vector<std::pair<const char*, graph::ImageHandle>>;

// One twin: a launch of the twin shader reading G-buffer images by name and writing one R16F image
// (readable as an AOV, for the tests that compare it with its pass) as `output`. `twinOf` names the
// pass it replays; `rays` its launched rays.
graph::ImageHandle traceTwin(graph::RenderGraph& graph, const FrameInputs& in, const char* pass, const char* twinOf,
                             uint64_t rays, const char* image, const Reads& reads, const char* output,
                             const char* raygen, VkExtent2D launch) {
  graph::ImageHandle out = graph.createImage(
      image, {kVisibilityFormat, in.size.width, in.size.height, 1, kScratchUsage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
      0u);  // hit counts and fractions, not light: never divided by the exposure
  const rhi::RayTracingPipeline& pipe = twinPipeline(in.pipelines, raygen);
  graph.addPass(
      pass,
      [&](graph::PassBuilder& b) {
        b.pipeline(pipe).bind("tlas", in.tlas);
        for (const auto& [name, h] : reads) b.bind(name, h);
        b.bind(output, out);
        b.sideEffect();
        b.twinOf(twinOf);
        b.rays(rays);
      },
      [&pipe, launch](graph::PassContext& pc) { pipe.trace(pc.cmd, launch.width, launch.height); });
  return out;
}
}  // namespace

void traceRawPrimary(graph::RenderGraph& graph, const FrameInputs& in) {
  graph::ImageHandle hit =
      graph.createImage("raw-primary-hit", {kVisibilityFormat, in.size.width, in.size.height, 1, kScratchUsage});
  const rhi::RayTracingPipeline& pipe = twinPipeline(in.pipelines, "raw_primary.rgen");
  graph.addPass(
      "raw-gbuffer-traced",
      [&](graph::PassBuilder& b) {
        b.pipeline(pipe).bind("tlas", in.tlas).bind("outHit", hit);
        b.sideEffect();
        b.twinOf("gbuffer-traced");
        b.rays(uint64_t(in.size.width) * in.size.height, true);
      },
      [&pipe, size = in.size](graph::PassContext& pc) { pipe.trace(pc.cmd, size.width, size.height); });
}

void traceRawShadows(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb, uint32_t lights) {
  if (lights == 0) return;  // many-light mode: the shadow pass traces nothing either
  graph::ImageHandle vis = graph.createImage(
      "raw-shadow-visibility", {kVisibilityFormat, in.size.width, in.size.height, lights, kScratchUsage, true});
  const rhi::RayTracingPipeline& pipe = twinPipeline(in.pipelines, "raw_shadows.rgen");
  graph.addPass(
      "raw-rt-shadows",
      [&](graph::PassBuilder& b) {
        b.pipeline(pipe).bind("tlas", in.tlas).bind("depthTex", gb.depth).bind("normalTex", gb.normals);
        b.bind("outVisibility", vis);
        b.sideEffect();
        b.twinOf("rt-shadows");
        b.rays(uint64_t(in.size.width) * in.size.height * lights);
      },
      [&pipe, lights, size = in.size](graph::PassContext& pc) { pipe.trace(pc.cmd, size.width, size.height, lights); });
}

RawTwinImages traceRawTwins(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb, RawTwinEffects effects,
                            bool indirectQuarter, bool aoHalf, uint32_t lightsPerHit) {
  RawTwinImages t;
  const uint64_t pixels = uint64_t(in.size.width) * in.size.height;
  const Reads surface = {{"depthTex", gb.depth}, {"normalTex", gb.normals}};
  if (effects.ao) {
    const VkExtent2D launch = aoLaunchSize(in.size, aoHalf);
    t.ao = traceTwin(graph, in, "raw-rt-ao", "rt-ao", uint64_t(launch.width) * launch.height, "raw-ao", surface,
                     "outAo", "raw_ao.rgen", launch);
  }
  if (effects.direct)
    t.direct = traceTwin(graph, in, "raw-rt-direct", "rt-direct", pixels, "raw-direct", surface, "outVisibility",
                         "raw_direct.rgen", in.size);
  if (effects.indirect)
    t.indirect =
        traceTwin(graph, in, "raw-rt-indirect", "rt-indirect", indirectLaunch(in.size, indirectQuarter) * 2,
                  "raw-indirect", surface, "outHit", "raw_indirect.rgen", indirectLaunchSize(in.size, indirectQuarter));
  // Only the first bounce: its ray and a shadow ray per light shaded at the hit.
  if (effects.specular)
    t.specular = traceTwin(graph, in, "raw-rt-specular", "rt-specular", pixels * (1u + lightsPerHit), "raw-specular",
                           {{"depthTex", gb.depth},
                            {"normalTex", gb.normals},
                            {"albedoTex", gb.albedo},
                            {"materialTex", gb.material},
                            {"emissiveTex", gb.emissive},
                            {"specularGbufTex", gb.specular}},
                           "outHit", "raw_specular.rgen", in.size);
  return t;
}

}  // namespace rayster::render
