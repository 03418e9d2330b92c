#version 460
#extension GL_EXT_ray_tracing : require

// The trivial closest hit of the raw-rate twins that replay a bounce (raw_indirect.rgen,
// raw_specular.rgen): only the hit distance, as float bits; no surface fetch, no material.
layout(location = 0) rayPayloadInEXT uint hitT;

void main() { hitT = floatBitsToUint(gl_HitTEXT); }
