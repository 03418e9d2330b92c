#version 460
// Shadow à-trous iteration for up to kMaxShadowDenoiseLayers layers (see lib/shadow_atrous.glsl).
#define SHADOW_ATROUS_LAYERS kMaxShadowDenoiseLayers
#include "lib/shadow_atrous.glsl"
