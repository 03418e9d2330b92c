// render/deform.cpp's deformedBounds(): the culling box of a deforming primitive, from its pose
// alone (docs/techniques.md §5b). It must hold every vertex the deform pass writes — checked
// against scene::deformPrimitive (the CPU reference of that pass) on Debian's skinned and morphed
// samples at many times — and stay near the posed mesh's own box, or culling gains nothing.
#include <algorithm>
#include <filesystem>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "render/deform.h"
#include "scene/animation.h"
#include "scene/loader.h"
#include "scene/skinning.h"

namespace rayster::render {
namespace {

namespace fs = std::filesystem;
const fs::path kModels = "/usr/share/assimp/models/glTF2";

// The pose deformMeshes() hands the bounds: joint matrices from the posed nodes, morph weights
// resolved from the instance and the mesh.
DeformPose poseOf(const scene::Scene& scene, const scene::Instance& instance) {
  DeformPose pose;
  if (instance.skin >= 0) pose.joints = scene::jointMatrices(scene, scene.skins[size_t(instance.skin)]);
  const scene::Mesh& mesh = scene.meshes[instance.mesh];
  pose.weights = scene::morphWeights(scene, instance, mesh.primitives.front().targets.size());
  return pose;
}

void expectBoundsHoldThePose(const char* model) {
  const fs::path file = kModels / model;
  if (!fs::exists(file)) GTEST_SKIP() << "assimp-testmodels is not installed";
  auto loaded = scene::loadScene(file.string());
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  int checked = 0;
  for (float t = 0.0f; t <= 3.0f; t += 0.125f) {
    scene::Scene posed = *loaded;
    scene::evaluateAnimations(posed, t);
    for (const scene::Instance& inst : posed.instances) {
      if (!scene::deforms(posed, inst)) continue;
      const DeformPose pose = poseOf(posed, inst);
      for (const scene::Primitive& prim : posed.meshes[inst.mesh].primitives) {
        const auto [lo, hi] = deformedBounds(deformBounds(prim, inst.skin >= 0), pose);
        const scene::Primitive out = scene::deformPrimitive(posed, inst, prim);
        glm::vec3 meshLo(1e30f), meshHi(-1e30f);
        for (const glm::vec3& p : out.positions) {
          meshLo = glm::min(meshLo, p), meshHi = glm::max(meshHi, p);
          const float slack = 1e-4f * (1.0f + glm::length(p));
          ASSERT_TRUE(glm::all(glm::greaterThanEqual(p, lo - slack)) && glm::all(glm::lessThanEqual(p, hi + slack)))
              << model << " at t = " << t << ": a posed vertex lies outside its culling box";
        }
        // Not so loose that culling gains nothing: within the posed mesh's own size on each side.
        const float size = glm::length(meshHi - meshLo);
        EXPECT_LE(glm::length(hi - lo), 3.0f * size) << model << " at t = " << t << ": the box is far too loose";
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 20);
}

TEST(DeformBounds, HoldEverySkinnedVertexAtEveryTime) { expectBoundsHoldThePose("simple_skin/simple_skin.gltf"); }

TEST(DeformBounds, HoldEveryMorphedVertexAtEveryTime) {
  expectBoundsHoldThePose("glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf");
}

// One triangle skinned half to a joint that moves 10 m away: the box follows both joints, and a
// vertex without weight keeps the rest box in it.
TEST(DeformBounds, FollowEveryWeightedJointAndTheUnweighted) {
  scene::Primitive prim;
  prim.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  prim.indices = {0, 1, 2};
  scene::SkinInfluences set;
  set.joints = {{0, 1, 0, 0}, {0, 0, 0, 0}, {1, 0, 0, 0}};
  set.weights = {{0.5f, 0.5f, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}};
  prim.influences = {set};
  DeformPose pose{{glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0))}, {}};
  DeformBounds b = deformBounds(prim, true);
  EXPECT_EQ(b.joints, (std::vector<uint32_t>{0, 1}));
  EXPECT_FALSE(b.unweighted);
  auto [lo, hi] = deformedBounds(b, pose);
  EXPECT_FLOAT_EQ(lo.x, 0.0f);
  EXPECT_FLOAT_EQ(hi.x, 11.0f);
  EXPECT_FLOAT_EQ(hi.y, 1.0f);
  // Joint 1 only through a zero weight: not a joint of the box.
  prim.influences[0].weights[0] = {1, 0, 0, 0};
  prim.influences[0].weights[2] = {0, 0, 0, 0};  // and vertex 2 has no weight at all
  b = deformBounds(prim, true);
  EXPECT_EQ(b.joints, (std::vector<uint32_t>{0}));
  EXPECT_TRUE(b.unweighted);
  pose.joints[0] = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -5));
  std::tie(lo, hi) = deformedBounds(b, pose);
  EXPECT_FLOAT_EQ(lo.z, -5.0f) << "joint 0's image";
  EXPECT_FLOAT_EQ(hi.z, 0.0f) << "the unweighted vertex stays at rest";
  // A morph target grows the box along its deltas × weight, a negative weight the other way.
  scene::MorphTarget target;
  target.positions = {{0, 0, 0}, {0, 0, 0}, {0, 2, 0}};
  prim.targets = {target};
  b = deformBounds(prim, false);
  std::tie(lo, hi) = deformedBounds(b, DeformPose{{}, {-0.5f}});
  EXPECT_FLOAT_EQ(lo.y, -1.0f);
  EXPECT_FLOAT_EQ(hi.y, 1.0f);
  EXPECT_FLOAT_EQ(lo.x, 0.0f);
  EXPECT_FLOAT_EQ(hi.x, 1.0f) << "a delta along y leaves x alone";
  std::tie(lo, hi) = deformedBounds(b, DeformPose{{}, {1.0f}});
  EXPECT_FLOAT_EQ(hi.y, 3.0f);
}

}  // namespace
}  // namespace rayster::render
