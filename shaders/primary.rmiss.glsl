#version 460
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/primary_payload.glsl"

layout(location = 0) rayPayloadInEXT PrimaryPayload payload;

void main() { payload.t = -1.0; }
