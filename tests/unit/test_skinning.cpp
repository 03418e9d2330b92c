// Skins and morph targets in the scene layer: the loader reads JOINTS/WEIGHTS (two sets), inverse
// bind matrices, morph targets, mesh and node weights and weights animations; deformPrimitive()
// poses a quad by hand-computed numbers; malformed skins and targets are refused in one line.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "gltf_test_util.h"
#include "scene/animation.h"
#include "scene/skinning.h"

using namespace rayster;
using namespace rayster::test;

namespace {

// quadDoc() with a two-joint skin: vertices 0 and 1 follow joint 0 (node 1, at the origin), 2 and 3
// joint 1 (node 2, 1 m up), vertex 3 half each through a second influence set; node 2 turns 90°
// about Z over 1 s. The quad also has a morph target moving vertex 2 by +1 in X (weight 0.5).
Doc skinnedQuad() {
  Doc d = quadDoc();
  const int joints0 =
      d.accessor(d.view(std::vector<uint8_t>{0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}), kUByte, 4, "VEC4");
  const int weights0 = d.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0, 0, 0}, "VEC4", 4);
  const int joints1 =
      d.accessor(d.view(std::vector<uint16_t>{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}), kUShort, 4, "VEC4");
  const int weights1 = d.floats({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.5f, 0, 0, 0}, "VEC4", 4);
  const int delta = d.floats({0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0}, "VEC3", 3);
  Json& prim = d.j["meshes"][0]["primitives"][0];
  prim["attributes"]["JOINTS_0"] = joints0;
  prim["attributes"]["WEIGHTS_0"] = weights0;
  prim["attributes"]["JOINTS_1"] = joints1;
  prim["attributes"]["WEIGHTS_1"] = weights1;
  prim["targets"] = Json::array({{{"POSITION", delta}}});
  d.j["meshes"][0]["weights"] = {0.5};
  // Inverse bind matrices: joint 1 sits at y = 1.
  std::vector<float> ibm(32, 0.0f);
  for (int k = 0; k < 4; ++k) ibm[size_t(k * 5)] = ibm[size_t(16 + k * 5)] = 1.0f;
  ibm[16 + 13] = -1.0f;
  const int inverseBind = d.floats(ibm, "MAT4", 16);
  d.j["skins"] = Json::array({{{"joints", {1, 2}}, {"inverseBindMatrices", inverseBind}}});
  d.node(0)["skin"] = 0;
  d.j["nodes"].push_back({{"name", "root"}, {"children", {2}}});
  d.j["nodes"].push_back({{"name", "tip"}, {"translation", {0, 1, 0}}});
  d.j["scenes"][0]["nodes"] = {0, 1};
  const int times = d.floats({0, 1}, "SCALAR", 1);
  const float s = std::sqrt(0.5f);
  const int turns = d.floats({0, 0, 0, 1, 0, 0, s, s}, "VEC4", 4);
  const int weightTimes = d.floats({0, 1}, "SCALAR", 1);
  const int weightValues = d.floats({0, 1}, "SCALAR", 1);
  d.j["animations"] = Json::array(
      {{{"samplers",
         Json::array({{{"input", times}, {"output", turns}}, {{"input", weightTimes}, {"output", weightValues}}})},
        {"channels", Json::array({{{"sampler", 0}, {"target", {{"node", 2}, {"path", "rotation"}}}},
                                  {{"sampler", 1}, {"target", {{"node", 0}, {"path", "weights"}}}}})}}});
  return d;
}

scene::Scene load(Doc d) {
  TempDir dir;
  auto scene = scene::loadGltf(dir.write("skin.gltf", d.gltf()));
  EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error().message);
  return scene.ok() ? std::move(*scene) : scene::Scene{};
}

std::string refusal(Doc d) {
  TempDir dir;
  auto scene = scene::loadGltf(dir.write("bad.gltf", d.gltf()));
  return scene.ok() ? std::string("(loaded)") : scene.error().message;
}

}  // namespace

TEST(Skinning, LoaderReadsSkinsTargetsAndWeights) {
  scene::Scene s = load(skinnedQuad());
  ASSERT_EQ(s.skins.size(), 1u);
  EXPECT_EQ(s.skins[0].joints.size(), 2u);
  ASSERT_EQ(s.instances.size(), 1u);
  EXPECT_EQ(s.instances[0].skin, 0);
  EXPECT_EQ(s.instances[0].worldFromObject, glm::mat4(1.0f)) << "a skin places its mesh in world space";
  const scene::Primitive& p = s.meshes[0].primitives[0];
  ASSERT_EQ(p.influences.size(), 2u);
  EXPECT_EQ(p.influences[0].joints[2].x, 1);
  EXPECT_FLOAT_EQ(p.influences[1].weights[3].x, 0.5f);
  ASSERT_EQ(p.targets.size(), 1u);
  EXPECT_FLOAT_EQ(p.targets[0].positions[2].x, 1.0f);
  EXPECT_EQ(s.meshes[0].weights, std::vector<float>{0.5f});
  EXPECT_TRUE(scene::deforms(s, s.instances[0]));
}

TEST(Skinning, DeformPrimitivePosesByHandComputedNumbers) {
  scene::Scene s = load(skinnedQuad());
  ASSERT_EQ(s.instances.size(), 1u);
  // Rest (t = 0): morph weight 0 from the animation, joints at bind: the quad as written.
  scene::evaluateAnimations(s, 0.0f);
  scene::Primitive rest = scene::deformPrimitive(s, s.instances[0], s.meshes[0].primitives[0]);
  EXPECT_NEAR(glm::length(rest.positions[2] - glm::vec3(1, 1, 0)), 0.0f, 1e-5f);
  // t = 1: weight 1 moves vertex 2 to (2, 1, 0) in bind space; joint 1 turns 90° about Z around
  // (0, 1, 0): (2, 1) -> (0, 3). Vertex 3 (0, 1, 0) sits on the joint, half on each: unmoved.
  // Vertex 0 follows joint 0 only: unmoved.
  scene::evaluateAnimations(s, 1.0f);
  scene::Primitive posed = scene::deformPrimitive(s, s.instances[0], s.meshes[0].primitives[0]);
  EXPECT_NEAR(glm::length(posed.positions[2] - glm::vec3(0, 3, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(posed.positions[3] - glm::vec3(0, 1, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(posed.positions[0] - glm::vec3(0, 0, 0)), 0.0f, 1e-5f);
  // Normals turn with their joint: +Z stays +Z under a turn about Z.
  EXPECT_NEAR(posed.normals[2].z, 1.0f, 1e-5f);
  // The baked copy holds the same positions and nothing that deforms.
  scene::Scene baked = scene::bakePose(s);
  EXPECT_TRUE(baked.animations.empty());
  EXPECT_FALSE(scene::deforms(baked, baked.instances[0]));
  EXPECT_NEAR(glm::length(baked.meshes[baked.instances[0].mesh].primitives[0].positions[2] - glm::vec3(0, 3, 0)), 0.0f,
              1e-5f);
}

TEST(Skinning, WeightsChannelsInterpolate) {
  scene::Scene s = load(skinnedQuad());
  scene::evaluateAnimations(s, 0.25f);
  ASSERT_EQ(s.instances[0].morphWeights.size(), 1u);
  EXPECT_NEAR(s.instances[0].morphWeights[0], 0.25f, 1e-6f);
}

TEST(Skinning, MalformedSkinsAndTargetsAreRefused) {
  {
    Doc d = skinnedQuad();
    d.j["skins"][0]["joints"] = {1, 7};
    EXPECT_NE(refusal(d).find("skins[0].joints[1]: node 7 does not exist"), std::string::npos) << refusal(d);
  }
  {
    Doc d = skinnedQuad();
    d.j["meshes"][0]["primitives"][0]["attributes"].erase("WEIGHTS_1");
    EXPECT_NE(refusal(d).find("attributes: 2 JOINTS_n sets but 1 WEIGHTS_n sets"), std::string::npos) << refusal(d);
  }
  {
    Doc d = skinnedQuad();
    d.j["skins"][0]["joints"] = {1};  // the quad's vertices use joint 1 too
    d.j["accessors"][d.j["skins"][0]["inverseBindMatrices"].get<int>()]["count"] = 1;
    EXPECT_NE(refusal(d).find("uses joint 1 of skin"), std::string::npos) << refusal(d);
  }
  {
    Doc d = skinnedQuad();
    d.j["meshes"][0]["weights"] = {0.5, 0.5};
    EXPECT_NE(refusal(d).find("2 weights for 1 morph targets"), std::string::npos) << refusal(d);
  }
  {
    Doc d = skinnedQuad();
    d.node(0)["weights"] = {0.1, 0.2};
    EXPECT_NE(refusal(d).find("nodes[0].weights: 2 weights for 1 morph targets"), std::string::npos) << refusal(d);
  }
}
