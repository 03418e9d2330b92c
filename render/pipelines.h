#pragma once
// The hybrid frame's image formats and the hit groups its ray-tracing pipelines share. The pipelines
// themselves belong to their pass files (rhi/pipeline_library.h).
#include <vector>

#include "rhi/pipeline_library.h"

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
// encodeLayers() (lib/common.glsl): clear coat and sheen, packed; 32 bits a word keep the coat normal
// at 16 bits per axis within the eight colour attachments every device has.
inline constexpr VkFormat kLayersFormat = VK_FORMAT_R32G32B32A32_UINT;
inline constexpr VkFormat kMotionFormat = VK_FORMAT_R16G16_SFLOAT;  // uvCurrent − uvPrevious
inline constexpr VkFormat kHdrFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kLdrFormat = VK_FORMAT_R8G8B8A8_UNORM;
inline constexpr VkFormat kVisibilityFormat = VK_FORMAT_R16_SFLOAT;
inline constexpr VkFormat kRadianceFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kPathAccumulationFormat = VK_FORMAT_R32G32B32A32_SFLOAT;  // sums of many samples: fp32
inline constexpr VkFormat kTaaHistoryFormat = VK_FORMAT_R16G16B16A16_SFLOAT;        // a resolved image: fp16 is enough

// Hit groups by geometry kind (gpu::kHitGroupTriangles, gpu::kHitGroupSpheres), shared by the
// ray-tracing passes that describe their pipelines (rhi/pipeline_library.h): alpha-tested triangles
// run any-hit; spheres run their intersection shader.
inline std::vector<rhi::HitGroup> radianceHitGroups() {
  return {{"primary.rchit", "alpha.rahit", ""}, {"primary.rchit", "", "sphere.rint"}};
}
// Shadow and AO rays skip closest hit: the miss shader marks visibility, any-hit tests alpha.
inline std::vector<rhi::HitGroup> shadowHitGroups() { return {{"", "alpha.rahit", ""}, {"", "", "sphere.rint"}}; }

}  // namespace rayster::render
