#version 460
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/textures.glsl"
#include "lib/surface.glsl"
#include "lib/sphere.glsl"
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
  vec3 dir = normalize(worldFromDepth(frame.worldFromClip, uv, 1.0) - origin);

  payload.t = -1.0;
  uint flags = (frame.sceneFlags & kSceneAlphaTested) != 0u ? gl_RayFlagsNoneEXT : gl_RayFlagsOpaqueEXT;
  traceRayEXT(tlas, flags, kMaskVisible | kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, 1e30, 0);

  if (payload.t < 0.0) {
    imageStore(outDepth, px, vec4(kBackgroundDepth));
    imageStore(outNormals, px, vec4(0.0));
    imageStore(outAlbedo, px, vec4(0.0));
    imageStore(outMaterial, px, vec4(0.0));
    imageStore(outEmissive, px, vec4(0.0));
    imageStore(outId, px, uvec4(kBackgroundId));
    return;
  }

  InstanceRecord inst = Instances(frame.instances).i[payload.instance];
  GeometryRecord g = Geometries(frame.geometries).g[payload.geometry];
  SurfacePoint sp;
  MaterialRecord m;
  if (g.kind == kGeometrySpheres) {
    SphereRecord s = Spheres(g.vertexAddress).s[payload.primitive];
    m = Materials(frame.materials).m[s.material];
    sp.position = origin + payload.t * dir;
    vec3 objPos = (inverse(inst.worldFromObject) * vec4(sp.position, 1.0)).xyz;
    vec3 objNormal;
    vec2 tex;
    vec4 tangent;
    sphereAttributes(s.center, objPos, objNormal, tex, tangent);
    sp.normal = (inst.normalFromObject * vec4(objNormal, 0.0)).xyz;
    sp.geometricNormal = sp.normal;
    sp.tangent = vec4((inst.worldFromObject * vec4(tangent.xyz, 0.0)).xyz, tangent.w);
    sp.uv0 = tex;
    sp.uv1 = tex;
  } else {
    m = Materials(frame.materials).m[g.material];
    Indices idx = Indices(g.indexAddress);
    Vertices vtx = Vertices(g.vertexAddress);
    uint base = payload.primitive * 3u;
    Vertex v0 = vtx.v[idx.i[base]], v1 = vtx.v[idx.i[base + 1u]], v2 = vtx.v[idx.i[base + 2u]];
    vec3 w = vec3(1.0 - payload.bary.x - payload.bary.y, payload.bary.x, payload.bary.y);
    vec3 p0, p1, p2;
    trianglePositions(g, inst, payload.primitive, p0, p1, p2);
    // Interpolating the triangle's world positions is more precise than origin + t·dir.
    sp.position = p0 * w.x + p1 * w.y + p2 * w.z;
    sp.normal = (inst.normalFromObject * vec4(v0.normal * w.x + v1.normal * w.y + v2.normal * w.z, 0.0)).xyz;
    vec4 t = v0.tangent * w.x + v1.tangent * w.y + v2.tangent * w.z;
    sp.tangent = vec4((inst.worldFromObject * vec4(t.xyz, 0.0)).xyz, v0.tangent.w);
    sp.geometricNormal = cross(p1 - p0, p2 - p0);
    sp.uv0 = v0.uv0 * w.x + v1.uv0 * w.y + v2.uv0 * w.z;
    sp.uv1 = v0.uv1 * w.x + v1.uv1 * w.y + v2.uv1 * w.z;
  }
  GBufferValues gb = evaluateSurface(m, sp, origin);

  vec4 clip = frame.clipFromWorld * vec4(sp.position, 1.0);
  imageStore(outDepth, px, vec4(clip.z / clip.w));
  imageStore(outNormals, px, gb.normals);
  imageStore(outAlbedo, px, gb.albedo);
  imageStore(outMaterial, px, gb.material);
  imageStore(outEmissive, px, gb.emissive);
  imageStore(outId, px, uvec4(payload.instance));
}
