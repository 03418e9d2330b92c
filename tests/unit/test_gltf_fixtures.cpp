// The glTF files the render tests write (tests/render/fixtures.h, analytic_scenes.h) are valid
// glTF (tests/unit/gltf_fixture_check.h says what that means here).
#include "gltf_fixture_check.h"
#include "tests/render/analytic_scenes.h"

using namespace rayster;
using namespace rayster::test;

TEST(GltfFixtures, RenderTestFilesAreValid) {
  const std::filesystem::path dir = uniqueTestDir("fixtures");
  std::vector<std::string> files = {writeAlphaMaskGltf(dir).string(), writeAnimatedGltf(dir).string()};
  analytic::MaterialSpec specular = analytic::blackAbsorber();
  specular.specular = 0.5f;
  analytic::MaterialSpec unlit = analytic::emitter(2.0f);
  unlit.unlit = true;
  const std::pair<const char*, analytic::MaterialSpec> materials[] = {{"glass", analytic::glass(1.5f, 0.1f)},
                                                                      {"emitter", analytic::emitter(4.0f)},
                                                                      {"specular", specular},
                                                                      {"unlit", unlit}};
  for (const auto& [name, material] : materials) {
    analytic::writeGltf(dir, name, analytic::unitSphere(6), material);
    files.push_back((dir / (std::string(name) + ".gltf")).string());
  }
  expectValidTestFiles(files);
}
