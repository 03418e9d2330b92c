// glTF material defaults (glTF 2.0 §5.19 material, §5.21 pbrMetallicRoughness, KHR_materials_ior):
// a property left out renders exactly as the same property written with its default value, in the
// hybrid frame, the raster mode and the path tracer (issue 14 item 3). One test per default.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "tests/render/run_rayster.h"
#include "tests/unit/gltf_test_util.h"

namespace rayster::test {
namespace {

class MaterialDefaults : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testDir(); }

  // A quad with `material` (none when null), lit by the default light, rendered in each mode.
  std::filesystem::path write(const std::string& name, const Json& material, bool iorExtension = false) {
    Doc d = quadDoc();
    if (!material.is_null()) {
      d.j["materials"] = Json::array({material});
      primitive(d)["material"] = 0;
    }
    if (iorExtension) d.j["extensionsUsed"] = {"KHR_materials_ior"};
    const auto path = dir_ / (name + ".gltf");
    std::ofstream(path) << d.gltf();
    return path;
  }

  Image8 render(const std::filesystem::path& scene, const std::string& mode) {
    const std::string name = scene.stem().string() + "-" + mode;
    const std::string frames = mode == "pathtrace" ? "--frames 8" : "--frames 2";
    return renderOk(dir_, name, scene.string() + " --mode " + mode + " --primary raster --seed 5 " + frames, 40, 30);
  }

  // Left out and written with its default: the same image, in every mode.
  void expectSame(const Json& omitted, const Json& explicitDefault, bool ior = false) {
    const auto a = write("omitted", omitted), b = write("explicit", explicitDefault, ior);
    for (const char* mode : {"hybrid", "raster", "pathtrace"}) {
      const Image8 ia = render(a, mode), ib = render(b, mode);
      EXPECT_EQ(ia.rgba, ib.rgba) << mode << ": " << omitted.dump() << " vs " << explicitDefault.dump();
    }
  }

  std::filesystem::path dir_;
};

TEST_F(MaterialDefaults, MetallicFactorIsOne) {
  const Json pbr = {{"baseColorFactor", {0.8, 0.5, 0.3, 1.0}}, {"roughnessFactor", 0.5}};
  Json explicitPbr = pbr;
  explicitPbr["metallicFactor"] = 1.0;
  expectSame({{"pbrMetallicRoughness", pbr}}, {{"pbrMetallicRoughness", explicitPbr}});
}

TEST_F(MaterialDefaults, RoughnessFactorIsOne) {
  const Json pbr = {{"baseColorFactor", {0.8, 0.5, 0.3, 1.0}}, {"metallicFactor", 0.0}};
  Json explicitPbr = pbr;
  explicitPbr["roughnessFactor"] = 1.0;
  expectSame({{"pbrMetallicRoughness", pbr}}, {{"pbrMetallicRoughness", explicitPbr}});
}

TEST_F(MaterialDefaults, BaseColorFactorIsWhite) {
  const Json pbr = {{"metallicFactor", 0.0}, {"roughnessFactor", 0.6}};
  Json explicitPbr = pbr;
  explicitPbr["baseColorFactor"] = {1.0, 1.0, 1.0, 1.0};
  expectSame({{"pbrMetallicRoughness", pbr}}, {{"pbrMetallicRoughness", explicitPbr}});
}

TEST_F(MaterialDefaults, EmissiveFactorIsBlack) {
  const Json pbr = {{"metallicFactor", 0.0}, {"roughnessFactor", 0.6}};
  expectSame({{"pbrMetallicRoughness", pbr}}, {{"pbrMetallicRoughness", pbr}, {"emissiveFactor", {0.0, 0.0, 0.0}}});
}

TEST_F(MaterialDefaults, IorIsOnePointFive) {
  const Json pbr = {{"metallicFactor", 0.0}, {"roughnessFactor", 0.3}};
  expectSame({{"pbrMetallicRoughness", pbr}},
             {{"pbrMetallicRoughness", pbr}, {"extensions", {{"KHR_materials_ior", {{"ior", 1.5}}}}}}, true);
}

// A primitive without a material uses the default material (§5.19): the same as an empty one.
TEST_F(MaterialDefaults, NoMaterialIsTheDefaultMaterial) { expectSame(Json(), Json::object()); }

TEST_F(MaterialDefaults, AlphaModeIsOpaqueAndCutoffIsOneHalf) {
  const Json pbr = {{"baseColorFactor", {0.8, 0.8, 0.8, 0.3}}, {"metallicFactor", 0.0}};
  expectSame({{"pbrMetallicRoughness", pbr}}, {{"pbrMetallicRoughness", pbr}, {"alphaMode", "OPAQUE"}});
  Json mask = {{"pbrMetallicRoughness", pbr}, {"alphaMode", "MASK"}};
  Json maskExplicit = mask;
  maskExplicit["alphaCutoff"] = 0.5;
  expectSame(mask, maskExplicit);
}

}  // namespace
}  // namespace rayster::test
