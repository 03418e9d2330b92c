#pragma once
// The passes of the hybrid frame (DESIGN.md §3), one file each: functions from graph inputs to
// graph outputs. A pass declares what it reads and writes; the graph places the barriers.
#include <cstdint>

#include <volk.h>

#include "graph/graph.h"

namespace rayster::rhi {
class Buffer;
class Sampler;
} // namespace rayster::rhi

namespace rayster::render {

struct GpuScene;
struct Pipelines;

// What every pass may read without declaring it: immutable for the whole frame.
struct FrameInputs {
  const Pipelines& pipelines;
  const GpuScene& scene;
  const rhi::Buffer& constants;  // FrameConstants, written by the host before submission
  const rhi::Sampler& nearest;
  VkExtent2D size;
  VkDescriptorSet textures;  // set 1: the scene's bindless textures
};

// Binds the bindless texture set as set 1 of `pipeline`.
void bindTextures(VkCommandBuffer cmd, const FrameInputs& in, VkPipelineBindPoint bindPoint, VkPipelineLayout layout);

struct GBuffer {
  graph::ImageHandle depth;     // D32 (raster) or R32F (traced): sample .r either way
  graph::ImageHandle normals;   // RGBA16_SNORM: oct shading normal, oct geometric normal
  graph::ImageHandle albedo;    // RGBA8: sRGB-encoded base colour
  graph::ImageHandle material;  // RGBA8: roughness, metallic, transmission, flags
  graph::ImageHandle emissive;  // RGBA16F
  graph::ImageHandle id;        // R32_UINT instance row, kBackgroundId for sky
};

GBuffer rasterGBuffer(graph::RenderGraph& graph, const FrameInputs& in);
GBuffer traceGBuffer(graph::RenderGraph& graph, const FrameInputs& in);

// One visibility layer per shadowed light (R16F array), 1 sample per pixel.
graph::ImageHandle traceShadows(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb, uint32_t lights);
// Denoised by denoiseShadows() (render/passes/denoise.h).

// Reflections and refractions of mirror, metal and glass pixels (RGBA16F radiance, 0 elsewhere).
graph::ImageHandle traceSpecular(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb);
// Denoised by denoiseRadiance() (render/passes/denoise.h).

graph::ImageHandle shadeLighting(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                                 graph::ImageHandle visibility, graph::ImageHandle specular);
graph::ImageHandle tonemap(graph::RenderGraph& graph, const FrameInputs& in, graph::ImageHandle hdr, float exposure,
                           uint32_t seed);
// Copies an image into a host-visible buffer and makes it visible to the host.
void readback(graph::RenderGraph& graph, graph::ImageHandle image, graph::BufferHandle buffer);

} // namespace rayster::render
