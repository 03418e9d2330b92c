#version 460
#extension GL_EXT_ray_tracing : require

// The trivial miss of the raw-rate twins' bounce rays: the payload keeps the raygen's "missed" value.
layout(location = 0) rayPayloadInEXT uint hitT;

void main() {}
