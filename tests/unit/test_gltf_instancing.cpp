// EXT_mesh_gpu_instancing (scene/gltf_instancing.cpp) and KHR_mesh_quantization: one instance per
// element at node × T × R × S, quantized attributes (normalized or not) with node scales that
// undo the quantization, animated instanced nodes moving every copy, and broken attributes refused.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include "scene/animation.h"
#include "tests/unit/gltf_test_util.h"

namespace rayster::test {
namespace {

// The quad drawn at three places: translated, rotated 90° about Y (quantized as normalized shorts)
// and scaled, under a parent node translated by (0, 10, 0).
Doc instancedQuad() {
  Doc d = quadDoc();
  d.j["extensionsUsed"] = {"EXT_mesh_gpu_instancing", "KHR_mesh_quantization"};
  const int t = d.floats({1, 0, 0, 0, 2, 0, 0, 0, 3}, "VEC3", 3);
  const int16_t h = int16_t(std::lround(std::sqrt(0.5) * 32767));
  const int r =
      d.accessor(d.view(std::vector<int16_t>{0, 0, 0, 32767, 0, h, 0, h, 0, 0, 0, 32767}), kShort, 3, "VEC4", true);
  const int s = d.floats({1, 1, 1, 1, 1, 1, 2, 2, 2}, "VEC3", 3);
  d.node(0)["extensions"]["EXT_mesh_gpu_instancing"] = {
      {"attributes", {{"TRANSLATION", t}, {"ROTATION", r}, {"SCALE", s}, {"_ID", t}}}};
  d.node(0)["translation"] = {0, 10, 0};
  return d;
}

glm::vec3 worldOf(const scene::Instance& instance, glm::vec3 p) {
  return glm::vec3(instance.worldFromObject * glm::vec4(p, 1.0f));
}

void expectNear(glm::vec3 a, glm::vec3 b) { EXPECT_LT(glm::length(a - b), 1e-4f) << a.x << "," << a.y << "," << a.z; }

TEST(GltfInstancing, EveryElementIsAnInstanceOfTheOneMesh) {
  TempDir dir;
  auto scene = loadBytes(dir, instancedQuad().glb(), "instanced.glb");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  ASSERT_EQ(scene->meshes.size(), 1u) << "one mesh, one BLAS";
  ASSERT_EQ(scene->instances.size(), 3u);
  for (const scene::Instance& i : scene->instances) EXPECT_EQ(i.mesh, 0u);
  expectNear(worldOf(scene->instances[0], {1, 1, 0}), {2, 11, 0});
  // Rotated 90° about +Y: +X goes to -Z.
  expectNear(worldOf(scene->instances[1], {1, 0, 0}), {0, 12, -1});
  expectNear(worldOf(scene->instances[2], {1, 1, 0}), {2, 12, 3});
  EXPECT_EQ(scene->instances[2].name, "quad#2");
}

TEST(GltfInstancing, AnAnimatedInstancedNodeMovesEveryCopy) {
  TempDir dir;
  Doc d = instancedQuad();
  const int times = d.floats({0, 1}, "SCALAR", 1);
  d.j["accessors"][size_t(times)]["min"] = {0};
  d.j["accessors"][size_t(times)]["max"] = {1};
  const int moves = d.floats({0, 10, 0, 5, 10, 0}, "VEC3", 3);
  d.j["animations"] = Json::array(
      {{{"samplers", Json::array({{{"input", times}, {"output", moves}}})},
        {"channels", Json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}})}}});
  auto scene = loadBytes(dir, d.glb(), "animated.glb");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  ASSERT_EQ(scene->instances.size(), 3u);
  scene::evaluateAnimations(*scene, 1.0f);
  expectNear(worldOf(scene->instances[0], {0, 0, 0}), {6, 10, 0});
  expectNear(worldOf(scene->instances[2], {1, 1, 0}), {7, 12, 3});
}

TEST(GltfInstancing, BrokenAttributesAreRefused) {
  TempDir dir;
  {
    Doc d = instancedQuad();
    d.j["accessors"].back()["count"] = 2;  // SCALE has 2 elements, the others 3
    auto scene = loadBytes(dir, d.glb(), "count.glb");
    ASSERT_FALSE(scene.ok());
    EXPECT_NE(scene.error().message.find("nodes[0].extensions.EXT_mesh_gpu_instancing.attributes.SCALE has 2 elements, "
                                         "the others 3"),
              std::string::npos)
        << scene.error().message;
  }
  {
    Doc d = instancedQuad();
    d.node(0)["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["TRANSLATION"] = 99;
    auto scene = loadBytes(dir, d.glb(), "missing.glb");
    ASSERT_FALSE(scene.ok());
    EXPECT_NE(scene.error().message.find("attributes.TRANSLATION names no accessor"), std::string::npos)
        << scene.error().message;
  }
}

// KHR_mesh_quantization as gltf-transform writes it: positions as normalized shorts in [-1, 1]
// with the node's scale and translation mapping them back, normals as normalized bytes, UVs as
// normalized unsigned shorts, positions also as plain (unnormalized) unsigned bytes.
TEST(GltfQuantization, NormalizedAndIntegerAttributesWithUndoingNodeScales) {
  TempDir dir;
  Doc d;
  d.j["extensionsUsed"] = {"KHR_mesh_quantization"};
  d.j["extensionsRequired"] = {"KHR_mesh_quantization"};
  const int pos = d.accessor(d.view(std::vector<int16_t>{-32767, -32767, 0, 0, 0, 32767, 0, 0, 32767, 0, 0, 0}, 8),
                             kShort, 3, "VEC3", true);
  // min and max of a normalized accessor are its stored integers (the validator compares those).
  d.j["accessors"][size_t(pos)]["min"] = {-32767, -32767, 0};
  d.j["accessors"][size_t(pos)]["max"] = {32767, 32767, 0};
  const int nrm =
      d.accessor(d.view(std::vector<int8_t>{0, 0, 127, 0, 0, 0, 127, 0, 0, 0, 127, 0}, 4), kByte, 3, "VEC3", true);
  const int uv = d.accessor(d.view(std::vector<uint16_t>{0, 65535, 65535, 65535, 32768, 0}), kUShort, 3, "VEC2", true);
  const int raw = d.accessor(d.view(std::vector<uint8_t>{0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0}, 4), kUByte, 3, "VEC3");
  d.j["accessors"][size_t(raw)]["min"] = {0, 0, 0};
  d.j["accessors"][size_t(raw)]["max"] = {2, 2, 0};
  Json quantized = {{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}}}};
  Json integer = {{"attributes", {{"POSITION", raw}}}};
  d.j["meshes"] = Json::array();
  d.j["meshes"].push_back({{"primitives", Json::array({quantized})}});
  d.j["meshes"].push_back({{"primitives", Json::array({integer})}});
  d.j["nodes"] = Json::array(
      {{{"mesh", 0}, {"scale", {2, 2, 2}}, {"translation", {5, 0, 0}}}, {{"mesh", 1}, {"scale", {0.5, 0.5, 0.5}}}});
  d.j["scenes"] = Json::array({{{"nodes", {0, 1}}}});
  auto scene = loadBytes(dir, d.glb(), "quantized.glb");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  ASSERT_EQ(scene->instances.size(), 2u);
  const scene::Primitive& p = scene->meshes[0].primitives.at(0);
  expectNear(worldOf(scene->instances[0], p.positions[0]), {3, -2, 0});
  expectNear(worldOf(scene->instances[0], p.positions[2]), {7, 0, 0});
  expectNear(p.normals[1], {0, 0, 1});
  EXPECT_NEAR(p.uvs[2].x, 32768.0f / 65535.0f, 1e-6f);
  EXPECT_EQ(p.uvs[1], glm::vec2(1, 1));
  const scene::Primitive& q = scene->meshes[1].primitives.at(0);
  expectNear(worldOf(scene->instances[1], q.positions[2]), {0, 1, 0});
}

}  // namespace
}  // namespace rayster::test
