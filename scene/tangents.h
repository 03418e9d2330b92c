#pragma once
#include "scene/scene.h"

namespace rayster::scene {

// Per-vertex tangents from UV set 0 (area-weighted per-triangle frames, Gram-Schmidt against the
// normal, handedness in w). Without UVs, an arbitrary frame around the normal (w = 1).
void generateTangents(Primitive& prim);

}  // namespace rayster::scene
