#pragma once
// The CPU scene model every loader produces and every renderer consumes. Plain data, no Vulkan:
// render/ uploads it, tests inspect it directly.
#include <array>
#include <cfloat>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_precision.hpp>

#include "core/error.h"

namespace rayster::scene {

// A texture as a material uses it: which texture, which UV set, and KHR_texture_transform.
struct TextureRef {
  int32_t texture = -1;   // index into Scene::textures; -1: none
  uint32_t texCoord = 0;  // UV set (0 or 1)
  glm::vec2 offset{0.0f};
  glm::vec2 scale{1.0f};
  float rotation = 0.0f;  // radians, counter-clockwise in UV space (KHR_texture_transform)
  bool valid() const { return texture >= 0; }
};

enum class AlphaMode { Opaque, Mask, Blend };

// glTF 2.0 metallic-roughness with the KHR_materials_* extensions Rayster renders.
struct Material {
  std::string name;
  glm::vec4 baseColor{1.0f};  // linear; alpha is coverage
  float metallic = 0.0f;
  float roughness = 1.0f;
  glm::vec3 emissive{0.0f};  // linear radiance, KHR_materials_emissive_strength folded in
  bool doubleSided = false;
  TextureRef baseColorTexture;          // sRGB
  TextureRef metallicRoughnessTexture;  // linear: G roughness, B metallic
  TextureRef normalTexture;             // linear, tangent space
  TextureRef occlusionTexture;          // linear: R
  TextureRef emissiveTexture;           // sRGB
  float normalScale = 1.0f;
  float occlusionStrength = 1.0f;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  float transmission = 0.0f;  // KHR_materials_transmission
  float ior = 1.5f;           // KHR_materials_ior
  float thickness = 0.0f;     // KHR_materials_volume; 0: thin-walled
  glm::vec3 attenuationColor{1.0f};
  float attenuationDistance = FLT_MAX;
  // KHR_materials_specular: the dielectric lobe's strength (F0 and F90) and its F0 tint.
  float specular = 1.0f;            // [0, 1]
  glm::vec3 specularColor{1.0f};    // linear, >= 0; may exceed 1 (F0 × colour is clamped to 1)
  TextureRef specularTexture;       // linear: A multiplies specular
  TextureRef specularColorTexture;  // sRGB: RGB multiplies specularColor
  // KHR_materials_unlit: the surface shows its base colour (× vertex colour × texture) as emitted
  // radiance and scatters no light (docs in render/gpu_materials.cpp).
  bool unlit = false;
  TextureRef transmissionTexture;  // KHR_materials_transmission: R × transmission
  TextureRef thicknessTexture;     // KHR_materials_volume: G × thickness

  // The layers on top of the base (docs/materials.md); each is off at its default.
  // KHR_materials_clearcoat: a GGX dielectric coat (η 1.5) with its own roughness and normal.
  float clearcoat = 0.0f;                // [0, 1]
  float clearcoatRoughness = 0.0f;       // [0, 1]
  TextureRef clearcoatTexture;           // linear: R × clearcoat
  TextureRef clearcoatRoughnessTexture;  // linear: G × clearcoatRoughness
  TextureRef clearcoatNormalTexture;     // linear, tangent space; none: the geometric shading normal
  float clearcoatNormalScale = 1.0f;
  // KHR_materials_sheen: a Charlie-distribution retro-reflective layer (cloth, velvet).
  glm::vec3 sheenColor{0.0f};        // linear, [0, 1]
  float sheenRoughness = 0.0f;       // [0, 1]
  TextureRef sheenColorTexture;      // sRGB: RGB × sheenColor
  TextureRef sheenRoughnessTexture;  // linear: A × sheenRoughness
  // KHR_materials_iridescence: a thin film (Belcour and Barla 2017) on the specular lobe.
  float iridescence = 0.0f;                // [0, 1]
  float iridescenceIor = 1.3f;             // >= 1
  float iridescenceThicknessMin = 100.0f;  // nm
  float iridescenceThicknessMax = 400.0f;  // nm
  TextureRef iridescenceTexture;           // linear: R × iridescence
  TextureRef iridescenceThicknessTexture;  // linear: G mixes min → max (none: max)
  // KHR_materials_anisotropy: GGX stretched along a direction in the tangent plane.
  float anisotropyStrength = 0.0f;  // [0, 1]
  float anisotropyRotation = 0.0f;  // radians, counter-clockwise from the tangent
  TextureRef anisotropyTexture;     // linear: RG direction in [-1, 1]², B × strength
  // KHR_materials_dispersion: 20 / Abbe number; 0: the same η for every wavelength.
  float dispersion = 0.0f;

  bool hasClearcoat() const { return clearcoat > 0.0f; }
  bool hasSheen() const { return sheenColor != glm::vec3(0.0f); }
  bool hasIridescence() const { return iridescence > 0.0f; }
  bool hasAnisotropy() const { return anisotropyStrength > 0.0f; }
  // Whether any layer above applies (the GPU gets a layer record only then).
  bool layered() const {
    return !unlit && (hasClearcoat() || hasSheen() || hasIridescence() || hasAnisotropy() || dispersion > 0.0f);
  }

  // Every texture slot, for code that treats them alike (merging scenes, counting uses).
  std::array<TextureRef*, 17> textureRefs() {
    return {&baseColorTexture,
            &metallicRoughnessTexture,
            &normalTexture,
            &occlusionTexture,
            &emissiveTexture,
            &specularTexture,
            &specularColorTexture,
            &transmissionTexture,
            &thicknessTexture,
            &clearcoatTexture,
            &clearcoatRoughnessTexture,
            &clearcoatNormalTexture,
            &sheenColorTexture,
            &sheenRoughnessTexture,
            &iridescenceTexture,
            &iridescenceThicknessTexture,
            &anisotropyTexture};
  }
  std::array<const TextureRef*, 17> textureRefs() const {
    std::array<const TextureRef*, 17> out;
    const auto refs = const_cast<Material*>(this)->textureRefs();
    for (size_t i = 0; i < refs.size(); ++i) out[i] = refs[i];
    return out;
  }

  // glTF: a single-sided material's back faces are not rendered, and rays ignore them. Transmissive
  // materials are the exception for rays: a refracted ray leaves a closed volume through its back
  // faces, so culling them would trap it inside (the raster G-buffer still culls them).
  bool cullsBackFaces() const { return !doubleSided && transmission <= 0.0f; }
};

// Decoded 8-bit RGBA pixels, as stored in a file (sRGB or linear is decided by the use).
struct ImageData {
  std::string name;
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };
enum class Filter { Nearest, Linear };
struct Sampler {
  Wrap wrapS = Wrap::Repeat, wrapT = Wrap::Repeat;
  Filter magFilter = Filter::Linear, minFilter = Filter::Linear;
  bool mipmaps = true;
};

struct Texture {
  uint32_t image = 0;
  uint32_t sampler = 0;  // index into Scene::samplers
};

// One set of skinning influences (JOINTS_n and WEIGHTS_n): per vertex four joints (indices into
// the skin's joint list) and their weights. Weights of all sets of a vertex sum to 1.
struct SkinInfluences {
  std::vector<glm::u16vec4> joints;
  std::vector<glm::vec4> weights;
};

// A morph target: per-vertex displacements added with the target's weight. An empty attribute
// displaces nothing.
struct MorphTarget {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec3> tangents;  // xyz only: the bitangent sign is not morphed
};

struct Primitive {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec4> tangents;  // xyz tangent, w bitangent sign; may be empty (generated on upload)
  std::vector<glm::vec2> uvs;       // UV set 0; may be empty
  std::vector<glm::vec2> uvs1;      // UV set 1; may be empty
  std::vector<glm::vec4> colors;    // COLOR_0, linear RGBA in [0, 1], multiplies the base colour; empty: white
  std::vector<uint32_t> indices;    // triangle list, counter-clockwise seen from the front
  uint32_t material = 0;
  // KHR_materials_variants: (variant, material) pairs, indices into Scene::variants and
  // Scene::materials; selectVariant() applies one. `defaultMaterial` is `material` as loaded.
  std::vector<std::pair<uint32_t, uint32_t>> variantMaterials;
  uint32_t defaultMaterial = 0;
  std::vector<SkinInfluences> influences;  // JOINTS_0/WEIGHTS_0, JOINTS_1/WEIGHTS_1, …; empty: not skinned
  std::vector<MorphTarget> targets;        // as many as the mesh's morph weights
};

// Analytic sphere, traced as AABB geometry with an intersection shader.
struct Sphere {
  glm::vec3 center{0.0f};
  float radius = 1.0f;
  uint32_t material = 0;
};

// A mesh holds triangle primitives or spheres, never both (one BLAS each).
struct Mesh {
  std::string name;
  std::vector<Primitive> primitives;
  std::vector<Sphere> spheres;
  std::vector<float> weights;  // default morph weights, one per target of every primitive
};

// A glTF skin: the nodes that pose a skinned mesh and their inverse bind matrices. A skinned
// vertex lands at Σ weight × worldFromNode[joint] × inverseBind[joint] × position, in world space:
// the skinned mesh's own node transform does not apply (glTF 2.0 §3.7.3.3).
struct Skin {
  std::string name;
  std::vector<uint32_t> joints;                // indices into Scene::nodes
  std::vector<glm::mat4> inverseBindMatrices;  // one per joint
};

struct Instance {
  std::string name;
  uint32_t mesh = 0;
  glm::mat4 worldFromObject{1.0f};
  bool castsShadows = true;  // false for the visible shape of an area light
  // The node (index into Scene::nodes) whose world transform this instance takes when animations
  // are evaluated; -1: static. Loaders set it only where an animation moves the node or a parent,
  // so a renderer can refit just these instances.
  int32_t node = -1;
  // Deformation (scene/skinning.h): the skin (index into Scene::skins, -1: none) and the morph
  // weights (empty: the mesh's defaults). A skinned instance's worldFromObject is the identity.
  int32_t skin = -1;
  std::vector<float> morphWeights;
};

// A node of the glTF hierarchy, kept so that animation can recompute instance transforms.
// Scene::nodes lists parents before their children (parent < own index), so one forward pass
// computes every world matrix.
struct SceneNode {
  std::string name;
  int32_t parent = -1;  // index into Scene::nodes; -1: a root
  // Local transform: TRS as glTF gives it, or a fixed matrix (glTF forbids animating those).
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z; unit length
  glm::vec3 scale{1.0f};
  bool hasMatrix = false;
  glm::mat4 matrix{1.0f};
  glm::mat4 worldFromNode{1.0f};  // as of the last load or evaluateAnimations()
  std::vector<float> weights;     // morph weights of the node's mesh; empty: the mesh's defaults

  glm::mat4 parentFromNode() const;  // the local transform as a matrix
};

// One animated property of one node, sampled as glTF 2.0 says.
struct AnimationChannel {
  uint32_t node = 0;  // index into Scene::nodes
  enum Path { Translation, Rotation, Scale, Weights } path = Translation;
  enum Interp { Step, Linear, CubicSpline } interp = Linear;
  std::vector<float> times;  // seconds, strictly increasing, >= 0
  // One value per key (xyz for translation and scale, quaternion xyzw for rotation, as glTF
  // stores it); CubicSpline holds in-tangent, value, out-tangent for each key, 3 × times.size().
  std::vector<glm::vec4> values;
  // Weights: `weightCount` morph weights per key (× 3 for CubicSpline, as above), key after key;
  // `values` is unused.
  std::vector<float> weights;
  uint32_t weightCount = 0;
};

struct Animation {
  std::string name;
  std::vector<AnimationChannel> channels;
  float duration = 0.0f;  // seconds: the last key time over all channels
};

enum class LightType { Point, Spot, Directional };

struct Light {
  std::string name;
  LightType type = LightType::Point;
  glm::vec3 position{0.0f};
  glm::vec3 direction{0, -1, 0};  // direction light travels, for spot/directional
  glm::vec3 color{1.0f};
  float intensity = 1.0f;      // W/sr-like radiant intensity for point/spot; irradiance for directional
  float radius = 0.0f;         // sphere light radius, 0 = hard point
  float angularRadius = 0.0f;  // directional, radians
  float innerConeAngle = 0.0f, outerConeAngle = 0.7853982f;
  int32_t node = -1;  // an animated node it follows (at its origin, shining down its -Z); -1: fixed
  // An emissive mesh of the scene shows it (the built-in sphere lights): rays that hit the mesh see
  // the light, so its highlight on traced surfaces is theirs; otherwise lighting adds it.
  bool visibleShape = false;
};

struct Camera {
  std::string name;
  glm::vec3 position{0, 0, 5};
  glm::vec3 target{0.0f};
  glm::vec3 up{0, 1, 0};
  float yFov = 0.7f;  // radians
  float zNear = 0.05f;
  float zFar = 100.0f;
  int32_t node = -1;  // an animated node it follows (at its origin, looking down its -Z); -1: fixed
};

// Light arriving from infinity where rays escape: nothing, a procedural sky, or an HDR map.
struct Environment {
  enum class Kind { Black, Sky, Map } kind = Kind::Black;
  std::string mapPath;  // for Map: the equirectangular .hdr/.exr it was read from
  int width = 0, height = 0;
  std::vector<float> rgb;  // Map: linear RGB, width × height × 3, top row first (+Y up)
  float intensity = 1.0f;
  float rotation = 0.0f;                 // radians about +Y
  glm::vec3 zenith{0.25f, 0.45f, 0.9f};  // Sky
  glm::vec3 horizon{0.85f, 0.9f, 1.0f};
  glm::vec3 ground{0.3f, 0.28f, 0.25f};
};

// A keyframed camera path for animated and benchmark runs; linear between keys.
struct CameraKey {
  float time = 0.0f;  // seconds
  glm::vec3 position{0.0f};
  glm::vec3 target{0.0f};
};

struct Aabb {
  glm::vec3 min{FLT_MAX}, max{-FLT_MAX};
  void extend(glm::vec3 p);
  bool valid() const;
  glm::vec3 centre() const { return (min + max) * 0.5f; }
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<ImageData> images;
  std::vector<Sampler> samplers;
  std::vector<Texture> textures;
  std::vector<Instance> instances;
  std::vector<SceneNode> nodes;  // the hierarchy behind animated instances; may be empty
  std::vector<Skin> skins;
  std::vector<Animation> animations;  // all play together (see scene/animation.h)
  std::vector<std::string> variants;  // KHR_materials_variants names (Primitive::variantMaterials)
  std::vector<Light> lights;
  std::vector<Camera> cameras;
  std::vector<CameraKey> cameraPath;
  Environment environment;
  glm::vec3 ambient{0.0f};       // uniform ambient radiance, stand-in for indirect light when RT indirect is off
  Aabb bounds() const;           // world-space, over all instances
  size_t triangleCount() const;  // over all instances, i.e. what the TLAS holds
  bool animated() const { return !animations.empty(); }
};

// Checks what the renderer would otherwise crash on or silently mis-draw. Failures are
// ExitCode::BadInput with a message naming the mesh/primitive/instance.
Status validate(const Scene& scene);

// KHR_materials_variants: gives every primitive the material the variant `name` maps it to, and
// the rest their default material; "" restores every default. An unknown name is
// ExitCode::BadInput naming the variants the scene has.
Status selectVariant(Scene& scene, const std::string& name);

}  // namespace rayster::scene
