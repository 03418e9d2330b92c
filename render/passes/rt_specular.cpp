// Pass 4: ray-traced reflections and refractions (the raygen bounce loop); denoised by SVGF
// (denoise_svgf.cpp). Rough glossy reflections trace half the pixels per frame in a checkerboard
// (lib/specular_weight.glsl); "rt-specular-fill" fills the other half from their neighbours, in place
// (recorded only where some surface is that rough: Renderer::Impl::specularFillOn).
// Where the device launches rays indirectly, the paths that go on after their first segment are
// compacted into a queue and traced on by "rt-specular-continue", one dense invocation per path
// (shaders/specular.rgen.glsl, docs/techniques.md §12).
#include <algorithm>

#include "render/passes/passes.h"
#include "render/pipelines.h"
#include "render/settings_table.h"
#include "rhi/context.h"

namespace rayster::render {
namespace {

const PassSetting kQueue{
    passSwitch("specular-queue", "Effects",
               "Compact the reflection/refraction paths that go on after their first bounce into a queue traced by "
               "a second, dense launch (rt-specular-continue); off: every pixel loops in its own invocation. The "
               "image is the same; on needs indirect ray launches (without them it is off)",
               true, kUseAll, false)};

// The queue's buffers, sized for `pixels` (kept while the size stays).
void ensureQueue(SpecularQueue& q, rhi::Context& ctx, uint64_t pixels) {
  if (q.paths && q.pixels == pixels) return;
  const uint64_t capacity = (pixels + gpu::kSpecularQueueDivisor - 1) / gpu::kSpecularQueueDivisor;
  q.paths = rhi::Buffer(ctx, capacity * gpu::kSpecularQueuePathWords * sizeof(uint32_t),
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, rhi::MemoryUsage::GpuOnly, "specular-queue");
  q.length = rhi::Buffer(ctx, sizeof(VkTraceRaysIndirectCommandKHR),
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                             VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                         rhi::MemoryUsage::GpuOnly, "specular-queue-length");
  q.pathsState = q.lengthState = {};
  q.pixels = pixels;
}

rhi::RayTracingPipelineDesc specularPipeline(const char* raygen) {
  rhi::RayTracingPipelineDesc d;
  d.raygen = raygen;
  d.miss = {"primary.rmiss", "shadow.rmiss"};  // radiance rays miss 0, shadow rays miss 1
  d.hitGroups = radianceHitGroups();
  return d;
}

}  // namespace

bool useSpecularQueue(const rhi::Context& ctx, const RenderSettings& settings, VkExtent2D size) {
  return passSwitchOn(settings, "specular-queue") && ctx.info().caps.traceRaysIndirect &&
         uint64_t(size.width) * size.height <= uint64_t(gpu::kSpecularQueuePixelMask) + 1;
}

graph::ImageHandle traceSpecular(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb, uint32_t bounces,
                                 uint32_t lightsPerHit, bool halfRateFill, const ProbeLookup& probes,
                                 SpecularQueue* queue) {
  graph::ImageHandle out =
      graph.createImage("specular-raw",
                        {kRadianceFormat, in.size.width, in.size.height, 1,
                         VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
                        kRadianceImage);
  // A path of one segment never goes on: nothing to queue.
  const bool compact = queue && bounces > 1;
  graph::BufferHandle paths, length;
  if (compact) {
    ensureQueue(*queue, *queue->ctx, uint64_t(in.size.width) * in.size.height);
    paths = graph.importBuffer("specular-queue", &queue->paths, &queue->pathsState);
    length = graph.importBuffer("specular-queue-length", &queue->length, &queue->lengthState);
    graph.addPass(
        "rt-specular-queue-clear", [&](graph::PassBuilder& b) { b.write(length, graph::Use::TransferDst); },
        [length](graph::PassContext& pc) {
          const VkTraceRaysIndirectCommandKHR empty{0, 1, 1};
          vkCmdUpdateBuffer(pc.cmd, pc.buffer(length).handle(), 0, sizeof(empty), &empty);
        });
  }
  const char* raygen = compact ? "specular_queue.rgen" : "specular.rgen";
  const rhi::RayTracingPipeline& pipe = in.pipelines.rayTracing(raygen, [raygen] { return specularPipeline(raygen); });
  // Without probes any image stands in (kProbeLookup unset: never read).
  const bool lookup = probes.irradiance.valid();
  auto bindShading = [&](graph::PassBuilder& b) {
    b.bind("tlas", in.tlas);
    b.bind("probeIrradianceTex", lookup ? probes.irradiance : gb.albedo, in.linear.handle());
    b.bind("probeVisibilityTex", lookup ? probes.visibility : gb.material, in.linear.handle());
    b.bind("probeDataTex", lookup ? probes.data : gb.material);
  };
  // Per pixel and bounce a ray and a shadow ray per light shaded at its hit: a bound, since
  // most pixels are not specular and most paths end after a bounce.
  const uint64_t pixels = uint64_t(in.size.width) * in.size.height;
  graph.addPass(
      "rt-specular",
      [&](graph::PassBuilder& b) {
        b.pipeline(pipe);
        bindShading(b);
        bindSurface(b, gb);
        b.bind("outSpecular", out);
        if (compact) b.bind("SpecularQueue", paths).bind("SpecularQueueLength", length);
        b.rays(pixels * (compact ? 1u : bounces) * (1u + lightsPerHit));
      },
      [&pipe, grid = probes.grid, size = in.size](graph::PassContext& pc) {
        pc.push(grid);
        pipe.trace(pc.cmd, size.width, size.height);
      });
  if (compact) {
    const rhi::RayTracingPipeline& next =
        in.pipelines.rayTracing("specular_continue.rgen", [] { return specularPipeline("specular_continue.rgen"); });
    graph.addPass(
        "rt-specular-continue",
        [&](graph::PassBuilder& b) {
          b.pipeline(next);
          bindShading(b);
          b.bind("SpecularQueue", paths);
          b.read(length, graph::Use::IndirectRead);
          b.bind("outSpecular", out);  // the queued paths' pixels, which rt-specular left
          const uint64_t capacity = (pixels + gpu::kSpecularQueueDivisor - 1) / gpu::kSpecularQueueDivisor;
          b.rays(capacity * (bounces - 1) * (1u + lightsPerHit));
        },
        [&next, grid = probes.grid, length](graph::PassContext& pc) {
          pc.push(grid);
          next.traceIndirect(pc.cmd, pc.buffer(length).address());
        });
  }
  if (!halfRateFill) return out;  // nothing traced at half rate: nothing to fill
  const rhi::Pipeline& fill = in.pipelines.compute("specular_fill.comp");
  graph.addPass(
      "rt-specular-fill",
      [&](graph::PassBuilder& b) {
        b.pipeline(fill).bind("specular", out).bind("depthTex", gb.depth).bind("materialTex", gb.material);
      },
      [size = in.size](graph::PassContext& pc) {
        vkCmdDispatch(pc.cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
      });
  return out;
}

}  // namespace rayster::render
