// JSON scene files and appendScene: composition, conversions, and what they must refuse.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "core/image_io.h"
#include "scene/builtin.h"
#include "scene/loader.h"
#include "scene/merge.h"
#include "scene/scene_file.h"
#include "tests/support/test_dirs.h"

using namespace rayster;
using namespace rayster::scene;
namespace fs = std::filesystem;

namespace {

// Loaders leave the camera to applyDefaults, and validate() wants one.
bool validWithDefaults(Scene scene) {
  applyDefaults(scene);
  Status status = validate(scene);
  if (!status.ok()) ADD_FAILURE() << status.error().message;
  return status.ok();
}

constexpr const char* kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

class SceneFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = rayster::test::testDir();  // removed when the test passes (tests/support/test_dirs.h)
    write("tri.obj", kTriangleObj);
  }

  fs::path write(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  void expectRejected(const std::string& json, const std::string& needle) {
    Result<Scene> scene = loadSceneFile(write("scene.json", json));
    ASSERT_FALSE(scene.ok()) << "accepted:\n" << json;
    EXPECT_EQ(scene.error().code, ExitCode::BadInput);
    EXPECT_NE(scene.error().message.find(needle), std::string::npos) << scene.error().message;
  }

  fs::path dir_;
};

}  // namespace

TEST_F(SceneFileTest, ComposesOneObjTwiceWithTransforms) {
  Result<Scene> loaded = loadSceneFile(write("scene.json", R"({
    "name": "pair",
    "models": [
      {"path": "tri.obj", "translate": [10, 0, 0], "name": "left"},
      {"path": "tri.obj", "translate": [0, 0, -5], "rotate": [0, 90, 0], "scale": 2}
    ]})"));
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const Scene& scene = *loaded;
  EXPECT_EQ(scene.name, "pair");
  ASSERT_EQ(scene.instances.size(), 2u);
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_EQ(scene.instances[0].name, "left");
  EXPECT_EQ(scene.instances[1].mesh, 1u);
  // Each model brought its own default material, re-based in the merged scene.
  ASSERT_EQ(scene.materials.size(), 2u);
  EXPECT_EQ(scene.meshes[1].primitives[0].material, 1u);
  // Vertex (1,0,0) of the second model: scaled by 2, turned 90 degrees about +Y, moved to z = -5.
  const glm::vec4 moved = scene.instances[1].worldFromObject * glm::vec4(1, 0, 0, 1);
  EXPECT_NEAR(moved.x, 0.0f, 1e-5f);
  EXPECT_NEAR(moved.z, -7.0f, 1e-5f);
  EXPECT_EQ(glm::vec3(scene.instances[0].worldFromObject[3]), glm::vec3(10, 0, 0));
  EXPECT_TRUE(validWithDefaults(scene));
}

TEST_F(SceneFileTest, LightsAndCamerasConvertDegrees) {
  Result<Scene> loaded = loadSceneFile(write("scene.json", R"({
    "models": [{"path": "tri.obj"}],
    "lights": [
      {"type": "spot", "position": [0, 4, 0], "direction": [0, -2, 0], "color": [1, 0.5, 0.25],
       "intensity": 20, "radius": 0.1, "innerConeAngle": 15, "outerConeAngle": 30},
      {"type": "directional", "name": "sun", "direction": [0, -1, 0], "angularRadius": 0.5}
    ],
    "cameras": [{"name": "front", "position": [0, 1, 5], "target": [0, 1, 0], "yfov": 60,
                 "znear": 0.1, "zfar": 50}]
  })"));
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const Scene& scene = *loaded;
  ASSERT_EQ(scene.lights.size(), 2u);
  const Light& spot = scene.lights[0];
  EXPECT_EQ(spot.type, LightType::Spot);
  EXPECT_EQ(spot.direction, glm::vec3(0, -1, 0));
  EXPECT_EQ(spot.color, glm::vec3(1, 0.5f, 0.25f));
  EXPECT_FLOAT_EQ(spot.intensity, 20.0f);
  EXPECT_FLOAT_EQ(spot.radius, 0.1f);
  EXPECT_NEAR(spot.innerConeAngle, glm::pi<float>() / 12, 1e-6f);
  EXPECT_NEAR(spot.outerConeAngle, glm::pi<float>() / 6, 1e-6f);
  EXPECT_EQ(scene.lights[1].type, LightType::Directional);
  EXPECT_EQ(scene.lights[1].name, "sun");
  EXPECT_NEAR(scene.lights[1].angularRadius, glm::radians(0.5f), 1e-7f);
  ASSERT_EQ(scene.cameras.size(), 1u);
  EXPECT_EQ(scene.cameras[0].name, "front");
  EXPECT_NEAR(scene.cameras[0].yFov, glm::pi<float>() / 3, 1e-6f);
  EXPECT_FLOAT_EQ(scene.cameras[0].zNear, 0.1f);
  EXPECT_FLOAT_EQ(scene.cameras[0].zFar, 50.0f);
}

TEST_F(SceneFileTest, EnvironmentMapAmbientAndCameraPath) {
  ImageF sky = ImageF::make(8, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) {
      float* p = sky.pixel(x, y);
      p[0] = static_cast<float>(x);
      p[1] = static_cast<float>(y);
      p[2] = 0.5f;
      p[3] = 1.0f;
    }
  ASSERT_TRUE(writeExr(dir_ / "env" / "sky.exr", sky).ok());
  Result<Scene> loaded = loadSceneFile(write("scene.json", R"({
    "models": [{"path": "tri.obj"}],
    "environment": {"map": "env/sky.exr", "intensity": 2, "rotation": 90},
    "ambient": [0.1, 0.2, 0.3],
    "cameraPath": [{"time": 0, "position": [0, 0, 5], "target": [0, 0, 0]},
                   {"time": 2.5, "position": [5, 0, 0], "target": [0, 1, 0]}]
  })"));
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const Environment& env = loaded->environment;
  EXPECT_EQ(env.kind, Environment::Kind::Map);
  EXPECT_EQ(env.width, 8);
  EXPECT_EQ(env.height, 4);
  ASSERT_EQ(env.rgb.size(), 8u * 4u * 3u);
  const size_t pixel = (2 * 8 + 5) * 3;  // x = 5, y = 2: halfs hold small integers exactly
  EXPECT_FLOAT_EQ(env.rgb[pixel + 0], 5.0f);
  EXPECT_FLOAT_EQ(env.rgb[pixel + 1], 2.0f);
  EXPECT_FLOAT_EQ(env.rgb[pixel + 2], 0.5f);
  EXPECT_FLOAT_EQ(env.intensity, 2.0f);
  EXPECT_NEAR(env.rotation, glm::half_pi<float>(), 1e-6f);
  EXPECT_NE(env.mapPath.find("sky.exr"), std::string::npos);
  EXPECT_EQ(loaded->ambient, glm::vec3(0.1f, 0.2f, 0.3f));
  ASSERT_EQ(loaded->cameraPath.size(), 2u);
  EXPECT_FLOAT_EQ(loaded->cameraPath[1].time, 2.5f);
  EXPECT_EQ(loaded->cameraPath[1].target, glm::vec3(0, 1, 0));
}

TEST_F(SceneFileTest, SkyEnvironmentAndBuiltinModels) {
  Result<Scene> loaded = loadSceneFile(write("scene.json", R"({
    "models": [{"path": "builtin:cornell"}, {"path": "tri.obj", "rotateAxisAngle": [0, 1, 0, 45]}],
    "environment": {"sky": {"zenith": [0, 0, 1]}, "intensity": 0.5}
  })"));
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const Scene cornell = makeCornellBox();
  EXPECT_EQ(loaded->environment.kind, Environment::Kind::Sky);
  EXPECT_EQ(loaded->environment.zenith, glm::vec3(0, 0, 1));
  EXPECT_EQ(loaded->instances.size(), cornell.instances.size() + 1);
  EXPECT_EQ(loaded->lights.size(), cornell.lights.size());
  EXPECT_EQ(loaded->meshes.back().primitives[0].material, cornell.materials.size());
  EXPECT_TRUE(validate(*loaded).ok()) << validate(*loaded).error().message;
}

TEST_F(SceneFileTest, UnknownKeysAreWarnings) {
  ::testing::internal::CaptureStderr();
  Result<Scene> loaded = loadSceneFile(write("scene.json", R"({"models": [{"path": "tri.obj", "colour": 1}],
                                                               "extra": true})"));
  const std::string log = ::testing::internal::GetCapturedStderr();
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_NE(log.find("models[0].colour"), std::string::npos) << log;
  EXPECT_NE(log.find("extra"), std::string::npos) << log;
}

TEST_F(SceneFileTest, RejectsTextThatIsNotUtf8WithItsPosition) {
  // The message names the byte and its place, and echoes no invalid bytes of its own.
  auto rejected = [&](const std::string& json, const std::string& needle) {
    expectRejected(json, needle);
    Result<Scene> scene = loadSceneFile(write("scene.json", json));
    ASSERT_FALSE(scene.ok());
    for (char c : scene.error().message) EXPECT_LT(uint8_t(c), 0x80) << scene.error().message;
  };
  rejected("{\"models\": [{\"path\": \"\xff\xfe.obj\"}]}",
           "scene.json: not UTF-8 text: byte 0xFF at byte offset 22 (line 1, column 23)");
  rejected("{\n  \"name\": \"caf\xc3\"\n}", "byte 0xC3 at byte offset 16 (line 2, column 15)");  // a truncated sequence
  rejected("{\"name\": \"\xc0\xaf\"}", "byte 0xC0 at byte offset 10 (line 1, column 11)");       // an overlong '/'
  rejected("{\"name\": \"\xed\xa0\x80\"}", "byte 0xED at byte offset 10 (line 1, column 11)");   // a surrogate
  // Well-formed UTF-8 is text like any other: a name in any script loads.
  write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  Result<Scene> ok = loadSceneFile(
      write("scene.json", "{\"name\": \"caf\xc3\xa9 \xe6\x97\xa5\", \"models\": [{\"path\": \"tri.obj\"}]}"));
  EXPECT_TRUE(ok.ok()) << (ok.ok() ? "" : ok.error().message);
}

TEST_F(SceneFileTest, RejectsTruncatedJsonWithItsPosition) {
  expectRejected("{\"models\": [{\"path\": \"tri.obj\"}", "scene.json: invalid JSON");
  expectRejected("{\"models\": [{\"path\": \"tri.obj\"}", "line 1");
  expectRejected("garbage", "invalid JSON");
}

TEST_F(SceneFileTest, RejectsNumbersTooLargeForADouble) {
  // nlohmann reports these as out_of_range, not parse_error; found by fuzz_scene_file.
  expectRejected(R"({"models": [{"path": "tri.obj"}], "ambient": [1e400, 0, 0]})", "number overflow parsing '1e400'");
  expectRejected("3330000000000000000000001623e340224473490069{}", "scene.json: invalid JSON");
}

TEST_F(SceneFileTest, RejectsWrongTypesNamingTheJsonPath) {
  expectRejected(R"({"models": [{"path": "tri.obj"}, {"path": "tri.obj"}, {"path": "tri.obj", "scale": "big"}]})",
                 "scene.json: models[2].scale must be a number or an array of 3 numbers");
  expectRejected(R"({"models": [{"path": "tri.obj"}], "lights": [{"type": "point", "color": [1, 1]}]})",
                 "lights[0].color must be an array of 3 numbers");
  expectRejected(R"({"models": [{"path": "tri.obj"}], "cameras": [{"yfov": 200}]})", "cameras[0].yfov");
  expectRejected(R"({"models": [{"path": "tri.obj"}], "lights": [{"type": "area"}]})", "lights[0].type");
  expectRejected(R"({"models": {}})", "models must be a non-empty array");
  expectRejected(R"([1, 2])", "top level must be an object");
}

TEST_F(SceneFileTest, RejectsPathsLeavingTheFolder) {
  expectRejected(R"({"models": [{"path": "../x.obj"}]})", "'..' is not allowed");
  expectRejected(R"({"models": [{"path": "/tmp/x.obj"}]})", "absolute path");
  expectRejected(R"({"models": [{"path": "https://example.com/x.obj"}]})", "URI");
  expectRejected(R"({"models": [{"path": "tri.obj"}], "environment": {"map": "../sky.hdr"}})", "environment.map");
}

TEST_F(SceneFileTest, RejectsMissingModelFile) {
  expectRejected(R"({"models": [{"path": "tri.obj"}, {"path": "gone.obj"}]})",
                 "scene.json: models[1]: cannot read scene");
}

TEST(SceneFileMerge, AppendSceneRebasesEveryIndex) {
  Scene a;
  a.materials.resize(2);
  a.images.resize(1);
  a.samplers.resize(1);
  a.textures.push_back({0, 0});
  a.meshes.resize(3);
  Scene b;
  b.images.resize(2);
  b.samplers.resize(2);
  b.textures.push_back({1, 1});
  Material m;
  m.baseColorTexture.texture = 0;
  m.emissiveTexture.texture = 0;
  m.specularTexture.texture = 0;
  m.specularColorTexture.texture = 0;
  b.materials.push_back(m);
  Mesh mesh;
  mesh.primitives.emplace_back();
  mesh.spheres.push_back({glm::vec3(0), 1.0f, 0});
  b.meshes.push_back(mesh);
  b.instances.push_back({"i", 0, glm::mat4(1.0f), true});
  Light light;
  light.position = glm::vec3(1, 0, 0);
  light.direction = glm::vec3(1, 0, 0);
  light.radius = 1.0f;
  b.lights.push_back(light);
  Camera camera;
  b.cameras.push_back(camera);
  // Uniform scale 2, then a quarter turn about +Y, then a move by +10 in y.
  glm::mat4 transform(1.0f);
  transform = glm::translate(transform, glm::vec3(0, 10, 0));
  transform = glm::rotate(transform, glm::half_pi<float>(), glm::vec3(0, 1, 0));
  transform = glm::scale(transform, glm::vec3(2.0f));
  appendScene(a, b, transform);

  EXPECT_EQ(a.meshes.size(), 4u);
  EXPECT_EQ(a.meshes[3].primitives[0].material, 2u);
  EXPECT_EQ(a.meshes[3].spheres[0].material, 2u);
  EXPECT_EQ(a.materials[2].baseColorTexture.texture, 1);
  EXPECT_EQ(a.materials[2].emissiveTexture.texture, 1);
  EXPECT_EQ(a.materials[2].specularTexture.texture, 1);
  EXPECT_EQ(a.materials[2].specularColorTexture.texture, 1);
  EXPECT_FALSE(a.materials[2].normalTexture.valid());
  EXPECT_EQ(a.textures[1].image, 2u);
  EXPECT_EQ(a.textures[1].sampler, 2u);
  EXPECT_EQ(a.instances.at(0).mesh, 3u);
  const Light& moved = a.lights.at(0);
  EXPECT_NEAR(glm::distance(moved.position, glm::vec3(0, 10, -2)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::distance(moved.direction, glm::vec3(0, 0, -1)), 0.0f, 1e-5f);
  EXPECT_NEAR(moved.radius, 2.0f, 1e-5f);
  EXPECT_NEAR(glm::distance(a.cameras.at(0).position, glm::vec3(10, 10, 0)), 0.0f, 1e-4f);
  EXPECT_NEAR(glm::distance(a.cameras.at(0).up, glm::vec3(0, 1, 0)), 0.0f, 1e-5f);
}
