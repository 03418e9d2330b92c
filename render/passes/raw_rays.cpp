// Raw ray rates (rayster bench --raw-rays): the rays of the frame's ray-traced passes traced again
// with trivial shaders into scratch images, so each pass can report the share of the device's raw
// ray rate it reaches (its rays are the same; only shading and memory traffic differ). Exact
// replays: primary, shadow, AO and many-light direct rays, the indirect bounce ray and the specular
// path's first ray. Approximate: the shadow rays at those bounce hits (the twins know only the hit
// distance, not the hit's normal) and, for specular, no deeper bounces (raw_specular.rgen). At
// quarter-rate indirect, raw-rt-indirect launches rt-indirect's quarter-size grid.
#include <utility>
#include <vector>

#include "render/gpu_scene.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

namespace {
// Results nobody reads: a side effect keeps the graph from culling the pass.
constexpr VkImageUsageFlags kScratchUsage = VK_IMAGE_USAGE_STORAGE_BIT;

// One twin: a full-screen launch of `pipe` reading G-buffer images at their bindings and writing
// one R16F image (readable as an AOV, for the tests that compare it with its pass) at `outBinding`.
// `twinOf` names the pass it replays; `rays` its launched rays.
graph::ImageHandle traceTwin(graph::RenderGraph& graph, const FrameInputs& in, const char* pass, const char* twinOf,
                             uint64_t rays, const char* image, std::vector<std::pair<uint32_t, graph::ImageHandle>> reads,
                             uint32_t outBinding, const rhi::RayTracingPipeline& pipe, bool quarterLaunch = false) {
  graph::ImageHandle out = graph.createImage(
      image, {kVisibilityFormat, in.size.width, in.size.height, 1, kScratchUsage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
      std::string_view(image) == "raw-ao" ? 0u : kRadianceImage);
  graph.addPass(
      pass,
      [&](graph::PassBuilder& b) {
        for (const auto& r : reads) b.read(r.second, graph::Use::SampledRayTracing);
        b.write(out, graph::Use::StorageWriteRayTracing);
        b.sideEffect();
        b.twinOf(twinOf);
        b.rays(rays);
      },
      [reads, out, outBinding, quarterLaunch, &in, &pipe](graph::PassContext& pc) {
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.handle());
        rhi::DescriptorWriter w;
        w.uniformBuffer(0, in.constants).accelerationStructure(1, in.scene.tlas.handle());
        for (const auto& r : reads) w.sampledImage(r.first, pc.image(r.second).view(), in.nearest.handle());
        w.storageImage(outBinding, pc.image(out).view()).push(pc.cmd, pipe);
        bindTextures(pc.cmd, in, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.layout());
        const VkExtent2D launch = indirectLaunchSize(in.size, quarterLaunch);
        pipe.trace(pc.cmd, launch.width, launch.height);
      });
  return out;
}
}  // namespace

void traceRawPrimary(graph::RenderGraph& graph, const FrameInputs& in, const RawRayPipelines& raw) {
  graph::ImageHandle hit =
      graph.createImage("raw-primary-hit", {kVisibilityFormat, in.size.width, in.size.height, 1, kScratchUsage});
  graph.addPass(
      "raw-gbuffer-traced",
      [&](graph::PassBuilder& b) {
        b.write(hit, graph::Use::StorageWriteRayTracing);
        b.sideEffect();
        b.twinOf("gbuffer-traced");
        b.rays(uint64_t(in.size.width) * in.size.height, true);
      },
      [hit, &in, &raw](graph::PassContext& pc) {
        const rhi::RayTracingPipeline& pipe = raw.primary;
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.handle());
        rhi::DescriptorWriter()
            .uniformBuffer(0, in.constants)
            .accelerationStructure(1, in.scene.tlas.handle())
            .storageImage(2, pc.image(hit).view())
            .push(pc.cmd, pipe);
        bindTextures(pc.cmd, in, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.layout());
        pipe.trace(pc.cmd, in.size.width, in.size.height);
      });
}

void traceRawShadows(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb, uint32_t lights,
                     const RawRayPipelines& raw) {
  if (lights == 0) return;  // many-light mode: the shadow pass traces nothing either
  graph::ImageHandle vis = graph.createImage(
      "raw-shadow-visibility", {kVisibilityFormat, in.size.width, in.size.height, lights, kScratchUsage, true});
  graph.addPass(
      "raw-rt-shadows",
      [&](graph::PassBuilder& b) {
        b.read(gb.depth, graph::Use::SampledRayTracing);
        b.read(gb.normals, graph::Use::SampledRayTracing);
        b.write(vis, graph::Use::StorageWriteRayTracing);
        b.sideEffect();
        b.twinOf("rt-shadows");
        b.rays(uint64_t(in.size.width) * in.size.height * lights);
      },
      [gb, vis, lights, &in, &raw](graph::PassContext& pc) {
        const rhi::RayTracingPipeline& pipe = raw.shadows;
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.handle());
        rhi::DescriptorWriter()
            .uniformBuffer(0, in.constants)
            .accelerationStructure(1, in.scene.tlas.handle())
            .sampledImage(2, pc.image(gb.depth).view(), in.nearest.handle())
            .sampledImage(3, pc.image(gb.normals).view(), in.nearest.handle())
            .storageImage(4, pc.image(vis).view())
            .push(pc.cmd, pipe);
        bindTextures(pc.cmd, in, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.layout());
        pipe.trace(pc.cmd, in.size.width, in.size.height, lights);
      });
}

RawTwinImages traceRawTwins(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb, RawTwinEffects effects,
                            bool indirectQuarter, uint32_t lightsPerHit, const RawRayPipelines& raw) {
  RawTwinImages t;
  const uint64_t pixels = uint64_t(in.size.width) * in.size.height;
  if (effects.ao)
    t.ao = traceTwin(graph, in, "raw-rt-ao", "rt-ao", pixels, "raw-ao", {{2, gb.depth}, {3, gb.normals}}, 4, raw.ao);
  if (effects.direct)
    t.direct = traceTwin(graph, in, "raw-rt-direct", "rt-direct", pixels, "raw-direct", {{2, gb.depth}, {3, gb.normals}},
                         4, raw.direct);
  if (effects.indirect)
    t.indirect = traceTwin(graph, in, "raw-rt-indirect", "rt-indirect", indirectLaunch(in.size, indirectQuarter) * 2,
                         "raw-indirect", {{2, gb.depth}, {3, gb.normals}}, 4, raw.indirect, indirectQuarter);
  // Only the first bounce: its ray and a shadow ray per light shaded at the hit.
  if (effects.specular)
    t.specular = traceTwin(graph, in, "raw-rt-specular", "rt-specular", pixels * (1u + lightsPerHit), "raw-specular",
                         {{2, gb.depth}, {3, gb.normals}, {4, gb.albedo}, {5, gb.material}, {7, gb.emissive},
                          {8, gb.specular}},
                         6,
                         raw.specular);
  return t;
}

}  // namespace rayster::render
