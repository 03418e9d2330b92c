// Structs shared by C++ and GLSL (docs/style.md §5). Compiled as both; layouts are GLSL `scalar`
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
using uvec3 = glm::uvec3;
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
// LightRecord::flags: an emissive mesh in the scene shows the light (the built-in scenes' sphere
// lights), so traced rays see its highlight; every other light has no shape any ray can hit.
RAYSTER_CONST uint kLightVisibleShape = 1u;

RAYSTER_CONST uint kMaxShadowLights = 8u;  // one visibility layer each
// Specular rays a reflection/refraction path may trace after the G-buffer surface (the bounce loop
// of specular.rgen); RenderSettings::maxDepth picks 1..this, default kDefaultSpecularBounces.
RAYSTER_CONST uint kMaxSpecularBounces = 8u;
RAYSTER_CONST uint kDefaultSpecularBounces = 7u;  // the loop's historical bound (8 path vertices)
// The queue of specular paths that go on after their first segment (specular.rgen SPECULAR_QUEUE,
// render/passes/rt_specular.cpp): room for one path per kSpecularQueueDivisor pixels, 48 bytes each
// (three uvec4); the last word of a path holds its pixel's index (y·width + x), the next segment's
// number and the glossy flag.
RAYSTER_CONST uint kSpecularQueueDivisor = 4u;
RAYSTER_CONST uint kSpecularQueuePathWords = 12u;
RAYSTER_CONST uint kSpecularQueuePixelMask = 0x07FFFFFFu;
RAYSTER_CONST uint kSpecularQueueBounceShift = 27u;
RAYSTER_CONST uint kSpecularQueueBounceMask = 0xFu;
RAYSTER_CONST uint kSpecularQueueGlossy = 0x80000000u;
// First surfaces rougher than FrameConstants::glossyThreshold fade from traced glossy reflections to
// the environment approximation over this much roughness (lib/specular_weight.glsl); past
// threshold + blend the specular pass traces nothing (render/gpu_scene.h SpecularSurfaces).
RAYSTER_CONST float kGlossyBlend = 0.1;
// Glossy first reflections at least this rough are traced on half the pixels each frame, the other
// half filled by rt-specular-fill (lib/specular_weight.glsl halfRateGlossy()); a scene with no
// opaque surface in that range records no fill pass (render/renderer_impl.h specularFillOn()).
RAYSTER_CONST float kHalfRateRoughness = 0.2;
RAYSTER_CONST uint kDfgSize = 32u;  // split-sum DFG table, kDfgSize² texels (render/dfg.h)
RAYSTER_CONST uint kBackgroundId = 0xFFFFFFFFu;
RAYSTER_CONST uint kNoTexture = 0xFFFFFFFFu;

// MaterialRecord::flags
RAYSTER_CONST uint kMaterialDoubleSided = 1u;
RAYSTER_CONST uint kMaterialAlphaMask = 2u;        // alpha test against alphaCutoff (any-hit, discard)
RAYSTER_CONST uint kMaterialAlphaBlend = 4u;       // stochastic (hashed) coverage, converges over frames
RAYSTER_CONST uint kMaterialCullsBackFaces = 16u;  // scene::Material::cullsBackFaces(): rays ignore back faces
// KHR_materials_unlit: only emits its base colour (× texture × vertex colour), scatters nothing.
// Surface evaluation turns it into emission with zero albedo and specular (lib/surface.glsl), so no
// pass that shades needs to know; the path tracer ends paths there and samples it as an emitter.
RAYSTER_CONST uint kMaterialUnlit = 8u;

// GeometryRecord::kind
RAYSTER_CONST uint kGeometryTriangles = 0u;
RAYSTER_CONST uint kGeometrySpheres = 1u;  // vertexAddress points at SphereRecord[]

// SBT hit-group offsets per geometry kind (instanceShaderBindingTableRecordOffset).
RAYSTER_CONST uint kHitGroupTriangles = 0u;
RAYSTER_CONST uint kHitGroupSpheres = 1u;

// FrameConstants::sceneFlags
RAYSTER_CONST uint kSceneAnyHit =
    1u;  // some geometry runs any-hit (alpha tests, back-face rejection): rays may not be forced opaque

// Tonemap operators (tonemap.comp push constant; render::Tonemapper mirrors them in C++)
RAYSTER_CONST uint kTonemapAces = 0u;
RAYSTER_CONST uint kTonemapNeutral = 1u;
// FrameConstants::effectFlags
RAYSTER_CONST uint kEffectAo = 1u;  // ray-traced ambient occlusion scales ambient/environment light
RAYSTER_CONST uint kEffectIndirect = 2u;
RAYSTER_CONST uint kEffectPrefilteredEnv = 4u;  // untraced glossy light from the GGX-prefiltered environment
// With kEffectIndirect: rt-indirect traces one pixel of each 2×2 block per frame (a quarter-size
// launch, lib/indirect_ray.glsl) and rt-indirect-fill fills the others (--indirect-rate quarter).
RAYSTER_CONST uint kEffectIndirectQuarter = 8u;
// The probes (--gi probes) also give the untraced specular light: their irradiance about the
// mirror direction / π (lighting's indirectSpecularTex), in place of the environment's.
RAYSTER_CONST uint kEffectIndirectSpecular = 16u;
// Lights cast shadows (--shadows, on by default): the shadow layers at the G-buffer surface and the
// shadow rays at every hit of the bounce loops (reflections, indirect, probes). Unset
// (--effects mirrors): every light reaches every point it faces, and no pass traces a shadow ray
// (lib/frame.glsl shadowRaysOn(), lib/shading.glsl shadeLight()).
RAYSTER_CONST uint kEffectShadows = 32u;
// Reflections and refractions are traced (--reflections, on by default). Unset (--effects shadows):
// no surface's specular light is traced (lib/specular_weight.glsl tracedSpecularWeight() is 0), so
// mirrors and glass take the environment approximation as rough surfaces do, and rt-specular is
// not recorded.
RAYSTER_CONST uint kEffectReflections = 64u;
// With kEffectAo: rt-ao traces half the pixels per frame, a checkerboard alternating with the frame
// (a half-width launch, lib/ao_ray.glsl), and rt-ao-fill gives the others the mean of their
// 4-neighbours on the same surface (--ao-rate half).
RAYSTER_CONST uint kEffectAoHalf = 128u;
// Levels of the prefiltered environment (render/gpu_environment.cpp): level k (1..N) is GGX
// roughness k/N, each kPrefilteredWidth × kPrefilteredWidth/2, stacked vertically in one image.
RAYSTER_CONST uint kPrefilteredLevels = 6u;
RAYSTER_CONST uint kPrefilteredWidth = 64u;  // one-bounce ray-traced indirect diffuse replaces ambient/env diffuse

// Environment kinds (FrameConstants::environmentKind)
RAYSTER_CONST uint kEnvironmentBlack = 0u;
RAYSTER_CONST uint kEnvironmentSky = 1u;
RAYSTER_CONST uint kEnvironmentMap = 2u;

struct Vertex {
  vec3 position;  // offset 0: the BLAS reads R32G32B32 positions with this stride
  vec3 normal;
  vec4 tangent;  // xyz tangent, w bitangent sign
  vec2 uv0;
  vec2 uv1;
};

struct SphereRecord {
  vec3 center;
  float radius;
  uint material;
  uint pad0;
  uint pad1;
  uint pad2;
};

// A material's use of a texture: bindless slot (kNoTexture: none), UV set, KHR_texture_transform.
struct TextureSlot {
  uint slot;
  uint texCoord;
  float rotation;
  float lodBias;  // ray cones (lib/textures.glsl): 0.5·log2(texels × |scale.x·scale.y|) of the texture
  vec2 offset;
  vec2 scale;
};

// One per primitive (BLAS geometry): where its vertices and indices live.
struct GeometryRecord {
  uint64_t vertexAddress;
  uint64_t indexAddress;
  uint material;  // triangles; spheres carry their own
  uint vertexCount;
  uint indexCount;
  uint kind;
  // COLOR_0: one RGBA16 UNORM colour per vertex (a uvec2, unpackUnorm2x16 twice), 0: white. A
  // stream of its own, present only where the file has colours, rather than a Vertex member: most
  // scenes have none, and every vertex of every scene would pay 8–16 bytes (14–29 % of Vertex) for
  // them. 16 bits hold 8- and 16-bit sources exactly and float ones to 1.5e-5.
  uint64_t colorAddress;
  // Deforming geometry (render/deform.h): last frame's positions, vec3 per vertex, for the motion
  // vectors; 0: the vertices do not move within the instance (motion is the instance's transform).
  uint64_t prevPositionAddress;
};

// One per TLAS instance; gl_InstanceCustomIndexEXT is its row.
struct InstanceRecord {
  mat4 worldFromObject;
  mat4 normalFromObject;  // inverse transpose of worldFromObject
  uint firstGeometry;     // geometry row = firstGeometry + gl_GeometryIndexEXT
  uint mask;
  uint pad0;
  uint pad1;
  mat4 prevWorldFromObject;  // last frame's transform: object motion in the motion vectors
};

struct MaterialRecord {
  vec4 baseColor;  // linear
  vec3 emissive;   // linear radiance
  float metallic;
  float roughness;
  uint flags;
  float alphaCutoff;
  float normalScale;
  float occlusionStrength;
  float transmission;
  float ior;
  float thickness;
  vec3 attenuationColor;
  float attenuationDistance;
  vec3 specularColor;
  float specular;
  TextureSlot baseColorTexture;  // sRGB view
  TextureSlot metallicRoughnessTexture;
  TextureSlot normalTexture;
  TextureSlot occlusionTexture;
  TextureSlot emissiveTexture;       // sRGB view
  TextureSlot specularTexture;       // KHR_materials_specular: A × specular
  TextureSlot specularColorTexture;  // sRGB view: RGB × specularColor
  TextureSlot transmissionTexture;   // R × transmission
  // MaterialLayers (clearcoat, sheen, iridescence, anisotropy, dispersion), or 0: none of them.
  uint64_t layers;
  uint pad0;
  uint pad1;
};

// The layers above the base of a material (scene::Material; docs/materials.md), one row per
// layered material, reached through MaterialRecord::layers.
struct MaterialLayers {
  float clearcoat;
  float clearcoatRoughness;
  float clearcoatNormalScale;
  float sheenRoughness;
  vec3 sheenColor;  // linear
  float iridescence;
  float iridescenceIor;
  float iridescenceThicknessMin;  // nm
  float iridescenceThicknessMax;  // nm
  float anisotropyStrength;
  float anisotropyRotation;  // radians
  float dispersion;          // 20 / Abbe number
  uint pad0;
  uint pad1;
  TextureSlot clearcoatTexture;           // R
  TextureSlot clearcoatRoughnessTexture;  // G
  TextureSlot clearcoatNormalTexture;
  TextureSlot sheenColorTexture;            // sRGB view: RGB
  TextureSlot sheenRoughnessTexture;        // A
  TextureSlot iridescenceTexture;           // R
  TextureSlot iridescenceThicknessTexture;  // G
  TextureSlot anisotropyTexture;            // RG direction, B strength
};

struct LightRecord {
  vec3 position;
  float radius;   // sphere light radius; 0: hard point light
  vec3 radiance;  // colour × intensity: radiant intensity (point/spot) or irradiance (directional)
  uint type;
  vec3 direction;  // the direction light travels (spot, directional)
  float angularRadius;
  float cosInner;
  float cosOuter;
  uint flags;  // kLightVisibleShape
  uint pad1;
};

// One emissive triangle of the path tracer's light list (render/gpu_emissive.cpp), in world space at
// upload. Picked with probability area / total area (`cdf`: inclusive running sum of that).
struct EmissiveTriangle {
  vec3 p0;
  float cdf;
  vec3 p1;
  uint material;
  vec3 p2;
  float frontSign;  // +1, or −1 under a mirroring transform: cross(p1 − p0, p2 − p0) · frontSign faces front
  vec2 uv0;         // TEXCOORD_0 at the corners: the emissive texture's lookup
  vec2 uv1;
  vec2 uv2;
  uint geometry;  // GeometryRecord row and triangle: vertex colours of unlit emitters
  uint primitive;
};

struct FrameConstants {
  mat4 clipFromWorld;
  mat4 worldFromClip;
  vec4 cameraPosition;  // xyz; w unused
  vec4 ambient;         // rgb: uniform ambient radiance
  uvec2 size;
  uint frameIndex;  // advances every frame; feeds the RNG
  uint seed;        // --seed
  uint lightCount;
  uint shadowLightCount;  // lights with a visibility layer (<= kMaxShadowLights)
  float exposure;         // linear multiplier applied to every light source (render/exposure.h)
  uint environmentKind;
  vec4 environment;  // rgb: intensity × (1,1,1) scale; w: rotation about +Y (radians)
  vec3 skyZenith;
  uint environmentSlot;  // bindless slot of the equirect map
  vec3 skyHorizon;
  uint sceneFlags;  // kScene* bits
  vec3 skyGround;
  uint prefilteredSlot;  // bindless slot of the prefiltered (GGX) environment levels; ~0u: none
  vec4 irradianceSh[9];  // environment irradiance, order-2 spherical harmonics (rgb)
  uint64_t geometries;   // GeometryRecord[]
  uint64_t instances;    // InstanceRecord[]
  uint64_t materials;    // MaterialRecord[]
  uint64_t lights;       // LightRecord[]
  // clipFromWorld and worldFromClip above carry this frame's sub-pixel jitter (TAA), so raster and
  // traced primaries follow it. Motion and reprojection use these unjittered ones (docs/techniques.md §2).
  mat4 unjitteredClipFromWorld;
  mat4 prevClipFromWorld;  // unjittered, the previous frame's (equal to the current one after a reset)
  vec2 jitter;             // NDC offset added to clip x/y per w this frame: (0, 0) without TAA
  uint manyLights;         // 1: one light per shading point by importance (lib/light_select.glsl)
  float mirrorRoughness;   // first surfaces at most this rough reflect as perfect mirrors (negative: none)
  float glossyThreshold;   // up to this roughness reflections trace GGX VNDF samples (docs/techniques.md §13)
  float aoRadius;          // RT AO ray length (world units)
  uint effectFlags;        // kEffect* bits
  uint dfgSlot;            // bindless slot of the split-sum DFG table (render/dfg.h)
  // Path tracer (shaders/pathtrace.rgen.glsl).
  uint64_t emissiveTriangles;  // EmissiveTriangle[] (render/gpu_emissive.cpp)
  uint64_t environmentCdf;     // float[]: cell probabilities, row CDFs, marginal CDF (render/gpu_environment.cpp)
  uint emissiveTriangleCount;
  float emissiveArea;        // Σ area of the emissive triangles
  uint environmentCdfWidth;  // cells of the environment CDF (0: no environment sampling)
  uint environmentCdfHeight;
  uint maxDepth;            // path vertices after the camera (--max-depth)
  uint maxSpecularBounces;  // specular.rgen traces at most this many rays per path (1..kMaxSpecularBounces)
  // Layer of the AO image that rt-ao writes and lighting reads: shadowLightCount when AO is on in
  // the hybrid (AO is the shadow denoiser's last layer, renderer_frame.cpp), else 0 (its own image).
  uint aoLayer;
  // This frame's exposure over the previous frame's (1 after a cut): radiance that histories of the
  // previous frame hold was pre-exposed with the old exposure and is multiplied by this when read.
  float exposureRatio;
  uint sheenSlot;  // bindless slot of the sheen albedo table (shared/sheen.h; render/gpu_environment.cpp), R16F
};

// GPU culling (render/passes/cull.cpp, docs/techniques.md §23): one row per GpuScene::Draw, in order.
RAYSTER_CONST uint kDrawSpheres = 1u;  // DrawRecord::flags: a sphere set (36-vertex boxes, count instances)
RAYSTER_CONST uint kCullGroupSize = 64u;
struct DrawRecord {
  uint instance;  // InstanceRecord row
  uint geometry;  // GeometryRecord row
  uint count;     // triangles: index count; spheres: sphere count
  uint flags;     // kDrawSpheres
  vec3 aabbMin;   // object space (deforming draws: rewritten with each pose, render/deform.h)
  vec3 aabbMax;
};

// CullPush::flags
RAYSTER_CONST uint kCullFrustum = 1u;  // 0 (--culling off): every draw passes, into the early lists
RAYSTER_CONST uint kCullLate = 2u;     // the late phase: test against this frame's depth pyramid

// Two-phase culling (render/passes/cull.h): the early phase appends the frustum-visible draws that
// were visible last frame, the late phase those the pyramid of the early depth does not hide and
// the early phase skipped. The indirect lists: early triangles, early spheres, late triangles,
// late spheres, each with drawCount slots and a count.
RAYSTER_CONST uint kCullLists = 4u;
struct CullPush {
  uint64_t records;     // DrawRecord[drawCount]
  uint64_t commands;    // VkDrawIndirectCommand[kCullLists * drawCount]
  uint64_t drawIds;     // uint[kCullLists * drawCount]: the DrawRecord row of each command
  uint64_t counts;      // uint[kCullLists]: commands per list (the draw-count buffer)
  uint64_t visibility;  // uint[drawCount]: 1 if visible in the last late phase (kept across frames)
  uint64_t hiz;         // the depth pyramid's float depths, level 0 first
  uint drawCount;
  uint flags;  // kCull*
};

// The depth pyramid (render/passes/cull.cpp): level 0 (the depth image's size) to the 1 × 1 level,
// each ceil(previous / 2) and row-major, holding the MIN depth of the texels it covers (reversed Z:
// the farthest). Kept in a buffer, so no per-level image views are needed.
RAYSTER_CONST uint kHizGroupSize = 8u;
// The occlusion test reads the pyramid level where a box's screen rectangle spans at most this many
// texels per axis (shaders/cull.comp.glsl).
RAYSTER_CONST uint kHizFootprint = 4u;

// hiz.comp push constants: one dispatch per level.
struct HizPush {
  uint64_t hiz;
  uint level;  // 0: from the depth image; k: from level k − 1
  uint pad0;
};

// Skinning and morph targets (render/deform.cpp, shaders/deform.comp.glsl): one dispatch per
// deforming (instance, primitive), kDeformGroupSize vertices per group.
RAYSTER_CONST uint kDeformGroupSize = 64u;
// One vertex's influences in one set (scene::SkinInfluences): joints as 16-bit halves (low first).
struct SkinInfluence {
  uvec2 joints;
  vec4 weights;
};
struct DeformPush {
  uint64_t restVertices;   // Vertex[vertexCount]: the mesh's primitive, as uploaded
  uint64_t outVertices;    // Vertex[vertexCount]: what this instance draws and traces
  uint64_t prevPositions;  // vec3[vertexCount]: outVertices' positions of the frame before
  uint64_t influences;     // SkinInfluence[influenceSets × vertexCount], set-major; 0: not skinned
  uint64_t joints;         // mat4[]: the skin's joint matrices this frame (world × inverse bind)
  uint64_t targets;        // vec3[targetCount × 3 × vertexCount]: target t's position, normal, tangent deltas
  uint64_t weights;        // float[targetCount]: this frame's morph weights
  uint vertexCount;
  uint influenceSets;
  uint targetCount;
  uint keepPrevious;  // 0 (the first frame of a run): the previous positions are this frame's
};

#ifdef __cplusplus
static_assert(sizeof(Vertex) == 56);
static_assert(sizeof(SphereRecord) == 32);
static_assert(sizeof(TextureSlot) == 32);
static_assert(sizeof(GeometryRecord) == 48);
static_assert(sizeof(SkinInfluence) == 24);
static_assert(sizeof(DeformPush) == 72);
static_assert(offsetof(GeometryRecord, colorAddress) == 32);
static_assert(sizeof(InstanceRecord) == 208);
static_assert(offsetof(InstanceRecord, firstGeometry) == 128);
static_assert(offsetof(MaterialRecord, baseColorTexture) == 96);
static_assert(offsetof(MaterialRecord, specularTexture) == 256);
static_assert(offsetof(MaterialRecord, layers) == 352);
static_assert(sizeof(MaterialRecord) == 368);
static_assert(sizeof(MaterialLayers) == 320);
static_assert(sizeof(LightRecord) == 64);
static_assert(offsetof(FrameConstants, size) == 160);
static_assert(offsetof(FrameConstants, environment) == 192);
static_assert(offsetof(FrameConstants, irradianceSh) == 256);
static_assert(offsetof(FrameConstants, geometries) == 400);
static_assert(offsetof(FrameConstants, lights) == 424);
static_assert(offsetof(FrameConstants, unjitteredClipFromWorld) == 432);
static_assert(offsetof(FrameConstants, prevClipFromWorld) == 496);
static_assert(offsetof(FrameConstants, jitter) == 560);
static_assert(offsetof(FrameConstants, mirrorRoughness) == 572);
static_assert(sizeof(EmissiveTriangle) == 80);
static_assert(offsetof(FrameConstants, emissiveTriangles) == 592);
static_assert(offsetof(FrameConstants, maxSpecularBounces) == 628);
static_assert(sizeof(FrameConstants) == 648);
static_assert(sizeof(DrawRecord) == 40);
static_assert(offsetof(DrawRecord, aabbMin) == 16);
static_assert(sizeof(CullPush) == 56);
static_assert(sizeof(HizPush) == 16);
}  // namespace rayster::gpu
#endif

#endif
