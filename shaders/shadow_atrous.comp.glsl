#version 460
// variant: shadow_atrous_2.comp SHADOW_ATROUS_LAYERS=2u
// Shadow à-trous iteration (see lib/shadow_atrous.glsl) for up to kMaxShadowDenoiseLayers layers;
// its variant shadow_atrous_2.comp for at most two (one light and AO, the common case).
#ifndef SHADOW_ATROUS_LAYERS
#define SHADOW_ATROUS_LAYERS kMaxShadowDenoiseLayers
#endif
#include "lib/shadow_atrous.glsl"
