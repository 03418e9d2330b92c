#pragma once
// Procedural primitives for built-in scenes and tests. All are right-handed with
// counter-clockwise winding seen from outside and outward normals; flat shapes give every face
// its own vertices so normals stay flat (no smoothing across a box edge).
#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace rayster::scene {

// Centred at the origin; rings >= 2 (latitude bands), segments >= 3 (longitude).
Primitive makeUvSphere(float radius, int rings, int segments, uint32_t material);

// Quad a-b-c-d, counter-clockwise seen from the side its normal faces. Slightly non-planar
// corners (measured data) are fine: the normal is taken from the diagonals.
Primitive makeQuad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, uint32_t material);
void appendQuad(Primitive& prim, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d);

// Axis-aligned box, 6 flat faces.
Primitive makeBox(glm::vec3 min, glm::vec3 max, uint32_t material);

// A vertical prism over a convex quad footprint given in the xz plane (x, z), from y0 to y1:
// top, 4 sides and, if capBottom, the bottom. Face orientation is derived from the prism's centre,
// so the footprint may be listed in either winding order.
Primitive makePrism(const std::array<glm::vec2, 4>& footprintXz, float y0, float y1, bool capBottom, uint32_t material);

// Triangles makeUvSphere produces (the pole bands are fans, not quads).
inline size_t uvSphereTriangleCount(int rings, int segments) {
  return static_cast<size_t>(rings) * segments * 2 - 2 * static_cast<size_t>(segments);
}

}  // namespace rayster::scene
