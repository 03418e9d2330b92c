// Passes that bind by name (PassBuilder::pipeline / bind): the access each descriptor implies, the
// check that a pass binds everything its shaders declare, and the descriptor writes at execution.
#include <algorithm>
#include <string>

#include "core/error.h"
#include "graph/graph.h"
#include "rhi/pipelines.h"

namespace rayster::graph {
namespace {

[[noreturn]] void bindError(const std::string& pass, std::string_view name, const std::string& what) {
  const std::string message = "pass '" + pass + "', descriptor '" + std::string(name) + "': " + what;
  fatal(message.c_str(), __FILE__, __LINE__);
}

// The access a storage descriptor implies, from how the GLSL qualifies it.
Use storageUse(const rhi::ShaderBinding& b, VkPipelineBindPoint point) {
  const bool rt = point == VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR;
  if (b.nonReadable) return rt ? Use::StorageWriteRayTracing : Use::StorageWriteCompute;
  if (b.nonWritable) return rt ? Use::StorageReadRayTracing : Use::StorageReadCompute;
  return rt ? Use::StorageReadWriteRayTracing : Use::StorageReadWriteCompute;
}

Use sampledUse(VkPipelineBindPoint point) {
  switch (point) {
    case VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR:
      return Use::SampledRayTracing;
    case VK_PIPELINE_BIND_POINT_GRAPHICS:
      return Use::SampledFragment;
    default:
      return Use::SampledCompute;
  }
}

}  // namespace

PassBuilder& PassBuilder::pipeline(const rhi::Pipeline& pipeline) {
  RenderGraph::Pass& pass = graph_.passes_[pass_];
  RAYSTER_ASSERT(pipeline, "pass given a pipeline that was not created");
  RAYSTER_ASSERT(!pass.pipeline, "a pass runs one pipeline");
  pass.pipeline = &pipeline;
  return *this;
}

// A name the compiled shaders do not declare binds nothing and records no access: the optimiser
// drops descriptors a variant never reads (a raw-rate twin's material images), and a misspelt name
// still fails, since the descriptor it meant is then left unbound (checkBindings).
const rhi::ShaderBinding* PassBuilder::declared(std::string_view name) const {
  const RenderGraph::Pass& pass = graph_.passes_[pass_];
  if (!pass.pipeline) bindError(pass.name, name, "bind() before pipeline()");
  const rhi::ShaderBinding* b = pass.pipeline->interface().find(name);
  if (!b) return nullptr;
  for (const RenderGraph::Descriptor& d : pass.descriptors)
    if (d.binding == b->binding) bindError(pass.name, name, "bound twice");
  return b;
}

PassBuilder& PassBuilder::bind(std::string_view name, ImageHandle image, VkSampler sampler) {
  const rhi::ShaderBinding* declaredBinding = declared(name);
  if (!declaredBinding) return *this;
  const rhi::ShaderBinding& b = *declaredBinding;
  RenderGraph::Pass& pass = graph_.passes_[pass_];
  const VkPipelineBindPoint point = pass.pipeline->bindPoint();
  RenderGraph::Descriptor d{b.binding, b.type, image.id};
  if (b.type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER) {
    d.sampler = sampler ? sampler : graph_.globals_.sampler;
    if (!d.sampler) bindError(pass.name, name, "a sampled image needs a sampler (none given, no default)");
    read(image, sampledUse(point));
  } else if (b.type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE) {
    if (point == VK_PIPELINE_BIND_POINT_GRAPHICS) bindError(pass.name, name, "storage images in graphics passes");
    const Use use = storageUse(b, point);
    if (accessInfo(use, true).writes)
      write(image, use);
    else
      read(image, use);
  } else {
    bindError(pass.name, name, "is not an image descriptor");
  }
  pass.descriptors.push_back(d);
  return *this;
}

PassBuilder& PassBuilder::bind(std::string_view name, BufferHandle buffer) {
  const rhi::ShaderBinding* declaredBinding = declared(name);
  if (!declaredBinding) return *this;
  const rhi::ShaderBinding& b = *declaredBinding;
  RenderGraph::Pass& pass = graph_.passes_[pass_];
  RenderGraph::Descriptor d{b.binding, b.type};
  d.buffer = buffer.id;
  if (b.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER) {
    read(buffer, Use::UniformRead);
  } else if (b.type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER) {
    if (pass.pipeline->bindPoint() == VK_PIPELINE_BIND_POINT_GRAPHICS)
      bindError(pass.name, name, "storage buffers in graphics passes are read through device addresses");
    const Use use = storageUse(b, pass.pipeline->bindPoint());
    if (accessInfo(use, false).writes)
      write(buffer, use);
    else
      read(buffer, use);
  } else {
    bindError(pass.name, name, "is not a buffer descriptor");
  }
  pass.descriptors.push_back(d);
  return *this;
}

PassBuilder& PassBuilder::bind(std::string_view name, AccelHandle accel) {
  const rhi::ShaderBinding* declaredBinding = declared(name);
  if (!declaredBinding) return *this;
  const rhi::ShaderBinding& b = *declaredBinding;
  RenderGraph::Pass& pass = graph_.passes_[pass_];
  if (b.type != VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR)
    bindError(pass.name, name, "is not an acceleration structure");
  if (pass.pipeline->bindPoint() != VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR)
    bindError(pass.name, name, "acceleration structures are traced from ray-tracing pipelines only");
  RenderGraph::Descriptor d{b.binding, b.type};
  d.buffer = accel.buffer.id;
  read(accel.buffer, Use::AccelStructRead);
  pass.descriptors.push_back(d);
  return *this;
}

PassBuilder& PassBuilder::bind(std::string_view name, const rhi::Buffer& constant) {
  const rhi::ShaderBinding* declaredBinding = declared(name);
  if (!declaredBinding) return *this;
  const rhi::ShaderBinding& b = *declaredBinding;
  RenderGraph::Pass& pass = graph_.passes_[pass_];
  if (b.type != VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER && b.type != VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)
    bindError(pass.name, name, "is not a buffer descriptor");
  if (b.type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER && !b.nonWritable)
    bindError(pass.name, name, "a shader that may write a buffer must bind it as a graph resource");
  RenderGraph::Descriptor d{b.binding, b.type};
  d.constant = &constant;
  pass.descriptors.push_back(d);
  return *this;
}

void RenderGraph::checkBindings(Pass& pass) const {
  if (!pass.pipeline) return;
  for (const Constant& c : globals_.constants) {
    const rhi::ShaderBinding* b = pass.pipeline->interface().find(c.name);
    const bool bound = b && std::any_of(pass.descriptors.begin(), pass.descriptors.end(),
                                        [&](const Descriptor& d) { return d.binding == b->binding; });
    if (b && !bound) {
      Descriptor d{b->binding, b->type};
      d.constant = c.buffer;
      pass.descriptors.push_back(d);
    }
  }
  std::string missing;
  for (const rhi::ShaderBinding& b : pass.pipeline->interface().bindings) {
    if (b.set != 0) continue;
    const bool bound = std::any_of(pass.descriptors.begin(), pass.descriptors.end(),
                                   [&](const Descriptor& d) { return d.binding == b.binding; });
    if (!bound) missing += (missing.empty() ? "" : ", ") + b.name;
  }
  if (!missing.empty()) bindError(pass.name, missing, "declared by the shaders but not bound");
  if (pass.pipeline->usesGlobalSet() && !globals_.set)
    bindError(pass.name, "set 1", "the pipeline uses the global set, but the graph has none (setGlobals)");
}

void RenderGraph::bindPipeline(VkCommandBuffer cmd, const Pass& pass) const {
  const rhi::Pipeline& pipe = *pass.pipeline;
  vkCmdBindPipeline(cmd, pipe.bindPoint(), pipe.handle());
  rhi::DescriptorWriter writer;
  for (const Descriptor& d : pass.descriptors) {
    switch (d.type) {
      case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
        writer.sampledImage(d.binding, images_[d.image].image->view(), d.sampler);
        break;
      case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
        writer.storageImage(d.binding, images_[d.image].image->view());
        break;
      case VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR:
        writer.accelerationStructure(d.binding, buffers_[d.buffer].accel);
        break;
      case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
        writer.uniformBuffer(d.binding, d.constant ? *d.constant : *buffers_[d.buffer].buffer);
        break;
      default:
        writer.storageBuffer(d.binding, d.constant ? *d.constant : *buffers_[d.buffer].buffer);
        break;
    }
  }
  if (!pass.descriptors.empty()) writer.push(cmd, pipe);
  if (pipe.usesGlobalSet())
    vkCmdBindDescriptorSets(cmd, pipe.bindPoint(), pipe.layout(), 1, 1, &globals_.set, 0, nullptr);
}

const rhi::Pipeline& PassContext::pipeline() const {
  const rhi::Pipeline* p = graph_.passes_[pass_].pipeline;
  RAYSTER_ASSERT(p, "PassContext::pipeline() in a pass without PassBuilder::pipeline()");
  return *p;
}

void PassContext::bindWithGlobals(const rhi::Pipeline& pipeline) const {
  RenderGraph::Pass pass;
  pass.name = graph_.passes_[pass_].name;
  pass.pipeline = &pipeline;
  graph_.checkBindings(pass);  // adds the global constants; fatal if anything else is declared
  graph_.bindPipeline(cmd, pass);
}

void PassContext::pushBytes(const void* data, uint32_t bytes) const { pipeline().pushConstants(cmd, data, bytes); }

}  // namespace rayster::graph
