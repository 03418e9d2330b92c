// What every frame's graph starts with: its globals and the TLAS as a graph resource.
#include "render/gpu_scene.h"
#include "render/passes/passes.h"
#include "rhi/resources.h"

namespace rayster::render {

graph::AccelHandle beginFrameGraph(graph::RenderGraph& graph, GpuScene& scene, const rhi::Buffer& constants,
                                   const rhi::Sampler& nearest) {
  graph.setGlobals({scene.bindless->set(), nearest.handle(), {{"FrameBlock", &constants}}});
  if (scene.tlas.handle() == VK_NULL_HANDLE) return {};
  return graph.importAccel("tlas", scene.tlas.handle(), &scene.tlas.buffer(), &scene.tlasState);
}

void updateTlas(graph::RenderGraph& graph, const FrameInputs& in, bool refit) {
  const rhi::Tlas& tlas = in.scene.tlas;
  // A side effect: the refit must land even in a frame that traces nothing (the next one will).
  graph.addPass(
      "tlas-update",
      [&](graph::PassBuilder& b) {
        b.write(in.tlas.buffer, graph::Use::AccelStructBuildWrite);
        b.sideEffect();
      },
      [&tlas, refit](graph::PassContext& pc) { tlas.record(pc.cmd, refit); });
}

}  // namespace rayster::render
