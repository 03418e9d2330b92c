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
  primitive(d)["attributes"]["TEXCOORD_1"] = primitive(d)["attributes"]["TEXCOORD_0"];  // specularTexture reads it
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

// Outside the schema's ranges (specularFactor in [0, 1], specularColorFactor >= 0) the validator
// reports an error, and the loader refuses the file naming the property.
TEST(GltfMaterialExt, SpecularFactorsOutsideTheirRangeAreRefused) {
  for (const auto& [specular, path] : std::vector<std::pair<const char*, const char*>>{
           {R"({"specularFactor": 3})",
            "materials[0].extensions.KHR_materials_specular.specularFactor: 3 is not [0, 1]"},
           {R"({"specularFactor": -1})", "KHR_materials_specular.specularFactor: -1 is not [0, 1]"},
           {R"({"specularColorFactor": [-1, 0.5, 1]})", "KHR_materials_specular.specularColorFactor[0]: -1"}}) {
    TempDir dir;
    Doc d = quadDoc();
    d.j["extensionsUsed"] = {"KHR_materials_specular"};
    d.j["materials"] = Json::array({{{"extensions", {{"KHR_materials_specular", Json::parse(specular)}}}}});
    primitive(d)["material"] = 0;
    Result<scene::Scene> s = loadBytes(dir, d.gltf());
    ASSERT_FALSE(s.ok()) << specular;
    EXPECT_NE(s.error().message.find(path), std::string::npos) << s.error().message;
  }
}

}  // namespace
