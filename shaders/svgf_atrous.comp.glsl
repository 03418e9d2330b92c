#version 460
// variant: svgf_atrous_history.comp SVGF_WRITE_HISTORY=1
// SVGF à-trous iteration (see lib/svgf_atrous.glsl); its variant svgf_atrous_history.comp, iteration 1
// while moving, also writes its output as the colour history.
#include "lib/svgf_atrous.glsl"
