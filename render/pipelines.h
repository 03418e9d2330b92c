#pragma once
// Every pipeline of the hybrid frame, created once per renderer.
#include "rhi/pipelines.h"
#include "render/passes/denoise.h"
#include "rhi/rt_pipeline.h"

namespace rayster::render {

// G-buffer formats (docs/techniques.md §1); both producers write the same formats except depth.
inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
inline constexpr VkFormat kTracedDepthFormat = VK_FORMAT_R32_SFLOAT;
inline constexpr VkFormat kNormalFormat = VK_FORMAT_R16G16B16A16_SNORM;
inline constexpr VkFormat kAlbedoFormat = VK_FORMAT_R8G8B8A8_UNORM;
inline constexpr VkFormat kMaterialFormat = VK_FORMAT_R8G8B8A8_UNORM;
inline constexpr VkFormat kEmissiveFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kSpecularFormat = VK_FORMAT_R8G8B8A8_UNORM;  // encodeSpecular(): 8 bits keep ~1 % steps
inline constexpr VkFormat kIdFormat = VK_FORMAT_R32_UINT;
inline constexpr VkFormat kMotionFormat = VK_FORMAT_R16G16_SFLOAT;  // uvCurrent − uvPrevious
inline constexpr VkFormat kHdrFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kLdrFormat = VK_FORMAT_R8G8B8A8_UNORM;
inline constexpr VkFormat kVisibilityFormat = VK_FORMAT_R16_SFLOAT;
inline constexpr VkFormat kRadianceFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kPathAccumulationFormat = VK_FORMAT_R32G32B32A32_SFLOAT;  // sums of many samples: fp32
inline constexpr VkFormat kTaaHistoryFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // a resolved image: fp16 is enough

struct Pipelines {
  rhi::Pipeline gbufferRaster;
  rhi::Pipeline gbufferSpheres;  // raster impostors for analytic spheres
  rhi::Pipeline cull;            // frustum and occlusion culling into the G-buffer's indirect lists
  rhi::Pipeline hiz;             // the depth pyramid occlusion culling tests against
  // The ray-tracing pipelines exist only on devices with ray-tracing pipelines (Capabilities::rayTracing()).
  rhi::RayTracingPipeline gbufferTraced;
  rhi::RayTracingPipeline shadows;
  rhi::RayTracingPipeline specular;  // reflections and refractions (bounce loop)
  rhi::Pipeline specularFill;        // the half-rate glossy pixels specular skipped this frame
  rhi::Pipeline indirectFill;        // the quarter-rate indirect pixels rt-indirect skipped this frame
  rhi::RayTracingPipeline direct;    // many-light stochastic direct light
  rhi::RayTracingPipeline ao;        // ambient occlusion
  rhi::RayTracingPipeline indirect;  // one-bounce indirect diffuse
  DenoisePipelines denoise;          // shadows/AO and SVGF (render/passes/denoise.h)
  rhi::Pipeline lighting;
  // Raster mode (render/raster_frame.h): depth-only shadow maps, their resolve, screen-space specular.
  rhi::Pipeline shadowMap;
  rhi::Pipeline shadowSpheres;  // analytic spheres: bounding cubes, exact depth in the fragment shader
  rhi::Pipeline shadowResolve;
  rhi::Pipeline ssr;
  rhi::Pipeline rasterConstants;
  rhi::Pipeline taa;
  rhi::Pipeline tonemap;

  // textures: the layout of the bindless texture set (set 1 of every pipeline that shades).
  static Pipelines create(rhi::Context& ctx, VkDescriptorSetLayout textures);
};

// The path tracer's pipeline, created only when a render asks for --mode pathtrace.
rhi::RayTracingPipeline createPathTracePipeline(rhi::Context& ctx, VkDescriptorSetLayout textures);

// Raw-ray-rate twins of the ray-traced passes (RenderSettings::rawRays, render/passes/raw_rays.cpp):
// the same rays with trivial hit and miss shaders. Created only when asked for.
struct RawRayPipelines {
  rhi::RayTracingPipeline primary;
  rhi::RayTracingPipeline shadows;
  rhi::RayTracingPipeline ao;
  rhi::RayTracingPipeline direct;
  rhi::RayTracingPipeline indirect;  // bounce ray with a closest hit returning t, then a shadow ray
  rhi::RayTracingPipeline specular;  // the first bounce ray, then shadow rays at its hit
  static RawRayPipelines create(rhi::Context& ctx, VkDescriptorSetLayout textures);
};

} // namespace rayster::render
