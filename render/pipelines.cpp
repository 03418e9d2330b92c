#include "render/pipelines.h"

#include "rhi/context.h"
#include "shaders/shared/types.h"

namespace rayster::render {
namespace {
constexpr VkDescriptorType kUniform = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr VkDescriptorType kTlas = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;

// Hit groups by geometry kind (gpu::kHitGroupTriangles, gpu::kHitGroupSpheres): alpha-tested
// triangles run any-hit; spheres run their intersection shader.
const std::vector<rhi::HitGroup> kRadianceHitGroups = {{"primary.rchit", "alpha.rahit", ""},
                                                       {"primary.rchit", "", "sphere.rint"}};
} // namespace

rhi::RayTracingPipeline createPathTracePipeline(rhi::Context& ctx, VkDescriptorSetLayout textures) {
  rhi::RayTracingPipelineDesc d;
  d.raygen = "pathtrace.rgen";
  d.miss = {"primary.rmiss", "shadow.rmiss"};  // radiance rays miss 0, shadow rays miss 1
  d.hitGroups = kRadianceHitGroups;
  d.globalSet = textures;
  d.bindings = {{0, kUniform}, {1, kTlas}, {2, kStorage}, {3, kStorage}, {4, kStorage}, {5, kStorage}};
  return rhi::RayTracingPipeline(ctx, d);
}

Pipelines Pipelines::create(rhi::Context& ctx, VkDescriptorSetLayout textures) {
  Pipelines p;
  rhi::GraphicsPipelineDesc g;
  g.globalSet = textures;
  g.vertex = "gbuffer.vert";
  g.fragment = "gbuffer.frag";
  g.colorFormats = {kNormalFormat, kAlbedoFormat, kMaterialFormat, kEmissiveFormat,
                    kIdFormat,     kMotionFormat, kSpecularFormat};
  g.depthFormat = kDepthFormat;
  g.bindings = {{0, kUniform}};
  g.pushConstantBytes = 16;  // DrawRecord[] and this list's draw ids (render/passes/cull.h)
  p.gbufferRaster = rhi::createGraphicsPipeline(ctx, g);
  g.vertex = "gbuffer_sphere.vert";
  g.fragment = "gbuffer_sphere.frag";
  p.gbufferSpheres = rhi::createGraphicsPipeline(ctx, g);
  const rhi::Binding cull[] = {{0, kUniform}};
  p.cull = rhi::createComputePipeline(ctx, "cull.comp", cull, sizeof(gpu::CullPush));
  const rhi::Binding hiz[] = {{0, kUniform}, {1, kSampled}};
  p.hiz = rhi::createComputePipeline(ctx, "hiz.comp", hiz, sizeof(gpu::HizPush));

  rhi::GraphicsPipelineDesc shadowMap;
  shadowMap.vertex = "shadow_map.vert";
  shadowMap.fragment = "shadow_map.frag";
  shadowMap.depthFormat = kDepthFormat;
  shadowMap.bindings = {{0, kUniform}};
  shadowMap.pushConstantBytes = 72;  // clipFromWorld, instance, geometry
  shadowMap.dynamicCulling = true;   // per draw: the material's sidedness, the instance's mirroring
  p.shadowMap = rhi::createGraphicsPipeline(ctx, shadowMap);
  shadowMap.dynamicCulling = false;
  shadowMap.vertex = "shadow_sphere.vert";
  shadowMap.fragment = "shadow_sphere.frag";
  shadowMap.pushConstantBytes = 88;  // clipFromWorld, instance, geometry, light position or direction
  p.shadowSpheres = rhi::createGraphicsPipeline(ctx, shadowMap);
  const rhi::Binding resolve[] = {{0, kUniform}, {1, kSampled}, {2, kSampled}, {3, kSampled}, {4, kUniform}, {5, kStorage}};
  p.shadowResolve = rhi::createComputePipeline(ctx, "shadow_resolve.comp", resolve, 0);
  const rhi::Binding ssr[] = {{0, kUniform}, {1, kSampled}, {2, kSampled}, {3, kSampled}, {4, kSampled},
                              {5, kSampled}, {6, kSampled}, {7, kStorage}, {8, kSampled}};
  p.ssr = rhi::createComputePipeline(ctx, "ssr.comp", ssr, 0, textures);
  const rhi::Binding constants[] = {{0, kStorage}, {1, kStorage}};
  p.rasterConstants = rhi::createComputePipeline(ctx, "raster_constants.comp", constants, 8);
  p.denoise = DenoisePipelines::create(ctx);
  const rhi::Binding lighting[] = {{0, kUniform}, {1, kSampled}, {2, kSampled}, {3, kSampled},
                                   {4, kSampled}, {5, kSampled}, {6, kSampled}, {7, kStorage},
                                   {8, kSampled}, {9, kSampled}, {10, kSampled}, {11, kSampled},
                                   {12, kSampled}};
  p.lighting = rhi::createComputePipeline(ctx, "lighting.comp", lighting, 0, textures);
  const rhi::Binding taa[] = {{0, kUniform}, {1, kSampled}, {2, kSampled}, {3, kSampled}, {4, kSampled}, {5, kStorage}};
  p.taa = rhi::createComputePipeline(ctx, "taa.comp", taa, 16);
  const rhi::Binding tone[] = {{1, kSampled}, {2, kStorage}};
  p.tonemap = rhi::createComputePipeline(ctx, "tonemap.comp", tone, 20);
  const rhi::Binding fill[] = {{0, kUniform}, {1, kStorage}, {2, kSampled}, {3, kSampled}};
  p.specularFill = rhi::createComputePipeline(ctx, "specular_fill.comp", fill, 0);
  const rhi::Binding indirectFill[] = {{0, kUniform}, {1, kStorage}, {2, kSampled}};
  p.indirectFill = rhi::createComputePipeline(ctx, "indirect_fill.comp", indirectFill, 0);
  if (!ctx.caps().rayTracing()) return p;

  // Hit groups by geometry kind (gpu::kHitGroupTriangles, gpu::kHitGroupSpheres): alpha-tested
  // triangles run any-hit; spheres run their intersection shader.

  rhi::RayTracingPipelineDesc primary;
  primary.raygen = "gbuffer.rgen";
  primary.miss = {"primary.rmiss"};
  primary.hitGroups = kRadianceHitGroups;
  primary.globalSet = textures;
  primary.bindings = {{0, kUniform}, {1, kTlas},    {2, kStorage}, {3, kStorage}, {4, kStorage},
                      {5, kStorage}, {6, kStorage}, {7, kStorage}, {8, kStorage}, {9, kStorage}};
  p.gbufferTraced = rhi::RayTracingPipeline(ctx, primary);

  // Shadow rays skip closest hit: the miss shader marks visibility, any-hit tests alpha.
  rhi::RayTracingPipelineDesc shadow;
  shadow.raygen = "shadows.rgen";
  shadow.miss = {"shadow.rmiss"};
  shadow.hitGroups = {{"", "alpha.rahit", ""}, {"", "", "sphere.rint"}};
  shadow.globalSet = textures;
  shadow.bindings = {{0, kUniform}, {1, kTlas}, {2, kSampled}, {3, kSampled}, {4, kStorage}};
  p.shadows = rhi::RayTracingPipeline(ctx, shadow);

  rhi::RayTracingPipelineDesc specular;
  specular.raygen = "specular.rgen";
  specular.miss = {"primary.rmiss", "shadow.rmiss"};  // radiance rays miss 0, shadow rays miss 1
  specular.hitGroups = primary.hitGroups;
  specular.bindings = {{0, kUniform}, {1, kTlas}, {2, kSampled}, {3, kSampled}, {4, kSampled}, {5, kSampled},
                       {6, kStorage}, {7, kSampled}, {8, kSampled}};
  specular.globalSet = textures;
  p.specular = rhi::RayTracingPipeline(ctx, specular);

  rhi::RayTracingPipelineDesc direct;
  direct.raygen = "direct.rgen";
  direct.miss = {"shadow.rmiss"};
  direct.hitGroups = shadow.hitGroups;
  direct.globalSet = textures;
  direct.bindings = {{0, kUniform}, {1, kTlas}, {2, kSampled}, {3, kSampled}, {4, kSampled}, {5, kSampled},
                     {6, kStorage}, {7, kSampled}, {8, kSampled}};
  p.direct = rhi::RayTracingPipeline(ctx, direct);
  // AO rays are shadow rays of another length: same miss and hit groups.
  rhi::RayTracingPipelineDesc ao = shadow;
  ao.raygen = "ao.rgen";
  p.ao = rhi::RayTracingPipeline(ctx, ao);
  rhi::RayTracingPipelineDesc indirect;
  indirect.raygen = "indirect.rgen";
  indirect.miss = {"primary.rmiss", "shadow.rmiss"};  // radiance rays miss 0, shadow rays miss 1
  indirect.hitGroups = primary.hitGroups;
  indirect.bindings = {{0, kUniform}, {1, kTlas}, {2, kSampled}, {3, kSampled}, {4, kStorage}};
  indirect.globalSet = textures;
  p.indirect = rhi::RayTracingPipeline(ctx, indirect);
  return p;
}

RawRayPipelines RawRayPipelines::create(rhi::Context& ctx, VkDescriptorSetLayout textures) {
  RawRayPipelines p;
  rhi::RayTracingPipelineDesc primary;
  primary.raygen = "raw_primary.rgen";
  primary.miss = {"shadow.rmiss"};  // marks the payload; any trivial miss would do
  primary.hitGroups = {{"raw.rchit", "alpha.rahit", ""}, {"raw.rchit", "", "sphere.rint"}};
  primary.globalSet = textures;
  primary.bindings = {{0, kUniform}, {1, kTlas}, {2, kStorage}};
  p.primary = rhi::RayTracingPipeline(ctx, primary);
  rhi::RayTracingPipelineDesc shadow;
  shadow.raygen = "raw_shadows.rgen";
  shadow.miss = {"shadow.rmiss"};
  shadow.hitGroups = {{"", "", ""}, {"", "", "sphere.rint"}};  // opaque: no alpha any-hit
  shadow.globalSet = textures;
  shadow.bindings = {{0, kUniform}, {1, kTlas}, {2, kSampled}, {3, kSampled}, {4, kStorage}};
  p.shadows = rhi::RayTracingPipeline(ctx, shadow);
  rhi::RayTracingPipelineDesc ao = shadow;  // AO and many-light shadow rays: shadow rays of their own
  ao.raygen = "raw_ao.rgen";
  p.ao = rhi::RayTracingPipeline(ctx, ao);
  ao.raygen = "raw_direct.rgen";
  p.direct = rhi::RayTracingPipeline(ctx, ao);
  // Bounce rays: a closest hit that returns t, and a miss that leaves the payload; shadow rays miss 1.
  rhi::RayTracingPipelineDesc bounce;
  bounce.raygen = "raw_indirect.rgen";
  bounce.miss = {"raw.rmiss", "shadow.rmiss"};
  bounce.hitGroups = {{"raw_t.rchit", "", ""}, {"raw_t.rchit", "", "sphere.rint"}};  // opaque
  bounce.globalSet = textures;
  bounce.bindings = {{0, kUniform}, {1, kTlas}, {2, kSampled}, {3, kSampled}, {4, kStorage}};
  p.indirect = rhi::RayTracingPipeline(ctx, bounce);
  bounce.raygen = "raw_specular.rgen";
  bounce.bindings = {{0, kUniform}, {1, kTlas},    {2, kSampled}, {3, kSampled}, {4, kSampled},
                     {5, kSampled}, {6, kStorage}, {7, kSampled}, {8, kSampled}};
  p.specular = rhi::RayTracingPipeline(ctx, bounce);
  return p;
}

} // namespace rayster::render
