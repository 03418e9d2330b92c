// render/deform.cpp's refitDrift(): the bound on how far a deforming mesh's vertices moved relative
// to one another since its BLAS was built, which decides refit or rebuild (docs/techniques.md §5b).
#include <cmath>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "render/deform.h"

namespace rayster::render {
namespace {

// A unit box skinned to three joints in their bind pose (joint matrices = identity).
DeformReach unitBox(size_t targets = 0) {
  DeformReach r;
  r.restMin = glm::vec3(-0.5f);
  r.restMax = glm::vec3(0.5f);
  r.targetReach.assign(targets, 0.25f);
  return r;
}
DeformPose bindPose() { return {{glm::mat4(1.0f), glm::mat4(1.0f), glm::mat4(1.0f)}, {}}; }

TEST(RefitDrift, RigidMotionOfTheWholeSkinIsNoDrift) {
  const DeformPose built = bindPose();
  DeformPose moved = built;
  const glm::mat4 walk = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(3, 0, 1)), 1.2f, glm::vec3(0, 1, 0));
  for (glm::mat4& m : moved.joints) m = walk * m;
  EXPECT_NEAR(refitDrift(unitBox(), built, moved), 0.0f, 1e-5f) << "walking without bending keeps the tree";
}

TEST(RefitDrift, BendingAJointDriftsWithTheBend) {
  const DeformPose built = bindPose();
  auto bent = [&](float degrees) {
    DeformPose p = built;
    p.joints[2] = glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::vec3(0, 0, 1));
    return refitDrift(unitBox(), built, p);
  };
  const float diagonal = std::sqrt(3.0f);
  // A rotation by θ about z moves the box's corners (√2/2 from the axis) by 2·sin(θ/2)·√2/2.
  EXPECT_NEAR(bent(1.0f), 2.0f * std::sin(glm::radians(0.5f)) * std::sqrt(0.5f), 1e-4f);
  EXPECT_LT(bent(1.0f), Deformers::kRefitDriftLimit * diagonal) << "a small bend refits";
  EXPECT_GT(bent(45.0f), Deformers::kRefitDriftLimit * diagonal) << "a limb swung by 45 degrees rebuilds";
  EXPECT_GT(bent(45.0f), bent(10.0f));
  // The same bend on top of a rigid motion of everything is the same drift.
  DeformPose walked = built;
  const glm::mat4 walk = glm::translate(glm::mat4(1.0f), glm::vec3(0, 2, 0));
  for (glm::mat4& m : walked.joints) m = walk * m;
  walked.joints[2] = walk * glm::rotate(glm::mat4(1.0f), glm::radians(10.0f), glm::vec3(0, 0, 1));
  EXPECT_NEAR(refitDrift(unitBox(), built, walked), bent(10.0f), 1e-4f);
}

TEST(RefitDrift, MorphDriftIsEachTargetsReachTimesItsWeightChange) {
  DeformPose built{{}, {0.0f, 0.5f}}, now{{}, {1.0f, 0.5f}};
  EXPECT_NEAR(refitDrift(unitBox(2), built, now), 0.25f, 1e-6f) << "target 0 went fully in: its reach";
  EXPECT_NEAR(refitDrift(unitBox(2), built, built), 0.0f, 1e-6f) << "no weight changed";
  now.weights = {0.5f, 0.0f};
  EXPECT_NEAR(refitDrift(unitBox(2), built, now), 0.25f * 0.5f + 0.25f * 0.5f, 1e-6f);
}

}  // namespace
}  // namespace rayster::render
