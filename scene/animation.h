#pragma once
// Plays glTF 2.0 node animations on the CPU scene: samples every channel at a time, updates the
// nodes' local TRS, recomputes world matrices down the hierarchy and moves the instances that
// follow animated nodes. Timing (frame rate, --time) is the caller's business.
#include <vector>

#include "scene/scene.h"

namespace rayster::scene {

// Evaluates every animation of `scene` at `timeSeconds`. Before the first key a channel holds its
// first value, after the last key its last. With `loop`, time wraps modulo the longest animation
// duration first, so all animations restart together. Returns whether any instance or node world
// transform changed.
bool evaluateAnimations(Scene& scene, float timeSeconds, bool loop = false);

// One channel's value at `timeSeconds` (clamped to its keys): xyz for translation and scale,
// a unit quaternion as xyzw for rotation. Exposed for tests.
glm::vec4 sampleChannel(const AnimationChannel& channel, float timeSeconds);

// A weights channel's morph weights at `timeSeconds` (clamped to its keys), weightCount of them.
std::vector<float> sampleWeights(const AnimationChannel& channel, float timeSeconds);

// Shortest-path spherical interpolation between unit quaternions, t in [0, 1].
glm::quat slerpShortest(const glm::quat& a, const glm::quat& b, float t);

// World matrices of every node from the local transforms (parents come first in Scene::nodes);
// then what follows a node: worldFromObject and morph weights of every instance with node >= 0
// (a skinned one keeps the identity), and cameras and lights with node >= 0.
void updateWorldTransforms(Scene& scene);

}  // namespace rayster::scene
