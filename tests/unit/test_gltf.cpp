// glTF loading: geometry, accessors, hierarchy, cameras, lights and materials from small
// documents built in the test. Refusals are in test_gltf_reject.cpp.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "core/image_io.h"
#include "gltf_test_util.h"

using namespace rayster;
using namespace rayster::test;
using scene::Scene;

namespace {

void expectNear(glm::vec3 a, glm::vec3 b, float eps = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

Scene mustLoad(const TempDir& dir, const std::string& bytes, const std::string& name = "test.gltf") {
  Result<Scene> scene = loadBytes(dir, bytes, name);
  EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error().message);
  return scene.ok() ? std::move(scene).value() : Scene{};
}

const scene::Primitive& firstPrimitive(const Scene& s) {
  static const scene::Primitive none;
  if (s.meshes.empty() || s.meshes[0].primitives.empty()) return none;
  return s.meshes[0].primitives[0];
}

TEST(GltfLoad, QuadHasPositionsNormalsUvsIndices) {
  TempDir dir;
  Doc d = quadDoc();
  Scene s = mustLoad(dir, d.gltf());
  ASSERT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.instances.size(), 1u);
  EXPECT_EQ(s.meshes[0].name, "quad");
  const scene::Primitive& p = firstPrimitive(s);
  ASSERT_EQ(p.positions.size(), 4u);
  expectNear(p.positions[2], {1, 1, 0});
  expectNear(p.normals[3], {0, 0, 1});
  ASSERT_EQ(p.uvs.size(), 4u);
  EXPECT_FLOAT_EQ(p.uvs[1].x, 1.0f);
  EXPECT_FLOAT_EQ(p.uvs[1].y, 1.0f);
  EXPECT_EQ(p.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_TRUE(p.tangents.empty());
  EXPECT_TRUE(s.cameras.empty()) << "a camera-less file gets its default later, in applyDefaults";
  // No material on the primitive: one default material.
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(p.material, 0u);
}

TEST(GltfLoad, GlbAndExternalBinLoadTheSame) {
  TempDir dir;
  Doc d = quadDoc();
  Scene glb = mustLoad(dir, d.glb(), "quad.glb");
  EXPECT_EQ(firstPrimitive(glb).indices.size(), 6u);
  std::string bin(d.bin.begin(), d.bin.end());
  dir.write("sub/quad.bin", bin);
  Scene external = mustLoad(dir, d.gltf("quad.bin"), "sub/quad.gltf");
  EXPECT_EQ(firstPrimitive(external).positions, firstPrimitive(glb).positions);
}

TEST(GltfLoad, NodeTransformsCompose) {
  TempDir dir;
  Doc d = quadDoc();
  // parent: translate (10,0,0), scale 2; child: matrix translating (0,1,0), holding the mesh.
  d.j["nodes"] =
      Json::array({{{"name", "parent"}, {"translation", {10, 0, 0}}, {"scale", {2, 2, 2}}, {"children", {1}}},
                   {{"name", "child"}, {"mesh", 0}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 1}}}});
  Scene s = mustLoad(dir, d.gltf());
  ASSERT_EQ(s.instances.size(), 1u);
  EXPECT_EQ(s.instances[0].name, "child");
  const glm::vec3 world = glm::vec3(s.instances[0].worldFromObject * glm::vec4(1, 0, 0, 1));
  expectNear(world, {12, 2, 0});
}

TEST(GltfLoad, TwoNodesShareOneMesh) {
  TempDir dir;
  Doc d = quadDoc();
  d.j["nodes"] = Json::array({{{"mesh", 0}}, {{"mesh", 0}, {"translation", {0, 0, -3}}}});
  d.j["scenes"][0]["nodes"] = {0, 1};
  Scene s = mustLoad(dir, d.gltf());
  EXPECT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.instances.size(), 2u);
  EXPECT_EQ(s.instances[0].mesh, s.instances[1].mesh);
  EXPECT_FLOAT_EQ(s.instances[1].worldFromObject[3].z, -3.0f);
}

TEST(GltfLoad, NoScenesMeansAllRootNodes) {
  TempDir dir;
  Doc d = quadDoc();
  d.j.erase("scenes");
  d.j.erase("scene");
  d.j["nodes"] = Json::array({{{"mesh", 0}, {"children", {1}}}, {{"mesh", 0}}, {{"mesh", 0}}});
  Scene s = mustLoad(dir, d.gltf());
  EXPECT_EQ(s.instances.size(), 3u);
}

TEST(GltfLoad, NormalizedUnsignedShortUvs) {
  TempDir dir;
  Doc d = quadDoc();
  const int uv =
      d.accessor(d.view(std::vector<uint16_t>{0, 65535, 65535, 65535, 65535, 0, 32768, 0}), kUShort, 4, "VEC2", true);
  primitive(d)["attributes"]["TEXCOORD_0"] = uv;
  Scene s = mustLoad(dir, d.gltf());
  const scene::Primitive& p = firstPrimitive(s);
  ASSERT_EQ(p.uvs.size(), 4u);
  EXPECT_FLOAT_EQ(p.uvs[0].x, 0.0f);
  EXPECT_FLOAT_EQ(p.uvs[0].y, 1.0f);
  EXPECT_NEAR(p.uvs[3].x, 0.5f, 1e-4f);
  for (glm::vec2 uv2 : p.uvs) EXPECT_TRUE(uv2.x >= 0 && uv2.x <= 1 && uv2.y >= 0 && uv2.y <= 1);
}

TEST(GltfLoad, NormalizedSignedBytesClampToMinusOne) {
  TempDir dir;
  Doc d = quadDoc();
  // -128 and -127 both map to -1 (the spec's max(c / 127, -1)).
  std::vector<int8_t> n = {0, 0, 127, 0, 0, -128, 0, 0, -127, 0, 0, 127};
  primitive(d)["attributes"]["NORMAL"] = d.accessor(d.view(n), kByte, 4, "VEC3", true);
  Scene s = mustLoad(dir, d.gltf());
  const scene::Primitive& p = firstPrimitive(s);
  EXPECT_FLOAT_EQ(p.normals[0].z, 1.0f);
  EXPECT_FLOAT_EQ(p.normals[1].z, -1.0f);
  EXPECT_FLOAT_EQ(p.normals[2].z, -1.0f);
}

TEST(GltfLoad, SparseAccessorOverridesVertices) {
  TempDir dir;
  Doc d = quadDoc();
  const int idxView = d.view(std::vector<uint16_t>{1, 3});
  const int valView = d.view(std::vector<float>{5, 5, 5, 7, 7, 7});
  Json& pos = d.j["accessors"][0];
  pos["sparse"] = {{"count", 2},
                   {"indices", {{"bufferView", idxView}, {"componentType", kUShort}}},
                   {"values", {{"bufferView", valView}}}};
  Scene s = mustLoad(dir, d.gltf());
  const scene::Primitive& p = firstPrimitive(s);
  expectNear(p.positions[0], {0, 0, 0});
  expectNear(p.positions[1], {5, 5, 5});
  expectNear(p.positions[2], {1, 1, 0});
  expectNear(p.positions[3], {7, 7, 7});
}

TEST(GltfLoad, SparseAccessorWithoutBufferViewStartsFromZeros) {
  TempDir dir;
  Doc d = quadDoc();
  const int idxView = d.view(std::vector<uint8_t>{2, 0, 0, 0});
  const int valView = d.view(std::vector<float>{0, 0, 1});
  const int offsets = d.accessor(-1, kFloat, 4, "VEC3");
  d.j["accessors"][size_t(offsets)]["sparse"] = {{"count", 1},
                                                 {"indices", {{"bufferView", idxView}, {"componentType", kUByte}}},
                                                 {"values", {{"bufferView", valView}}}};
  primitive(d)["attributes"]["NORMAL"] = offsets;
  Scene s = mustLoad(dir, d.gltf());
  const scene::Primitive& p = firstPrimitive(s);
  expectNear(p.normals[0], {0, 0, 0});
  expectNear(p.normals[2], {0, 0, 1});
}

TEST(GltfLoad, ByteStrideHonoured) {
  TempDir dir;
  Doc d = quadDoc();
  // Interleaved position + normal, 24 bytes per vertex.
  const int view =
      d.view(std::vector<float>{0, 0, 0, 0, 0, 1, 2, 0, 0, 0, 0, 1, 2, 2, 0, 0, 0, 1, 0, 2, 0, 0, 0, 1}, 24);
  primitive(d)["attributes"]["POSITION"] = d.accessor(view, kFloat, 4, "VEC3");
  primitive(d)["attributes"]["NORMAL"] = d.accessor(view, kFloat, 4, "VEC3", false, 12);
  Scene s = mustLoad(dir, d.gltf());
  const scene::Primitive& p = firstPrimitive(s);
  expectNear(p.positions[1], {2, 0, 0});
  expectNear(p.positions[2], {2, 2, 0});
  expectNear(p.normals[3], {0, 0, 1});
}

TEST(GltfLoad, NonIndexedGetsSequentialIndices) {
  TempDir dir;
  Doc d = quadDoc();
  primitive(d).erase("indices");
  primitive(d)["attributes"] = {
      {"POSITION", d.floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3", 3)}};
  Scene s = mustLoad(dir, d.gltf());
  const scene::Primitive& p = firstPrimitive(s);
  EXPECT_EQ(p.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
  // No normals in the file: flat normals, as the spec asks.
  ASSERT_EQ(p.normals.size(), 6u);
  expectNear(p.normals[4], {0, 0, 1});
}

TEST(GltfLoad, MissingNormalsAreFlatOnSharedVertices) {
  TempDir dir;
  Doc d = quadDoc();
  // Fold the quad along its diagonal: vertex 3 moves to z = 1, so the two triangles differ.
  primitive(d)["attributes"] = {{"POSITION", d.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 1}, "VEC3", 3)}};
  Scene s = mustLoad(dir, d.gltf());
  const scene::Primitive& p = firstPrimitive(s);
  ASSERT_EQ(p.positions.size(), 6u) << "shared vertices are split so each face keeps its own normal";
  expectNear(p.normals[0], {0, 0, 1});
  EXPECT_NEAR(glm::length(p.normals[5]), 1.0f, 1e-5f);
  EXPECT_GT(glm::length(p.normals[5] - p.normals[0]), 0.1f);
}

TEST(GltfLoad, CameraFromRotatedNode) {
  TempDir dir;
  Doc d = quadDoc();
  const float h = std::sqrt(0.5f);  // 90 degrees about +Y: local -Z looks down world -X
  d.j["cameras"] = Json::array(
      {{{"type", "perspective"}, {"name", "cam"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}, {"zfar", 50}}}}});
  d.j["nodes"].push_back({{"name", "eye"}, {"camera", 0}, {"translation", {5, 0, 0}}, {"rotation", {0, h, 0, h}}});
  d.j["scenes"][0]["nodes"] = {0, 1};
  Scene s = mustLoad(dir, d.gltf());
  ASSERT_EQ(s.cameras.size(), 1u);
  const scene::Camera& c = s.cameras[0];
  EXPECT_EQ(c.name, "eye");
  expectNear(c.position, {5, 0, 0});
  expectNear(c.target, {4, 0, 0});
  expectNear(c.up, {0, 1, 0});
  EXPECT_FLOAT_EQ(c.yFov, 0.5f);
  EXPECT_FLOAT_EQ(c.zNear, 0.1f);
  EXPECT_FLOAT_EQ(c.zFar, 50.0f);
}

TEST(GltfLoad, PunctualLights) {
  TempDir dir;
  Doc d = quadDoc();
  d.j["extensionsUsed"] = {"KHR_lights_punctual"};
  d.j["extensions"]["KHR_lights_punctual"]["lights"] =
      Json::array({{{"type", "point"},
                    {"name", "bulb"},
                    {"color", {1, 0.5, 0.25}},
                    {"intensity", 20},
                    {"extras", {{"radius", 0.5}}}},
                   {{"type", "spot"}, {"intensity", 30}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.4}}}},
                   {{"type", "directional"}, {"intensity", 3}, {"extras", {{"angularRadius", 0.01}}}}});
  const float h = std::sqrt(0.5f);  // -90 degrees about +X: local -Z points down world -Y
  d.j["nodes"].push_back({{"translation", {0, 3, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  d.j["nodes"].push_back(
      {{"name", "spot"}, {"translation", {1, 2, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  d.j["nodes"].push_back({{"rotation", {-h, 0, 0, h}}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
  d.j["scenes"][0]["nodes"] = {0, 1, 2, 3};
  Scene s = mustLoad(dir, d.gltf());
  ASSERT_EQ(s.lights.size(), 3u);
  EXPECT_EQ(s.lights[0].type, scene::LightType::Point);
  EXPECT_EQ(s.lights[0].name, "bulb");
  expectNear(s.lights[0].position, {0, 3, 0});
  expectNear(s.lights[0].color, {1, 0.5f, 0.25f});
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 20.0f);
  EXPECT_FLOAT_EQ(s.lights[0].radius, 0.5f);
  EXPECT_EQ(s.lights[1].type, scene::LightType::Spot);
  EXPECT_EQ(s.lights[1].name, "spot");
  expectNear(s.lights[1].position, {1, 2, 3});
  expectNear(s.lights[1].direction, {0, 0, -1});
  EXPECT_FLOAT_EQ(s.lights[1].innerConeAngle, 0.2f);
  EXPECT_FLOAT_EQ(s.lights[1].outerConeAngle, 0.4f);
  EXPECT_EQ(s.lights[2].type, scene::LightType::Directional);
  expectNear(s.lights[2].direction, {0, -1, 0});
  EXPECT_FLOAT_EQ(s.lights[2].angularRadius, 0.01f);
  EXPECT_FLOAT_EQ(s.lights[2].intensity, 3.0f);
}

TEST(GltfLoad, MaterialsWithExtensionsAndTextures) {
  TempDir dir;
  Image8 pixels = Image8::make(2, 3);
  pixels.rgba[0] = 255;
  ASSERT_TRUE(writePng(dir.path() / "tex.png", pixels).ok());
  Doc d = quadDoc();
  d.j["images"] = Json::array({{{"uri", "tex.png"}}});
  d.j["samplers"] = Json::array({{{"magFilter", 9728}, {"minFilter", 9729}, {"wrapS", 33071}, {"wrapT", 33648}}});
  d.j["textures"] = Json::array({{{"source", 0}, {"sampler", 0}}, {{"source", 0}}});
  d.j["materials"] = Json::parse(R"([
    {"name": "glass",
     "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.6, 0.7, 0.8], "metallicFactor": 0.25,
       "roughnessFactor": 0.75,
       "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform":
         {"offset": [0.5, 0.25], "scale": [2, 3], "rotation": 0.5, "texCoord": 1}}}},
     "normalTexture": {"index": 1, "scale": 0.5}, "occlusionTexture": {"index": 0, "strength": 0.3},
     "emissiveTexture": {"index": 0}, "emissiveFactor": [1, 0.5, 0.25], "doubleSided": true,
     "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4},
       "KHR_materials_transmission": {"transmissionFactor": 0.9}, "KHR_materials_ior": {"ior": 1.33},
       "KHR_materials_volume": {"thicknessFactor": 0.1, "attenuationColor": [0.9, 0.8, 0.7],
         "attenuationDistance": 2},
       "KHR_materials_specular": {"specularFactor": 0.5, "specularColorFactor": [1, 0.9, 0.8]}}},
    {"name": "cutout", "alphaMode": "MASK", "alphaCutoff": 0.3},
    {"name": "see-through", "alphaMode": "BLEND"}])");
  primitive(d)["material"] = 1;
  Scene s = mustLoad(dir, d.gltf());
  ASSERT_EQ(s.images.size(), 1u);
  EXPECT_EQ(s.images[0].width, 2);
  EXPECT_EQ(s.images[0].height, 3);
  EXPECT_EQ(s.images[0].rgba.size(), 2u * 3u * 4u);
  EXPECT_EQ(s.images[0].rgba[0], 255);
  ASSERT_EQ(s.samplers.size(), 2u) << "one from the file, one default for the texture without a sampler";
  EXPECT_EQ(s.samplers[0].magFilter, scene::Filter::Nearest);
  EXPECT_EQ(s.samplers[0].wrapS, scene::Wrap::ClampToEdge);
  EXPECT_EQ(s.samplers[0].wrapT, scene::Wrap::MirroredRepeat);
  EXPECT_FALSE(s.samplers[0].mipmaps);
  EXPECT_TRUE(s.samplers[1].mipmaps);
  ASSERT_EQ(s.textures.size(), 2u);
  EXPECT_EQ(s.textures[1].sampler, 1u);

  ASSERT_EQ(s.materials.size(), 3u) << "no default material: every primitive has one";
  const scene::Material& m = s.materials[0];
  EXPECT_EQ(m.name, "glass");
  EXPECT_FLOAT_EQ(m.baseColor.w, 0.8f);
  EXPECT_FLOAT_EQ(m.metallic, 0.25f);
  EXPECT_FLOAT_EQ(m.roughness, 0.75f);
  EXPECT_EQ(m.baseColorTexture.texture, 0);
  EXPECT_EQ(m.baseColorTexture.texCoord, 1u) << "KHR_texture_transform texCoord overrides";
  EXPECT_FLOAT_EQ(m.baseColorTexture.offset.x, 0.5f);
  EXPECT_FLOAT_EQ(m.baseColorTexture.scale.y, 3.0f);
  EXPECT_FLOAT_EQ(m.baseColorTexture.rotation, 0.5f);
  EXPECT_EQ(m.normalTexture.texture, 1);
  EXPECT_FLOAT_EQ(m.normalScale, 0.5f);
  EXPECT_FLOAT_EQ(m.occlusionStrength, 0.3f);
  EXPECT_TRUE(m.emissiveTexture.valid());
  expectNear(m.emissive, {4, 2, 1});
  EXPECT_TRUE(m.doubleSided);
  EXPECT_FLOAT_EQ(m.transmission, 0.9f);
  EXPECT_FLOAT_EQ(m.ior, 1.33f);
  EXPECT_FLOAT_EQ(m.thickness, 0.1f);
  expectNear(m.attenuationColor, {0.9f, 0.8f, 0.7f});
  EXPECT_FLOAT_EQ(m.attenuationDistance, 2.0f);
  EXPECT_FLOAT_EQ(m.specular, 0.5f);
  expectNear(m.specularColor, {1, 0.9f, 0.8f});
  EXPECT_FALSE(s.materials[1].metallicRoughnessTexture.valid());

  EXPECT_EQ(s.materials[1].alphaMode, scene::AlphaMode::Mask);
  EXPECT_FLOAT_EQ(s.materials[1].alphaCutoff, 0.3f);
  EXPECT_EQ(s.materials[2].alphaMode, scene::AlphaMode::Blend);
  EXPECT_EQ(firstPrimitive(s).material, 1u);
}

TEST(GltfLoad, DefaultMaterialAppendedOnce) {
  TempDir dir;
  Doc d = quadDoc();
  d.j["materials"] = Json::array({{{"name", "red"}}});
  Json prim = primitive(d);
  d.j["meshes"][0]["primitives"] = {prim, prim, prim};
  d.j["meshes"][0]["primitives"][1]["material"] = 0;
  Scene s = mustLoad(dir, d.gltf());
  ASSERT_EQ(s.materials.size(), 2u);
  ASSERT_EQ(s.meshes[0].primitives.size(), 3u);
  EXPECT_EQ(s.meshes[0].primitives[0].material, 1u);
  EXPECT_EQ(s.meshes[0].primitives[1].material, 0u);
  EXPECT_EQ(s.meshes[0].primitives[2].material, 1u);
}

TEST(GltfLoad, UnknownOptionalExtensionOnlyWarns) {
  TempDir dir;
  Doc d = quadDoc();
  d.j["extensionsUsed"] = {"EXT_something_new", "KHR_materials_ior"};
  d.j["extensionsRequired"] = {"KHR_materials_ior"};
  EXPECT_TRUE(loadBytes(dir, d.gltf()).ok());
}

}  // namespace
