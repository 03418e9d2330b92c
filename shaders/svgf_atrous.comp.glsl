#version 460
// SVGF à-trous iteration (see lib/svgf_atrous.glsl).
#include "lib/svgf_atrous.glsl"
