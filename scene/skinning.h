#pragma once
// Skinning and morph targets on the CPU: which instances deform, the joint matrices of a pose, the
// morph weights in effect, and a reference deformation of a primitive. The renderer deforms on the
// GPU (render/deform.h) from the same joint matrices and weights; deformPrimitive() is what its
// output is checked against (tests) and what bakePose() freezes into a static scene.
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace rayster::scene {

// Whether an instance's vertices move with its skin or its morph weights (a mesh with morph targets
// deforms even under constant weights: the targets are applied to its rest shape).
bool deforms(const Scene& scene, const Instance& instance);
bool anyDeforms(const Scene& scene);

// worldFromNode[joint] × inverseBind[joint] for each joint of `skin`, from the nodes' current world
// matrices (updateWorldTransforms).
std::vector<glm::mat4> jointMatrices(const Scene& scene, const Skin& skin);

// The morph weights in effect: the instance's, else the mesh's defaults; padded with zeros (or
// cut) to `targets` entries.
std::vector<float> morphWeights(const Scene& scene, const Instance& instance, size_t targets);

// The primitive as posed now: morph targets added, then skinned (to world space, where the
// instance is skinned). Normals and tangents are renormalised; tangents keep their w.
Primitive deformPrimitive(const Scene& scene, const Instance& instance, const Primitive& primitive);

// Freezes the current pose: every deforming instance gets a mesh of its own with its deformed
// primitives (and no skin or targets); animations, skins and node links are dropped, so the result
// is a static scene that draws what `scene` draws now.
Scene bakePose(const Scene& scene);

}  // namespace rayster::scene
