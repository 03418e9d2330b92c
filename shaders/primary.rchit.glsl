#version 460
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/primary_payload.glsl"

layout(location = 0) rayPayloadInEXT PrimaryPayload payload;
hitAttributeEXT vec2 bary;

void main() {
  InstanceRecord inst = Instances(frame.instances).i[gl_InstanceCustomIndexEXT];
  payload.t = gl_HitTEXT;
  payload.instance = gl_InstanceCustomIndexEXT;
  payload.geometry = inst.firstGeometry + gl_GeometryIndexEXT;
  payload.primitive = gl_PrimitiveID;
  payload.bary = bary;
}
