#version 460
// SVGF à-trous iteration 1 while moving: its output also becomes the colour history.
#define SVGF_WRITE_HISTORY 1
#include "lib/svgf_atrous.glsl"
