// Built-in scenes (scene/builtin*.cpp) and the embedded .mesh format they read.
#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scene/builtin.h"
#include "scene/mesh_asset.h"

namespace rayster::scene {
namespace {

Scene make(const std::string& name) {
  Result<Scene> scene = makeBuiltinScene(name);
  EXPECT_TRUE(scene.ok()) << name << ": " << (scene.ok() ? "" : scene.error().message);
  return scene.ok() ? std::move(*scene) : Scene{};
}

// World bounds of one instance, for "stands on the floor" checks.
Aabb instanceBounds(const Scene& scene, const Instance& instance) {
  Aabb box;
  for (const Primitive& prim : scene.meshes[instance.mesh].primitives)
    for (const glm::vec3& p : prim.positions) box.extend(glm::vec3(instance.worldFromObject * glm::vec4(p, 1.0f)));
  return box;
}

const Instance* findInstance(const Scene& scene, const std::string& name) {
  for (const Instance& instance : scene.instances)
    if (instance.name == name) return &instance;
  return nullptr;
}

size_t triangles(const Mesh& mesh) {
  size_t count = 0;
  for (const Primitive& prim : mesh.primitives) count += prim.indices.size() / 3;
  return count;
}

// A valid buffer: one triangle, three vertices.
std::vector<uint8_t> oneTriangleAsset(uint32_t thirdIndex = 2) {
  std::vector<uint8_t> bytes(16 + 3 * 12 + 3 * 4);
  const auto put = [&](size_t at, const void* value) { std::memcpy(&bytes[at], value, 4); };
  std::memcpy(bytes.data(), "RMSH", 4);
  const uint32_t header[3] = {1, 3, 1};
  for (int i = 0; i < 3; ++i) put(4 + 4 * i, &header[i]);
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  for (int i = 0; i < 9; ++i) put(16 + 4 * i, &positions[i]);
  const uint32_t indices[3] = {0, 1, thirdIndex};
  for (int i = 0; i < 3; ++i) put(52 + 4 * i, &indices[i]);
  return bytes;
}

TEST(BuiltinScenes, EveryOneValidatesWithCameraAndLight) {
  for (const std::string& name : builtinSceneNames()) {
    SCOPED_TRACE(name);
    const Scene scene = make("builtin:" + name);
    const Status status = validate(scene);
    EXPECT_TRUE(status.ok()) << status.error().message;
    EXPECT_GE(scene.cameras.size(), 1u);
    EXPECT_GE(scene.lights.size(), 1u);
  }
}

TEST(BuiltinScenes, NamesListAllFour) {
  EXPECT_EQ(builtinSceneNames(), (std::vector<std::string>{"cornell", "whitted", "spheres", "instances", "lights"}));
  Result<Scene> unknown = makeBuiltinScene("builtin:sponza");
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().code, ExitCode::BadInput);
  EXPECT_EQ(
      unknown.error().message,
      "unknown built-in scene 'builtin:sponza' (available: cornell, whitted, spheres, instances[:N], lights[:N])");
  Result<Scene> parameter = makeBuiltinScene("cornell:3");
  ASSERT_FALSE(parameter.ok());
  EXPECT_EQ(parameter.error().code, ExitCode::BadInput);
}

TEST(BuiltinScenes, WhittedTeapotAndBunnyStandOnTheFloor) {
  const Scene scene = make("whitted");
  const Instance* teapot = findInstance(scene, "teapot");
  const Instance* bunny = findInstance(scene, "bunny");
  ASSERT_TRUE(teapot && bunny);
  const Mesh& teapotMesh = scene.meshes[teapot->mesh];
  const Mesh& bunnyMesh = scene.meshes[bunny->mesh];
  EXPECT_GT(triangles(teapotMesh), 1000u);
  EXPECT_GT(triangles(bunnyMesh), 10000u);
  EXPECT_EQ(scene.materials[teapotMesh.primitives[0].material].metallic, 1.0f);
  const Material& ice = scene.materials[bunnyMesh.primitives[0].material];
  EXPECT_EQ(ice.transmission, 1.0f);
  EXPECT_GT(ice.thickness, 0.0f);
  for (const Instance* instance : {teapot, bunny}) {
    SCOPED_TRACE(instance->name);
    const Aabb box = instanceBounds(scene, *instance);
    EXPECT_NEAR(box.min.y, 0.0f, 1e-3f);
    EXPECT_GT(box.max.y, 0.5f);  // about a metre tall, not raw scan units
    EXPECT_LT(box.max.y, 1.5f);
  }
  // Side by side, not overlapping.
  EXPECT_LT(instanceBounds(scene, *teapot).max.x, instanceBounds(scene, *bunny).min.x);
  // Smooth normals are unit length.
  for (const glm::vec3& n : bunnyMesh.primitives[0].normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
  EXPECT_EQ(scene.environment.kind, Environment::Kind::Sky);
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_GT(scene.lights[0].radius, 0.0f);
}

TEST(BuiltinScenes, WhittedFloorIsVeinedMarble) {
  const Scene scene = make("whitted");
  const Instance* floor = findInstance(scene, "floor");
  ASSERT_TRUE(floor);
  const Primitive& prim = scene.meshes[floor->mesh].primitives[0];
  ASSERT_EQ(prim.uvs.size(), prim.positions.size());
  const Material& marble = scene.materials[prim.material];
  ASSERT_TRUE(marble.baseColorTexture.valid());
  EXPECT_GT(marble.baseColorTexture.scale.x, 1.0f);  // tiled
  const Texture& texture = scene.textures[size_t(marble.baseColorTexture.texture)];
  EXPECT_EQ(scene.samplers[texture.sampler].wrapS, Wrap::Repeat);
  const ImageData& image = scene.images[texture.image];
  double sum = 0.0, sumSq = 0.0;
  uint8_t darkest = 255, lightest = 0;
  for (size_t i = 0; i < image.rgba.size(); i += 4) {
    const uint8_t g = image.rgba[i + 1];
    sum += g;
    sumSq += double(g) * g;
    darkest = std::min(darkest, g);
    lightest = std::max(lightest, g);
  }
  const double n = double(image.rgba.size() / 4);
  const double variance = sumSq / n - (sum / n) * (sum / n);
  EXPECT_GT(variance, 50.0);  // not a flat colour
  EXPECT_GT(sum / n, 150.0);  // mostly light stone
  EXPECT_LT(darkest, 140);    // with dark veins
  EXPECT_GT(int(lightest) - int(darkest), 80);
}

TEST(BuiltinScenes, SpheresMixAnalyticAndTriangleMeshes) {
  const Scene scene = make("builtin:spheres");
  const auto spheres =
      std::find_if(scene.meshes.begin(), scene.meshes.end(), [](const Mesh& m) { return !m.spheres.empty(); });
  ASSERT_NE(spheres, scene.meshes.end());
  EXPECT_GE(spheres->spheres.size(), 15u);
  EXPECT_TRUE(std::any_of(scene.meshes.begin(), scene.meshes.end(), [](const Mesh& m) { return triangles(m) > 0; }));
  EXPECT_TRUE(std::any_of(spheres->spheres.begin(), spheres->spheres.end(),
                          [&](const Sphere& s) { return scene.materials[s.material].transmission > 0.0f; }));
  EXPECT_TRUE(std::any_of(scene.lights.begin(), scene.lights.end(),
                          [](const Light& l) { return l.type == LightType::Directional && l.angularRadius > 0.0f; }));
}

TEST(BuiltinScenes, InstancesShareOneMesh) {
  const Scene scene = make("builtin:instances:10");
  std::vector<const Instance*> bunnies;
  for (const Instance& instance : scene.instances)
    if (instance.name.rfind("bunny", 0) == 0) bunnies.push_back(&instance);
  ASSERT_EQ(bunnies.size(), 10u);
  for (const Instance* b : bunnies) EXPECT_EQ(b->mesh, bunnies[0]->mesh);
  // Every copy stands on the floor, inside the camera's far plane.
  for (const Instance* b : bunnies) EXPECT_NEAR(instanceBounds(scene, *b).min.y, 0.0f, 1e-3f);
  EXPECT_EQ(make("instances").instances.size(), size_t(kDefaultBuiltinInstances) + 1);  // + floor
}

TEST(BuiltinScenes, InstanceCountIsChecked) {
  for (const char* bad : {"instances:0", "instances:abc", "builtin:instances:", "instances:-5", "instances:12x",
                          "instances:1000001", "instances:99999999999"}) {
    SCOPED_TRACE(bad);
    Result<Scene> scene = makeBuiltinScene(bad);
    ASSERT_FALSE(scene.ok());
    EXPECT_EQ(scene.error().code, ExitCode::BadInput);
  }
}

TEST(BuiltinMeshAsset, ParsesAValidBuffer) {
  const std::vector<uint8_t> bytes = oneTriangleAsset();
  Result<Primitive> prim = parseMeshAsset(bytes, 7);
  ASSERT_TRUE(prim.ok()) << prim.error().message;
  EXPECT_EQ(prim->positions.size(), 3u);
  EXPECT_EQ(prim->indices, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_EQ(prim->material, 7u);
  EXPECT_TRUE(prim->uvs.empty());
  ASSERT_EQ(prim->normals.size(), 3u);
  EXPECT_NEAR(prim->normals[0].z, 1.0f, 1e-6f);  // counter-clockwise in xy faces +z
}

TEST(BuiltinMeshAsset, RejectsTruncatedBuffers) {
  const std::vector<uint8_t> bytes = oneTriangleAsset();
  for (size_t size : {size_t(0), size_t(3), size_t(15), size_t(16), bytes.size() - 1}) {
    SCOPED_TRACE(size);
    Result<Primitive> prim = parseMeshAsset(std::span<const uint8_t>(bytes.data(), size), 0);
    ASSERT_FALSE(prim.ok());
    EXPECT_EQ(prim.error().code, ExitCode::BadInput);
  }
  std::vector<uint8_t> longer = bytes;
  longer.push_back(0);
  EXPECT_FALSE(parseMeshAsset(longer, 0).ok());
}

TEST(BuiltinMeshAsset, RejectsBadHeaderAndIndices) {
  Result<Primitive> pastEnd = parseMeshAsset(oneTriangleAsset(3), 0);
  ASSERT_FALSE(pastEnd.ok());
  EXPECT_EQ(pastEnd.error().code, ExitCode::BadInput);
  EXPECT_NE(pastEnd.error().message.find("past the vertex count"), std::string::npos) << pastEnd.error().message;

  std::vector<uint8_t> magic = oneTriangleAsset();
  magic[0] = 'X';
  EXPECT_FALSE(parseMeshAsset(magic, 0).ok());
  std::vector<uint8_t> version = oneTriangleAsset();
  version[4] = 2;
  EXPECT_FALSE(parseMeshAsset(version, 0).ok());
  // Counts chosen so 32-bit size arithmetic would wrap to the real buffer size.
  std::vector<uint8_t> huge = oneTriangleAsset();
  const uint32_t wraps = 0x80000000u / 3 * 2;
  std::memcpy(&huge[8], &wraps, 4);
  EXPECT_FALSE(parseMeshAsset(huge, 0).ok());
}

TEST(BuiltinMeshAsset, EmbeddedMeshesParse) {
  for (EmbeddedMesh which : {EmbeddedMesh::Teapot, EmbeddedMesh::Bunny}) {
    Result<Primitive> prim = parseMeshAsset(embeddedMeshBytes(which), 0);
    ASSERT_TRUE(prim.ok()) << prim.error().message;
    EXPECT_GT(prim->indices.size(), 3000u);
  }
}

}  // namespace
}  // namespace rayster::scene

TEST(BuiltinScenes, LightsSceneHasTheRequestedLights) {
  for (uint32_t n : {1u, 8u, 256u}) {
    auto scene = rayster::scene::makeBuiltinScene("builtin:lights:" + std::to_string(n));
    ASSERT_TRUE(scene.ok());
    EXPECT_EQ(scene->lights.size(), n);
    EXPECT_FALSE(scene->cameras.empty());
  }
  EXPECT_FALSE(rayster::scene::makeBuiltinScene("lights:0").ok());
  EXPECT_FALSE(rayster::scene::makeBuiltinScene("lights:x").ok());
}

namespace rayster::scene {
namespace {

// Built-in models (scene/builtin_models.cpp): one object and its material for scene files to
// compose, no light or camera of its own; rendered alone, completed as a file is.
TEST(BuiltinScenes, ModelsAreOneObjectWithANamedMaterial) {
  Result<Scene> teapot = makeBuiltinModel("builtin:teapot:mirror");
  ASSERT_TRUE(teapot.ok()) << teapot.error().message;
  ASSERT_EQ(teapot->meshes.size(), 1u);
  EXPECT_EQ(teapot->triangleCount(), 3968u);
  EXPECT_TRUE(teapot->lights.empty());
  EXPECT_TRUE(teapot->cameras.empty());
  ASSERT_EQ(teapot->materials.size(), 1u);
  EXPECT_EQ(teapot->materials[0].metallic, 1.0f);
  EXPECT_EQ(teapot->materials[0].roughness, 0.0f);
  Result<Scene> bunny = makeBuiltinModel("bunny");
  ASSERT_TRUE(bunny.ok());
  EXPECT_EQ(bunny->triangleCount(), 14696u);
  EXPECT_EQ(bunny->materials[0].name, "white");
  Result<Scene> sphere = makeBuiltinModel("builtin:sphere:red");
  ASSERT_TRUE(sphere.ok());
  ASSERT_EQ(sphere->meshes.size(), 1u);
  EXPECT_EQ(sphere->meshes[0].spheres.size(), 1u);
  EXPECT_TRUE(isBuiltinModel("builtin:floor:grey"));
  EXPECT_FALSE(isBuiltinModel("builtin:whitted"));

  Result<Scene> plaid = makeBuiltinModel("builtin:bunny:plaid");
  ASSERT_FALSE(plaid.ok());
  EXPECT_EQ(plaid.error().code, ExitCode::BadInput);
  EXPECT_EQ(plaid.error().message,
            "builtin:bunny: unknown material 'plaid' (available: white, grey, red, green, blue, mirror)");
}

}  // namespace
}  // namespace rayster::scene
