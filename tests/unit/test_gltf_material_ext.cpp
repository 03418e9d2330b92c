// KHR_materials_unlit and KHR_materials_specular as the glTF loader reads them (the renderer's side
// is tests/render/test_materials.cpp).
#include <gtest/gtest.h>

#include "core/image_io.h"
#include "gltf_test_util.h"

using namespace rayster;
using namespace rayster::test;

namespace {

scene::Scene loadMaterials(const TempDir& dir, Doc& d, const char* materials) {
  Image8 pixels = Image8::make(1, 1);
  EXPECT_TRUE(writePng(dir.path() / "tex.png", pixels).ok());
  d.j["images"] = Json::array({{{"uri", "tex.png"}}});
  d.j["textures"] = Json::array({{{"source", 0}}, {{"source", 0}}, {{"source", 0}}});
  d.j["materials"] = Json::parse(materials);
  primitive(d)["material"] = 0;
  Result<scene::Scene> s = loadBytes(dir, d.gltf());
  EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.error().message);
  return s.ok() ? std::move(s).value() : scene::Scene{};
}

TEST(GltfMaterialExt, UnlitIsRead) {
  TempDir dir;
  Doc d = quadDoc();
  d.j["extensionsUsed"] = {"KHR_materials_unlit"};
  scene::Scene s = loadMaterials(dir, d, R"([
    {"name": "flat", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 1], "baseColorTexture": {"index": 1}},
     "extensions": {"KHR_materials_unlit": {}}},
    {"name": "lit"}])");
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_TRUE(s.materials[0].unlit);
  EXPECT_FLOAT_EQ(s.materials[0].baseColor.y, 0.4f);
  EXPECT_EQ(s.materials[0].baseColorTexture.texture, 1) << "unlit keeps its base colour texture";
  EXPECT_FALSE(s.materials[1].unlit);
}

TEST(GltfMaterialExt, SpecularFactorsAndTextures) {
  TempDir dir;
  Doc d = quadDoc();
  d.j["extensionsUsed"] = {"KHR_materials_specular", "KHR_texture_transform"};
  scene::Scene s = loadMaterials(dir, d, R"([
    {"name": "tinted", "extensions": {"KHR_materials_specular": {
       "specularFactor": 0.25, "specularTexture": {"index": 2, "texCoord": 1},
       "specularColorFactor": [2, 0.5, 0],
       "specularColorTexture": {"index": 1, "extensions": {"KHR_texture_transform": {"scale": [4, 4]}}}}}},
    {"name": "plain"}])");
  ASSERT_EQ(s.materials.size(), 2u);
  const scene::Material& m = s.materials[0];
  EXPECT_FLOAT_EQ(m.specular, 0.25f);
  EXPECT_FLOAT_EQ(m.specularColor.x, 2.0f) << "specularColorFactor may exceed 1 (the product with F0 is clamped)";
  EXPECT_FLOAT_EQ(m.specularColor.y, 0.5f);
  EXPECT_FLOAT_EQ(m.specularColor.z, 0.0f);
  EXPECT_EQ(m.specularTexture.texture, 2);
  EXPECT_EQ(m.specularTexture.texCoord, 1u);
  EXPECT_EQ(m.specularColorTexture.texture, 1);
  EXPECT_FLOAT_EQ(m.specularColorTexture.scale.x, 4.0f);
  const scene::Material& plain = s.materials[1];
  EXPECT_FLOAT_EQ(plain.specular, 1.0f);
  EXPECT_EQ(plain.specularColor, glm::vec3(1.0f));
  EXPECT_FALSE(plain.specularTexture.valid());
  EXPECT_FALSE(plain.specularColorTexture.valid());
}

TEST(GltfMaterialExt, SpecularFactorIsClampedToItsRange) {
  TempDir dir;
  Doc d = quadDoc();
  scene::Scene s = loadMaterials(dir, d, R"([
    {"extensions": {"KHR_materials_specular": {"specularFactor": 3, "specularColorFactor": [-1, 0.5, 1]}}},
    {"extensions": {"KHR_materials_specular": {"specularFactor": -1}}}])");
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_FLOAT_EQ(s.materials[0].specular, 1.0f) << "the schema's range is [0, 1]";
  EXPECT_FLOAT_EQ(s.materials[0].specularColor.x, 0.0f) << "a negative colour reflects nothing";
  EXPECT_FLOAT_EQ(s.materials[1].specular, 0.0f);
}

}  // namespace
