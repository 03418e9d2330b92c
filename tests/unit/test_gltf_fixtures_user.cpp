// The glTF files shaped like users' (tests/render/user_scenes.h) and the unit tests' quad
// (gltf_test_util.h) are valid glTF (tests/unit/gltf_fixture_check.h says what that means here).
#include "gltf_fixture_check.h"
#include "gltf_test_util.h"
#include "tests/render/user_scenes.h"

using namespace rayster;
using namespace rayster::test;

TEST(GltfFixtures, UserShapedTestFilesAreValid) {
  TempDir dir;
  expectValidTestFiles({writeSphereRowGltf(dir.path(), 0.001).string(),
                        writeSpecularSpheresGltf(dir.path(), 1.0).string(), writeSidednessGltf(dir.path()).string(),
                        dir.write("quad.gltf", quadDoc().gltf()).string(),
                        dir.write("quad.glb", quadDoc().glb()).string()});
}
