#version 460
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/surface.glsl"
#include "lib/primary_payload.glsl"

// Traced primary rays (--primary rt): writes the same G-buffer as the raster pass. Depth goes to
// R32F (D32 is no storage format) as the same clip-space depth the rasteriser would produce.
layout(set = 0, binding = 1) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = 2, r32f) uniform writeonly image2D outDepth;
layout(set = 0, binding = 3, rgba16_snorm) uniform writeonly image2D outNormals;
layout(set = 0, binding = 4, rgba8) uniform writeonly image2D outAlbedo;
layout(set = 0, binding = 5, rgba8) uniform writeonly image2D outMaterial;
layout(set = 0, binding = 6, rgba16f) uniform writeonly image2D outEmissive;
layout(set = 0, binding = 7, r32ui) uniform writeonly uimage2D outId;

layout(location = 0) rayPayloadEXT PrimaryPayload payload;

void main() {
  ivec2 px = ivec2(gl_LaunchIDEXT.xy);
  vec2 uv = (vec2(px) + 0.5) / vec2(gl_LaunchSizeEXT.xy);
  vec3 origin = frame.cameraPosition.xyz;
  vec3 target = worldFromDepth(frame.worldFromClip, uv, 1.0);
  vec3 dir = normalize(target - origin);

  payload.t = -1.0;
  traceRayEXT(tlas, gl_RayFlagsOpaqueEXT, kMaskVisible | kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, 1e30, 0);

  if (payload.t < 0.0) {
    imageStore(outDepth, px, vec4(1.0));
    imageStore(outNormals, px, vec4(0.0));
    imageStore(outAlbedo, px, vec4(0.0));
    imageStore(outMaterial, px, vec4(0.0));
    imageStore(outEmissive, px, vec4(0.0));
    imageStore(outId, px, uvec4(kBackgroundId));
    return;
  }

  InstanceRecord inst = Instances(frame.instances).i[payload.instance];
  GeometryRecord g = Geometries(frame.geometries).g[payload.geometry];
  MaterialRecord m = Materials(frame.materials).m[g.material];
  Indices idx = Indices(g.indexAddress);
  Vertices vtx = Vertices(g.vertexAddress);
  uint base = payload.primitive * 3u;
  Vertex v0 = vtx.v[idx.i[base]], v1 = vtx.v[idx.i[base + 1u]], v2 = vtx.v[idx.i[base + 2u]];
  vec3 w = vec3(1.0 - payload.bary.x - payload.bary.y, payload.bary.x, payload.bary.y);
  vec3 objNormal = v0.normal * w.x + v1.normal * w.y + v2.normal * w.z;
  vec2 texUv = v0.uv * w.x + v1.uv * w.y + v2.uv * w.z;
  vec3 p0, p1, p2;
  trianglePositions(g, inst, payload.primitive, p0, p1, p2);
  // Interpolating the triangle's world positions is more precise than origin + t·dir.
  vec3 worldPos = p0 * w.x + p1 * w.y + p2 * w.z;
  vec3 normal = (inst.normalFromObject * vec4(objNormal, 0.0)).xyz;
  GBufferValues gb = evaluateSurface(m, worldPos, normal, cross(p1 - p0, p2 - p0), texUv, origin);

  vec4 clip = frame.clipFromWorld * vec4(worldPos, 1.0);
  imageStore(outDepth, px, vec4(clip.z / clip.w));
  imageStore(outNormals, px, gb.normals);
  imageStore(outAlbedo, px, gb.albedo);
  imageStore(outMaterial, px, gb.material);
  imageStore(outEmissive, px, gb.emissive);
  imageStore(outId, px, uvec4(payload.instance));
}
