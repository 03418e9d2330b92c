#version 460
#extension GL_EXT_ray_tracing : require

// Shadow rays skip closest-hit shaders: reaching the miss shader is what "visible" means.
layout(location = 0) rayPayloadInEXT uint visible;

void main() { visible = 1u; }
