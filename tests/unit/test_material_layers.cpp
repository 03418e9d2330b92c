// The material layers (KHR_materials_clearcoat, _sheen, _iridescence, _anisotropy, _dispersion),
// the transmission and thickness textures and KHR_materials_variants as the glTF loader reads them,
// and the sheen albedo table the path tracer uses (shared/sheen.h). Rendering: test_layers.cpp.
#include <cmath>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "gltf_test_util.h"
#include "scene/merge.h"
#include "shaders/shared/sheen.h"

using namespace rayster;
using namespace rayster::test;

namespace {

Result<scene::Scene> loadWith(const TempDir& dir, Doc& d, const char* materials) {
  Image8 pixels = Image8::make(1, 1);
  EXPECT_TRUE(writePng(dir.path() / "tex.png", pixels).ok());
  d.j["images"] = Json::array({{{"uri", "tex.png"}}});
  d.j["textures"] = Json::array({{{"source", 0}}, {{"source", 0}}, {{"source", 0}}});
  d.j["materials"] = Json::parse(materials);
  primitive(d)["material"] = 0;
  return loadBytes(dir, d.gltf());
}

TEST(MaterialLayers, EveryLayerAndItsTexturesAreRead) {
  TempDir dir;
  Doc d = quadDoc();
  d.j["extensionsUsed"] = {"KHR_materials_clearcoat",  "KHR_materials_sheen",      "KHR_materials_iridescence",
                           "KHR_materials_anisotropy", "KHR_materials_dispersion", "KHR_materials_transmission",
                           "KHR_materials_volume"};
  // The base normal map gives the clear coat's normal texture a tangent space (the validator's
  // MESH_PRIMITIVE_NO_TANGENT_SPACE otherwise).
  Result<scene::Scene> s = loadWith(dir, d, R"([{"name": "layered", "normalTexture": {"index": 2}, "extensions": {
    "KHR_materials_clearcoat": {"clearcoatFactor": 0.8, "clearcoatTexture": {"index": 0},
      "clearcoatRoughnessFactor": 0.3, "clearcoatRoughnessTexture": {"index": 1},
      "clearcoatNormalTexture": {"index": 2, "scale": 0.5}},
    "KHR_materials_sheen": {"sheenColorFactor": [0.9, 0.2, 0.1], "sheenColorTexture": {"index": 1},
      "sheenRoughnessFactor": 0.6, "sheenRoughnessTexture": {"index": 2}},
    "KHR_materials_iridescence": {"iridescenceFactor": 1.0, "iridescenceIor": 1.8,
      "iridescenceThicknessMinimum": 200, "iridescenceThicknessMaximum": 800,
      "iridescenceTexture": {"index": 0}, "iridescenceThicknessTexture": {"index": 1}},
    "KHR_materials_anisotropy": {"anisotropyStrength": 0.7, "anisotropyRotation": 1.25,
      "anisotropyTexture": {"index": 2}},
    "KHR_materials_dispersion": {"dispersion": 0.4},
    "KHR_materials_transmission": {"transmissionFactor": 1.0, "transmissionTexture": {"index": 0}},
    "KHR_materials_volume": {"thicknessFactor": 0.1, "thicknessTexture": {"index": 2}}}},
    {"name": "plain"}])");
  ASSERT_TRUE(s.ok()) << s.error().message;
  const scene::Material& m = s->materials[0];
  EXPECT_FLOAT_EQ(m.clearcoat, 0.8f);
  EXPECT_FLOAT_EQ(m.clearcoatRoughness, 0.3f);
  EXPECT_FLOAT_EQ(m.clearcoatNormalScale, 0.5f);
  EXPECT_TRUE(m.clearcoatTexture.valid());
  EXPECT_TRUE(m.clearcoatRoughnessTexture.valid());
  EXPECT_TRUE(m.clearcoatNormalTexture.valid());
  EXPECT_EQ(m.sheenColor, glm::vec3(0.9f, 0.2f, 0.1f));
  EXPECT_FLOAT_EQ(m.sheenRoughness, 0.6f);
  EXPECT_TRUE(m.sheenColorTexture.valid());
  EXPECT_TRUE(m.sheenRoughnessTexture.valid());
  EXPECT_FLOAT_EQ(m.iridescence, 1.0f);
  EXPECT_FLOAT_EQ(m.iridescenceIor, 1.8f);
  EXPECT_FLOAT_EQ(m.iridescenceThicknessMin, 200.0f);
  EXPECT_FLOAT_EQ(m.iridescenceThicknessMax, 800.0f);
  EXPECT_TRUE(m.iridescenceTexture.valid());
  EXPECT_TRUE(m.iridescenceThicknessTexture.valid());
  EXPECT_FLOAT_EQ(m.anisotropyStrength, 0.7f);
  EXPECT_FLOAT_EQ(m.anisotropyRotation, 1.25f);
  EXPECT_TRUE(m.anisotropyTexture.valid());
  EXPECT_FLOAT_EQ(m.dispersion, 0.4f);
  EXPECT_TRUE(m.transmissionTexture.valid());
  EXPECT_TRUE(m.thicknessTexture.valid());
  EXPECT_TRUE(m.layered());

  const scene::Material& plain = s->materials[1];
  EXPECT_FALSE(plain.layered()) << "every layer is off at its default";
  EXPECT_FLOAT_EQ(plain.iridescenceIor, 1.3f);
  EXPECT_FLOAT_EQ(plain.iridescenceThicknessMin, 100.0f);
  EXPECT_FLOAT_EQ(plain.iridescenceThicknessMax, 400.0f);
}

TEST(MaterialLayers, AnUnlitMaterialHasNoLayers) {
  scene::Material m;
  m.clearcoat = 1.0f;
  EXPECT_TRUE(m.layered());
  m.unlit = true;
  EXPECT_FALSE(m.layered()) << "unlit ignores every other property";
}

// Two variants over two materials on the quad: selecting one swaps the material, "" restores it.
Doc variantDoc() {
  Doc d = quadDoc();
  d.j["extensionsUsed"] = {"KHR_materials_variants"};
  d.j["extensions"]["KHR_materials_variants"]["variants"] = Json::array({{{"name", "red"}}, {{"name", "blue"}}});
  d.j["materials"] = Json::parse(R"([{"name": "grey"}, {"name": "red"}, {"name": "blue"}])");
  primitive(d)["material"] = 0;
  primitive(d)["extensions"]["KHR_materials_variants"]["mappings"] =
      Json::parse(R"([{"material": 1, "variants": [0]}, {"material": 2, "variants": [1]}])");
  return d;
}

TEST(MaterialVariants, SelectingAVariantSwapsTheMaterialsAndEmptyRestoresThem) {
  TempDir dir;
  Doc d = variantDoc();
  Result<scene::Scene> s = loadBytes(dir, d.gltf());
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_EQ(s->variants, (std::vector<std::string>{"red", "blue"}));
  scene::Primitive& prim = s->meshes[0].primitives[0];
  EXPECT_EQ(prim.material, 0u) << "without --variant the primitive's own material";
  ASSERT_TRUE(scene::selectVariant(*s, "blue").ok());
  EXPECT_EQ(prim.material, 2u);
  ASSERT_TRUE(scene::selectVariant(*s, "red").ok());
  EXPECT_EQ(prim.material, 1u);
  ASSERT_TRUE(scene::selectVariant(*s, "").ok());
  EXPECT_EQ(prim.material, 0u);

  Status unknown = scene::selectVariant(*s, "green");
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().code, ExitCode::BadInput);
  EXPECT_NE(unknown.error().message.find("'red', 'blue'"), std::string::npos) << unknown.error().message;
}

TEST(MaterialVariants, APrimitiveWithoutAMappingForTheVariantKeepsItsMaterial) {
  TempDir dir;
  Doc d = variantDoc();
  primitive(d)["extensions"]["KHR_materials_variants"]["mappings"] =
      Json::parse(R"([{"material": 2, "variants": [1]}])");
  Result<scene::Scene> s = loadBytes(dir, d.gltf());
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_TRUE(scene::selectVariant(*s, "red").ok());
  EXPECT_EQ(s->meshes[0].primitives[0].material, 0u);
}

TEST(MaterialVariants, BadMappingsAreRefusedNamingTheirPath) {
  struct Case {
    const char* mappings;
    const char* path;
  };
  const Case cases[] = {
      {R"([{"material": 7, "variants": [0]}])", "mappings[0].material"},
      {R"([{"material": 1, "variants": [2]}])", "mappings[0].variants[0]"},
      {R"([{"material": 1, "variants": []}])", "mappings[0].variants"},
      {R"([{"material": 1, "variants": [0]}, {"material": 2, "variants": [0]}])", "mapped twice"},
  };
  for (const Case& c : cases) {
    TempDir dir;
    Doc d = variantDoc();
    primitive(d)["extensions"]["KHR_materials_variants"]["mappings"] = Json::parse(c.mappings);
    Result<scene::Scene> s = loadBytes(dir, d.gltf());
    ASSERT_FALSE(s.ok()) << c.mappings;
    EXPECT_EQ(s.error().code, ExitCode::BadInput);
    EXPECT_NE(s.error().message.find(c.path), std::string::npos) << s.error().message;
    EXPECT_NE(s.error().message.find("meshes[0].primitives[0]"), std::string::npos) << s.error().message;
  }
}

TEST(MaterialVariants, ScenesMergeVariantsByName) {
  TempDir dir;
  Doc d = variantDoc();
  Result<scene::Scene> a = loadBytes(dir, d.gltf());
  ASSERT_TRUE(a.ok()) << a.error().message;
  scene::Scene b = *a;
  std::swap(b.variants[0], b.variants[1]);  // the same names in the other order
  scene::Scene merged;
  scene::appendScene(merged, *a, glm::mat4(1.0f));
  scene::appendScene(merged, b, glm::mat4(1.0f));
  ASSERT_EQ(merged.variants, (std::vector<std::string>{"red", "blue"}));
  ASSERT_TRUE(scene::selectVariant(merged, "red").ok());
  EXPECT_EQ(merged.meshes[0].primitives[0].material, 1u);
  EXPECT_EQ(merged.meshes[1].primitives[0].material, 3u + 2u) << "b's 'red' was its second variant: material 2";
}

// The table in shared/sheen.h is the integral of the lobe it scales (recomputed here from the same
// functions, so a change to either shows).
TEST(SheenAlbedo, TableIsTheIntegralOfTheLobe) {
  using namespace rayster::gpu;
  auto albedo = [](double nv, double roughness) {
    const int n = 256;
    const double a = sheenAlpha(float(roughness)), sv = std::sqrt(std::max(0.0, 1 - nv * nv));
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      const double nl = (i + 0.5) / n, sl = std::sqrt(1 - nl * nl);
      for (int j = 0; j < 2 * n; ++j) {
        const double phi = (j + 0.5) / (2 * n) * 2 * M_PI;
        const double hx = sl * std::cos(phi) + sv, hy = sl * std::sin(phi), hz = nl + nv;
        const double nh = hz / std::sqrt(hx * hx + hy * hy + hz * hz);
        sum += charlieDistribution(float(nh), float(a)) * ashikhminVisibility(float(nl), float(nv)) * nl;
      }
    }
    return sum * (1.0 / n) * (M_PI / n);
  };
  const uint n = kSheenTableSize;
  for (uint r = 0; r < n; r += 3)
    for (uint v = 1; v < n; v += 3) {  // v = 0 (n·v = 1e-3) is too steep for the coarser grid here
      const double nv = v / double(n - 1), roughness = r / double(n - 1);
      const double expected = albedo(nv, roughness);
      EXPECT_NEAR(kSheenAlbedo[r * n + v], expected, 0.01 * expected + 2e-4)
          << "n·v " << nv << ", roughness " << roughness;
      EXPECT_NEAR(sheenAlbedo(float(nv), float(roughness)), kSheenAlbedo[r * n + v], 1e-5) << "lookup at a texel";
    }
  // A white sheen never reflects more than arrives away from grazing views.
  for (uint r = 0; r < n; ++r)
    for (uint v = n / 4; v < n; ++v) EXPECT_LE(kSheenAlbedo[r * n + v], 1.0f) << r << ", " << v;
}

}  // namespace
