// loadScene's dispatch, the defaults it adds to bare model files, and the shared path policy.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/builtin.h"
#include "scene/loader.h"
#include "tests/support/test_dirs.h"

using namespace rayster;
using namespace rayster::scene;
namespace fs = std::filesystem;

namespace {

constexpr const char* kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

class LoaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = rayster::test::testDir();  // removed when the test passes (tests/support/test_dirs.h)
  }

  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return (dir_ / name).string();
  }

  fs::path dir_;
};

// Where a world point lands in normalised device coordinates of the camera (aspect 16:9).
glm::vec3 project(const Camera& camera, glm::vec3 point) {
  const glm::mat4 clipFromWorld = glm::perspective(camera.yFov, 16.0f / 9.0f, camera.zNear, camera.zFar) *
                                  glm::lookAt(camera.position, camera.target, camera.up);
  const glm::vec4 clip = clipFromWorld * glm::vec4(point, 1.0f);
  return glm::vec3(clip) / clip.w;
}

}  // namespace

TEST_F(LoaderTest, DispatchesByExtensionCaseInsensitively) {
  Result<Scene> obj = loadScene(write("Model.OBJ", kTriangleObj));
  ASSERT_TRUE(obj.ok()) << obj.error().message;
  EXPECT_EQ(obj->name, "Model");
  EXPECT_EQ(obj->triangleCount(), 1u);

  write("tri.obj", kTriangleObj);
  Result<Scene> json = loadScene(write("composed.json", R"({"models": [{"path": "tri.obj"}, {"path": "tri.obj"}]})"));
  ASSERT_TRUE(json.ok()) << json.error().message;
  EXPECT_EQ(json->name, "composed");
  EXPECT_EQ(json->triangleCount(), 2u);

  // glTF goes to loadGltf: garbage is refused as bad input whether or not glTF is built in.
  Result<Scene> gltf = loadScene(write("broken.gltf", "not a gltf"));
  ASSERT_FALSE(gltf.ok());
  EXPECT_EQ(gltf.error().code, ExitCode::BadInput);
}

TEST_F(LoaderTest, BuiltinSceneIsLoadedAsDefined) {
  Result<Scene> loaded = loadScene("builtin:cornell");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const Scene cornell = makeCornellBox();
  // No defaults added: built-in scenes define their own lights and cameras.
  EXPECT_EQ(loaded->lights.size(), cornell.lights.size());
  EXPECT_EQ(loaded->cameras.size(), cornell.cameras.size());
  EXPECT_EQ(loaded->triangleCount(), cornell.triangleCount());
  EXPECT_FALSE(loadScene("builtin:nonesuch").ok());
}

TEST_F(LoaderTest, RefusesUnknownExtensionsAndMissingFiles) {
  Result<Scene> fbx = loadScene(write("model.fbx", "binary"));
  ASSERT_FALSE(fbx.ok());
  EXPECT_EQ(fbx.error().code, ExitCode::BadInput);
  EXPECT_NE(fbx.error().message.find(".gltf, .glb, .obj, .json"), std::string::npos) << fbx.error().message;

  const std::string missing = (dir_ / "x.obj").string();
  Result<Scene> none = loadScene(missing);
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.error().code, ExitCode::BadInput);
  EXPECT_EQ(none.error().message, "cannot read scene '" + missing + "': no such file");

  Result<Scene> bare = loadScene("cornell");
  ASSERT_FALSE(bare.ok());
  EXPECT_NE(bare.error().message.find("builtin:cornell"), std::string::npos) << bare.error().message;
}

TEST_F(LoaderTest, AddsSunSkyAndFramingCameraToBareModels) {
  // A box far from the origin, so framing has to find it.
  Result<Scene> loaded = loadScene(write("far.obj", "v 100 0 0\nv 104 0 0\nv 104 2 0\nv 100 2 -3\nf 1 2 3\nf 1 3 4\n"));
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const Scene& scene = *loaded;
  ASSERT_EQ(scene.lights.size(), 1u);
  const Light& sun = scene.lights[0];
  EXPECT_EQ(sun.name, "default sun");
  EXPECT_EQ(sun.type, LightType::Directional);
  EXPECT_NEAR(glm::distance(sun.direction, glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f))), 0.0f, 1e-6f);
  EXPECT_FLOAT_EQ(sun.intensity, 3.0f);
  EXPECT_FLOAT_EQ(sun.angularRadius, 0.0047f);
  EXPECT_EQ(scene.environment.kind, Environment::Kind::Sky);

  ASSERT_EQ(scene.cameras.size(), 1u);
  const Camera& camera = scene.cameras[0];
  EXPECT_EQ(camera.name, "default");
  EXPECT_NEAR(camera.yFov, glm::radians(45.0f), 1e-6f);
  const Aabb box = scene.bounds();
  EXPECT_GT(camera.position.z, box.max.z);       // in front, on the +Z side
  EXPECT_GT(camera.position.y, box.centre().y);  // slightly above
  // The centre is in view, and so is every corner of the bounds.
  const glm::vec3 centre = project(camera, box.centre());
  EXPECT_NEAR(centre.x, 0.0f, 1e-4f);
  EXPECT_NEAR(centre.y, 0.0f, 1e-4f);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p(corner & 1 ? box.max.x : box.min.x, corner & 2 ? box.max.y : box.min.y,
                      corner & 4 ? box.max.z : box.min.z);
    const glm::vec3 ndc = project(camera, p);
    EXPECT_LE(std::abs(ndc.x), 1.0f);
    EXPECT_LE(std::abs(ndc.y), 1.0f);
    EXPECT_GE(ndc.z, 0.0f);
    EXPECT_LE(ndc.z, 1.0f);
  }
}

TEST_F(LoaderTest, DefaultsKeepWhatTheSceneDefines) {
  write("tri.obj", kTriangleObj);
  Result<Scene> loaded = loadScene(write("lit.json", R"({"models": [{"path": "tri.obj"}],
      "lights": [{"type": "point", "position": [0, 2, 0]}],
      "cameras": [{"position": [0, 0, 3], "target": [0, 0, 0]}]})"));
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_EQ(loaded->lights.size(), 1u);
  EXPECT_EQ(loaded->lights[0].type, LightType::Point);
  EXPECT_EQ(loaded->environment.kind, Environment::Kind::Black);  // a lit scene keeps its black sky
  EXPECT_EQ(loaded->cameras.size(), 1u);
}

TEST(LoaderPaths, ResolveRelativePathPolicy) {
  Result<fs::path> ok = resolveRelativePath("/data/scenes", "textures\\wood.png", "t");
  ASSERT_TRUE(ok.ok()) << ok.error().message;
  EXPECT_EQ(*ok, fs::path("/data/scenes/textures/wood.png"));
  EXPECT_TRUE(resolveRelativePath("/d", "./a/./b.png", "t").ok());
  for (const char* bad :
       {"", "/etc/passwd", "..", "a/../../b", "..\\b", "file:///etc/passwd", "C:\\x.png", "http://example.com/a.png"}) {
    Result<fs::path> refused = resolveRelativePath("/d", bad, "t");
    EXPECT_FALSE(refused.ok()) << bad;
    if (!refused.ok()) {
      EXPECT_EQ(refused.error().code, ExitCode::BadInput);
    }
  }
}
