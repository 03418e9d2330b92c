#ifndef RAYSTER_PRIMARY_PAYLOAD_GLSL
#define RAYSTER_PRIMARY_PAYLOAD_GLSL
// Small radiance payload (docs/techniques.md §4): the closest hit only records what it hit; raygen
// fetches vertices and shades.
struct PrimaryPayload {
  float t;  // < 0: miss
  uint instance;
  uint geometry;  // global geometry row
  uint primitive;
  vec2 bary;
};
#endif
