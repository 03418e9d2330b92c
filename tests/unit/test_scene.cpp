// The CPU scene model: the built-in Cornell box, procedural geometry and validate().
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "scene/builtin.h"
#include "scene/geometry.h"
#include "scene/scene.h"

using namespace rayster;
using namespace rayster::scene;

namespace {

const Instance& findInstance(const Scene& scene, const std::string& name) {
  for (const Instance& instance : scene.instances)
    if (instance.name == name) return instance;
  ADD_FAILURE() << "no instance " << name;
  static const Instance none;
  return none;
}

const Primitive& primitiveOf(const Scene& scene, const std::string& name) {
  return scene.meshes.at(findInstance(scene, name).mesh).primitives.at(0);
}

glm::vec3 centroid(const std::vector<glm::vec3>& points) {
  glm::vec3 sum(0.0f);
  for (const glm::vec3& p : points) sum += p;
  return sum / static_cast<float>(points.size());
}

// Every triangle's winding agrees with its vertex normals (counter-clockwise from the front).
void expectWindingMatchesNormals(const Primitive& prim, const std::string& what) {
  for (size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
    const uint32_t a = prim.indices[t], b = prim.indices[t + 1], c = prim.indices[t + 2];
    const glm::vec3 face = glm::cross(prim.positions[b] - prim.positions[a], prim.positions[c] - prim.positions[a]);
    const glm::vec3 normal = prim.normals[a] + prim.normals[b] + prim.normals[c];
    EXPECT_GT(glm::dot(face, normal), 0.0f) << what << " triangle " << t / 3;
  }
}

Scene smallValidScene() {
  Scene scene;
  scene.materials.push_back(Material{});
  Mesh mesh;
  mesh.primitives.push_back(makeQuad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 0));
  scene.meshes.push_back(mesh);
  scene.instances.push_back(Instance{"quad", 0, glm::mat4(1.0f), true});
  scene.cameras.push_back(Camera{});
  return scene;
}

void expectBadInput(const Scene& scene, const std::string& fragment) {
  const Status status = validate(scene);
  ASSERT_FALSE(status.ok()) << "expected failure mentioning '" << fragment << "'";
  EXPECT_EQ(status.error().code, ExitCode::BadInput);
  EXPECT_NE(status.error().message.find(fragment), std::string::npos) << status.error().message;
}

}  // namespace

TEST(Builtin, NamesAndPrefix) {
  EXPECT_EQ(builtinSceneNames(), (std::vector<std::string>{"cornell", "whitted", "spheres", "instances", "lights"}));
  EXPECT_TRUE(makeBuiltinScene("cornell").ok());
  EXPECT_TRUE(makeBuiltinScene("builtin:cornell").ok());
  auto unknown = makeBuiltinScene("sponza");
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().code, ExitCode::BadInput);
  EXPECT_EQ(unknown.error().message,
            "unknown built-in scene 'sponza' (available: cornell, whitted, spheres, instances[:N], lights[:N])");
}

TEST(Cornell, ValidatesWithOneLightAndCamera) {
  const Scene scene = makeCornellBox();
  const Status status = validate(scene);
  EXPECT_TRUE(status.ok()) << status.error().message;
  ASSERT_EQ(scene.lights.size(), 1u);
  ASSERT_EQ(scene.cameras.size(), 1u);
  EXPECT_EQ(scene.cameras[0].name, "default");
  EXPECT_NEAR(glm::degrees(scene.cameras[0].yFov), 39.3, 0.05);
  EXPECT_EQ(scene.cameras[0].position, glm::vec3(2.78f, 2.73f, -8.0f));
  EXPECT_EQ(scene.ambient, glm::vec3(0.02f));
  for (const Instance& instance : scene.instances) EXPECT_EQ(instance.worldFromObject, glm::mat4(1.0f));
}

TEST(Cornell, MaterialColours) {
  const Scene scene = makeCornellBox();
  auto materialOf = [&](const std::string& name) { return scene.materials.at(primitiveOf(scene, name).material); };
  EXPECT_EQ(materialOf("floor").baseColor, glm::vec4(0.725f, 0.71f, 0.68f, 1.0f));
  EXPECT_EQ(materialOf("red-wall").baseColor, glm::vec4(0.63f, 0.065f, 0.05f, 1.0f));
  EXPECT_EQ(materialOf("green-wall").baseColor, glm::vec4(0.14f, 0.45f, 0.091f, 1.0f));
  EXPECT_EQ(materialOf("short-block").roughness, 1.0f);
  EXPECT_EQ(materialOf("short-block").metallic, 0.0f);
  const Material& mirror = materialOf("tall-block");
  EXPECT_EQ(mirror.metallic, 1.0f);
  EXPECT_NEAR(mirror.roughness, 0.08f, 1e-6f);
}

TEST(Cornell, LightAndVisibleEmitterAgree) {
  const Scene scene = makeCornellBox();
  const Light& light = scene.lights[0];
  EXPECT_EQ(light.type, LightType::Point);
  EXPECT_EQ(light.position, glm::vec3(2.78f, 4.9f, 2.795f));
  EXPECT_FLOAT_EQ(light.radius, 0.3f);
  EXPECT_FLOAT_EQ(light.intensity, 12.0f);
  const Instance& sphere = findInstance(scene, "light-sphere");
  EXPECT_FALSE(sphere.castsShadows);
  const Primitive& prim = scene.meshes[sphere.mesh].primitives[0];
  for (const glm::vec3& p : prim.positions) EXPECT_NEAR(glm::length(p - light.position), light.radius, 1e-5f);
  // Radiance L of a sphere with radiant intensity I: I = L * pi r^2.
  const glm::vec3 emissive = scene.materials[prim.material].emissive;
  const glm::vec3 intensity = emissive * glm::pi<float>() * light.radius * light.radius;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(intensity[c], light.color[c] * light.intensity, 1e-4f);
}

TEST(Cornell, WallNormalsFaceIntoTheRoom) {
  const Scene scene = makeCornellBox();
  const glm::vec3 roomCentre = scene.bounds().centre();
  for (const char* name : {"floor", "ceiling", "back-wall", "red-wall", "green-wall"}) {
    const Primitive& prim = primitiveOf(scene, name);
    const glm::vec3 faceCentre = centroid(prim.positions);
    for (const glm::vec3& n : prim.normals) {
      EXPECT_GT(glm::dot(n, roomCentre - faceCentre), 0.0f) << name;
      EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f) << name;
    }
    expectWindingMatchesNormals(prim, name);
  }
}

TEST(Cornell, BlockNormalsFaceOutward) {
  const Scene scene = makeCornellBox();
  for (const char* name : {"short-block", "tall-block"}) {
    const Primitive& prim = primitiveOf(scene, name);
    ASSERT_EQ(prim.positions.size(), 20u) << name;  // top + 4 sides, 4 vertices each
    const glm::vec3 blockCentre = centroid(prim.positions);
    for (size_t face = 0; face < 5; ++face) {
      const std::vector<glm::vec3> corners(prim.positions.begin() + face * 4, prim.positions.begin() + face * 4 + 4);
      const glm::vec3 faceCentre = centroid(corners);
      for (size_t k = 0; k < 4; ++k)
        EXPECT_GT(glm::dot(prim.normals[face * 4 + k], faceCentre - blockCentre), 0.0f) << name << " face " << face;
    }
    expectWindingMatchesNormals(prim, name);
  }
  float shortTop = 0, tallTop = 0;
  for (const glm::vec3& p : primitiveOf(scene, "short-block").positions) shortTop = std::max(shortTop, p.y);
  for (const glm::vec3& p : primitiveOf(scene, "tall-block").positions) tallTop = std::max(tallTop, p.y);
  EXPECT_FLOAT_EQ(shortTop, 1.65f);
  EXPECT_FLOAT_EQ(tallTop, 3.30f);
}

TEST(Cornell, RedWallIsAtLargerX) {
  const Scene scene = makeCornellBox();
  const float redX = centroid(primitiveOf(scene, "red-wall").positions).x;
  const float greenX = centroid(primitiveOf(scene, "green-wall").positions).x;
  EXPECT_GT(redX, 5.4f);
  EXPECT_NEAR(greenX, 0.0f, 1e-6f);
}

TEST(Cornell, BoundsAndTriangleCount) {
  const Scene scene = makeCornellBox();
  const Aabb box = scene.bounds();
  ASSERT_TRUE(box.valid());
  EXPECT_NEAR(box.min.x, 0.0f, 1e-5f);
  EXPECT_NEAR(box.min.y, 0.0f, 1e-5f);
  EXPECT_NEAR(box.min.z, 0.0f, 1e-5f);
  EXPECT_NEAR(box.max.x, 5.56f, 1e-5f);
  EXPECT_NEAR(box.max.y, 5.488f, 1e-5f);
  EXPECT_NEAR(box.max.z, 5.592f, 1e-5f);
  // 5 walls * 2 + 2 blocks * 5 faces * 2 + a 16x32 sphere (pole bands are fans).
  EXPECT_EQ(scene.triangleCount(), 10u + 20u + (16u * 32u * 2u - 2u * 32u));
  for (const Mesh& mesh : scene.meshes) expectWindingMatchesNormals(mesh.primitives[0], mesh.name);
}

TEST(Geometry, UvSphere) {
  const Primitive sphere = makeUvSphere(2.0f, 6, 8, 3);
  EXPECT_EQ(sphere.material, 3u);
  EXPECT_EQ(sphere.indices.size() / 3, uvSphereTriangleCount(6, 8));
  EXPECT_EQ(sphere.uvs.size(), sphere.positions.size());
  for (size_t i = 0; i < sphere.positions.size(); ++i) {
    EXPECT_NEAR(glm::length(sphere.positions[i]), 2.0f, 1e-5f);
    EXPECT_NEAR(glm::length(sphere.normals[i] - sphere.positions[i] * 0.5f), 0.0f, 1e-5f);
  }
  expectWindingMatchesNormals(sphere, "sphere");
  for (size_t t = 0; t < sphere.indices.size(); t += 3) {  // no degenerate triangles
    const glm::vec3 a = sphere.positions[sphere.indices[t]], b = sphere.positions[sphere.indices[t + 1]],
                    c = sphere.positions[sphere.indices[t + 2]];
    EXPECT_GT(glm::length(glm::cross(b - a, c - a)), 1e-6f);
  }
}

TEST(Geometry, BoxIsFlatAndOutward) {
  const Primitive box = makeBox({-1, -2, -3}, {1, 2, 3}, 0);
  EXPECT_EQ(box.positions.size(), 24u);
  EXPECT_EQ(box.indices.size(), 36u);
  for (size_t i = 0; i < box.positions.size(); ++i) {
    const glm::vec3 n = box.normals[i];
    EXPECT_NEAR(std::abs(n.x) + std::abs(n.y) + std::abs(n.z), 1.0f, 1e-6f);  // axis-aligned
    EXPECT_GT(glm::dot(n, box.positions[i]), 0.0f);
  }
  expectWindingMatchesNormals(box, "box");
  const Primitive quad = makeQuad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 0);
  EXPECT_EQ(quad.normals[0], glm::vec3(0, 0, 1));  // counter-clockwise seen from +z
}

TEST(Validate, AcceptsASmallScene) { EXPECT_TRUE(validate(smallValidScene()).ok()); }

TEST(Validate, RejectsIndexPastVertexCount) {
  Scene scene = smallValidScene();
  scene.meshes[0].primitives[0].indices[4] = 4;
  expectBadInput(scene, "past the vertex count");
}

TEST(Validate, RejectsNanTransform) {
  Scene scene = smallValidScene();
  scene.instances[0].worldFromObject[3][1] = std::numeric_limits<float>::quiet_NaN();
  expectBadInput(scene, "non-finite transform");
}

TEST(Validate, RejectsOutOfRangeMaterialAndMesh) {
  Scene scene = smallValidScene();
  scene.meshes[0].primitives[0].material = 1;
  expectBadInput(scene, "material 1 out of range");
  scene = smallValidScene();
  scene.instances[0].mesh = 2;
  expectBadInput(scene, "mesh 2");
}

TEST(Validate, RejectsMalformedPrimitives) {
  Scene scene = smallValidScene();
  scene.meshes[0].primitives[0].indices.pop_back();
  expectBadInput(scene, "multiple of 3");
  scene = smallValidScene();
  scene.meshes[0].primitives[0].normals.pop_back();
  expectBadInput(scene, "normals");
  scene = smallValidScene();
  scene.meshes[0].primitives[0].uvs.pop_back();
  expectBadInput(scene, "uvs");
  scene = smallValidScene();
  scene.meshes[0].primitives[0].colors.assign(2, glm::vec4(1.0f));
  expectBadInput(scene, "colours");
  scene = smallValidScene();
  scene.materials[0].specularColorTexture.texture = 3;
  expectBadInput(scene, "missing texture");
  scene = smallValidScene();
  scene.meshes[0].primitives[0].uvs.clear();  // no uvs at all is fine
  EXPECT_TRUE(validate(scene).ok());
  scene.meshes[0].primitives[0].positions[2].z = std::numeric_limits<float>::infinity();
  expectBadInput(scene, "not finite");
}

TEST(Validate, RejectsNoCamera) {
  Scene scene = smallValidScene();
  scene.cameras.clear();
  expectBadInput(scene, "no camera");
}
