// Structs shared by C++ and GLSL (STYLE.md §5). Compiled as both; layouts are GLSL `scalar`
// (std430-like, vec3 packed to 12 bytes), checked on the C++ side with static_assert.
#ifndef RAYSTER_SHARED_TYPES_H
#define RAYSTER_SHARED_TYPES_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace rayster::gpu {
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec2 = glm::uvec2;
using mat4 = glm::mat4;
using uint = uint32_t;
#define RAYSTER_CONST inline constexpr
#else
#define RAYSTER_CONST const
#endif

// Instance mask bits (TLAS): shadow rays only see casters, so a light's visible shape casts nothing.
RAYSTER_CONST uint kMaskCastsShadow = 0x01u;
RAYSTER_CONST uint kMaskVisible = 0x02u;

RAYSTER_CONST uint kLightPoint = 0u;  // a sphere light when radius > 0
RAYSTER_CONST uint kLightSpot = 1u;
RAYSTER_CONST uint kLightDirectional = 2u;

RAYSTER_CONST uint kMaxShadowLights = 8u;  // one visibility layer each
RAYSTER_CONST uint kBackgroundId = 0xFFFFFFFFu;

struct Vertex {
  vec3 position;  // offset 0: the BLAS reads R32G32B32 positions with this stride
  vec3 normal;
  vec2 uv;
};

// One per primitive (BLAS geometry): where its vertices and indices live.
struct GeometryRecord {
  uint64_t vertexAddress;
  uint64_t indexAddress;
  uint material;
  uint vertexCount;
  uint indexCount;
  uint pad0;
};

// One per TLAS instance; gl_InstanceCustomIndexEXT is its row.
struct InstanceRecord {
  mat4 worldFromObject;
  mat4 normalFromObject;  // inverse transpose of worldFromObject
  uint firstGeometry;     // geometry row = firstGeometry + gl_GeometryIndexEXT
  uint mask;
  uint pad0;
  uint pad1;
};

struct MaterialRecord {
  vec4 baseColor;  // linear
  vec3 emissive;   // linear radiance
  float metallic;
  float roughness;
  uint flags;
  uint pad0;
  uint pad1;
};

struct LightRecord {
  vec3 position;
  float radius;  // sphere light radius; 0: hard point light
  vec3 radiance; // colour × intensity: radiant intensity (point/spot) or irradiance (directional)
  uint type;
  vec3 direction;  // the direction light travels (spot, directional)
  float angularRadius;
  float cosInner;
  float cosOuter;
  uint pad0;
  uint pad1;
};

struct FrameConstants {
  mat4 clipFromWorld;
  mat4 worldFromClip;
  vec4 cameraPosition;  // xyz; w unused
  vec4 ambient;         // rgb: uniform ambient radiance
  uvec2 size;
  uint frameIndex;      // advances every frame; feeds the RNG
  uint seed;            // --seed
  uint lightCount;
  uint shadowLightCount;  // lights with a visibility layer (<= kMaxShadowLights)
  float exposure;         // linear multiplier, 2^EV
  uint pad0;
  uint64_t geometries;  // GeometryRecord[]
  uint64_t instances;   // InstanceRecord[]
  uint64_t materials;   // MaterialRecord[]
  uint64_t lights;      // LightRecord[]
};

#ifdef __cplusplus
static_assert(sizeof(Vertex) == 32);
static_assert(sizeof(GeometryRecord) == 32);
static_assert(sizeof(InstanceRecord) == 144);
static_assert(offsetof(InstanceRecord, firstGeometry) == 128);
static_assert(sizeof(MaterialRecord) == 48);
static_assert(sizeof(LightRecord) == 64);
static_assert(offsetof(FrameConstants, size) == 160);
static_assert(offsetof(FrameConstants, geometries) == 192);
static_assert(sizeof(FrameConstants) == 224);
} // namespace rayster::gpu
#endif

#endif
