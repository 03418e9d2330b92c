#version 460
// Shadow à-trous iteration for at most two layers (see lib/shadow_atrous.glsl).
#define SHADOW_ATROUS_LAYERS 2u
#include "lib/shadow_atrous.glsl"
