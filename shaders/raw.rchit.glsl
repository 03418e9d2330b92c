#version 460
#extension GL_EXT_ray_tracing : require

// The trivial closest hit of raw_primary.rgen: no surface fetch, no material.
layout(location = 0) rayPayloadInEXT uint hit;

void main() { hit = 2u; }
