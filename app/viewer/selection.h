#pragma once
// The viewer's selected instance: picking under the cursor, its transform as position / rotation /
// scale for the panel's drags, and moving it with the mouse while G is held.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace rayster::app {

// Translation, rotation (XYZ Euler angles, degrees) and scale: what the panel edits.
struct Trs {
  glm::vec3 position{0.0f}, rotationDeg{0.0f}, scale{1.0f};
};
Trs decompose(const glm::mat4& worldFromObject);
glm::mat4 compose(const Trs& trs);

// Picks the scene instance whose world bounds a ray through `pixel` (window pixels, top-left
// origin) enters first; -1: none. `transforms` are the current worldFromObject of each instance.
int32_t pickInstance(const scene::Scene& scene, const std::vector<glm::mat4>& transforms, const scene::Camera& camera,
                     glm::vec2 pixel, glm::vec2 windowSize);

// The world-space offset of dragging the cursor by `cursorDelta` pixels for a point at `point`:
// the point stays under the cursor, in the plane facing the camera.
glm::vec3 dragOffset(const scene::Camera& camera, glm::vec3 point, glm::vec2 cursorDelta, float windowHeight);

struct Selection {
  int32_t instance = -1;  // index into scene.instances
  Trs trs;                // as edited in the panel
  bool edited = false;    // the panel or a drag changed trs: the viewer sends it to the renderer
};

}  // namespace rayster::app
