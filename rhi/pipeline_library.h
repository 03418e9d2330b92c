#pragma once
// Pipelines belong to the passes that run them (docs/architecture.md §4): a pass file describes its
// pipeline and asks the library for it while the frame is recorded; the library creates it on first
// use and keeps it (keyed by name) until clear() (shader hot reload). Nothing builds pipelines up
// front, so a frame that never runs an effect never compiles its shaders.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>

#include "rhi/pipelines.h"
#include "rhi/rt_pipeline.h"

namespace rayster::rhi {

class PipelineLibrary {
 public:
  // globalSet: the set 1 layout (bindless textures) every pipeline whose shaders use set 1 gets.
  PipelineLibrary(Context& ctx, VkDescriptorSetLayout globalSet) : ctx_(&ctx), globalSet_(globalSet) {}

  // A compute pipeline of one shader (its key is the shader's name, e.g. "taa.comp").
  const Pipeline& compute(std::string_view shader);
  // `describe` is called only when `key` is not in the library yet.
  const Pipeline& graphics(std::string_view key, const std::function<GraphicsPipelineDesc()>& describe);
  const RayTracingPipeline& rayTracing(std::string_view key, const std::function<RayTracingPipelineDesc()>& describe);

  size_t size() const { return pipelines_.size(); }
  bool contains(std::string_view key) const { return pipelines_.count(std::string(key)) != 0; }
  // Drops every pipeline (retired, not destroyed under the GPU): the next frame creates what it uses.
  void clear() { pipelines_.clear(); }

 private:
  Context* ctx_;
  VkDescriptorSetLayout globalSet_;
  std::map<std::string, std::unique_ptr<Pipeline>, std::less<>> pipelines_;  // stable addresses
};

}  // namespace rayster::rhi
