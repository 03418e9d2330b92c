#pragma once
// Composes scenes: a scene file places several models (each loaded as its own Scene) in one world.
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace rayster::scene {

// Moves src into dst with every mesh/material/texture/image/sampler/skin/node index re-based, and instances,
// lights, cameras and camera-path keys moved by `transform` (worldFromModel). src's node hierarchy
// hangs under a new fixed root node holding `transform`; its animations follow their nodes. Sphere-light radii
// scale with the transform's mean scale; directions are re-normalised. dst keeps its environment,
// ambient, camera path and name unless it has none, then src's are taken.
void appendScene(Scene& dst, Scene src, const glm::mat4& transform);

}  // namespace rayster::scene
