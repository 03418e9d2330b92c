#include "rhi/pipeline_library.h"

#include "core/error.h"

namespace rayster::rhi {

const Pipeline& PipelineLibrary::compute(std::string_view shader) {
  if (auto it = pipelines_.find(shader); it != pipelines_.end()) return *it->second;
  auto p = std::make_unique<Pipeline>(createComputePipeline(*ctx_, shader, globalSet_));
  return *pipelines_.emplace(std::string(shader), std::move(p)).first->second;
}

const Pipeline& PipelineLibrary::graphics(std::string_view key, const std::function<GraphicsPipelineDesc()>& describe) {
  if (auto it = pipelines_.find(key); it != pipelines_.end()) return *it->second;
  GraphicsPipelineDesc d = describe();
  d.globalSet = globalSet_;
  auto p = std::make_unique<Pipeline>(createGraphicsPipeline(*ctx_, d));
  return *pipelines_.emplace(std::string(key), std::move(p)).first->second;
}

const RayTracingPipeline& PipelineLibrary::rayTracing(std::string_view key,
                                                      const std::function<RayTracingPipelineDesc()>& describe) {
  if (auto it = pipelines_.find(key); it != pipelines_.end()) {
    const auto* rt = dynamic_cast<const RayTracingPipeline*>(it->second.get());
    RAYSTER_ASSERT(rt, "a pipeline key names a ray-tracing pipeline and another kind");
    return *rt;
  }
  RayTracingPipelineDesc d = describe();
  d.globalSet = globalSet_;
  auto p = std::make_unique<RayTracingPipeline>(*ctx_, d);
  return static_cast<const RayTracingPipeline&>(*pipelines_.emplace(std::string(key), std::move(p)).first->second);
}

}  // namespace rayster::rhi
