#version 460
// variant: raw_primary.rgen RAW_RATE
// variant: gbuffer_flat.rgen NO_LAYERS
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/ray_flags.glsl"
#ifndef RAW_RATE
#include "lib/textures.glsl"
#include "lib/surface.glsl"
#include "lib/sphere.glsl"
#include "lib/primary_payload.glsl"
#include "lib/hit_surface.glsl"
#include "lib/motion.glsl"
#include "lib/ray_cone.glsl"
#endif

// Traced primary rays (--primary rt): writes the same G-buffer as the raster pass. Depth goes to
// R32F (D32 is no storage format) as the same clip-space depth the rasteriser would produce.
// RAW_RATE (raw_primary.rgen, the raw ray rate of gbuffer-traced, rayster bench --raw-rays): the
// same primary rays, with a closest-hit shader that only marks the hit (raw.rchit: 2) and a trivial
// miss (shadow.rmiss: 1), and one 16-bit write per pixel instead of the G-buffer's seven.
// NO_LAYERS (gbuffer_flat.rgen): for scenes without a clear coat or sheen, no layers target.
layout(set = 0, binding = 1) uniform accelerationStructureEXT tlas;
#ifdef RAW_RATE
layout(set = 0, binding = 2, r16f) uniform writeonly image2D outHit;

layout(location = 0) rayPayloadEXT uint hit;
#else
layout(set = 0, binding = 2, r32f) uniform writeonly image2D outDepth;
layout(set = 0, binding = 3, rgba16_snorm) uniform writeonly image2D outNormals;
layout(set = 0, binding = 4, rgba8) uniform writeonly image2D outAlbedo;
layout(set = 0, binding = 5, rgba8) uniform writeonly image2D outMaterial;
layout(set = 0, binding = 6, rgba16f) uniform writeonly image2D outEmissive;
layout(set = 0, binding = 7, r32ui) uniform writeonly uimage2D outId;
layout(set = 0, binding = 8, rg16f) uniform writeonly image2D outMotion;
layout(set = 0, binding = 9, rgba8) uniform writeonly image2D outSpecular;
#ifndef NO_LAYERS
layout(set = 0, binding = 10, rgba32ui) uniform writeonly uimage2D outLayers;
#endif

layout(location = 0) rayPayloadEXT PrimaryPayload payload;
#endif

// The camera ray through pixel px's centre, traced into the payload.
void tracePrimaryRay(ivec2 px, out vec3 origin, out vec3 dir) {
  vec2 uv = (vec2(px) + 0.5) / vec2(gl_LaunchSizeEXT.xy);
  origin = frame.cameraPosition.xyz;
  dir = cameraRayDirection(frame.worldFromClip, uv, origin);
  uint flags = sceneRayFlags();
  traceRayEXT(tlas, flags, kMaskVisible | kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, 1e30, 0);
}

#ifdef RAW_RATE

void main() {
  ivec2 px = ivec2(gl_LaunchIDEXT.xy);
  vec3 origin, dir;
  hit = 0u;
  tracePrimaryRay(px, origin, dir);
  imageStore(outHit, px, vec4(float(hit)));
}

#else

void main() {
  ivec2 px = ivec2(gl_LaunchIDEXT.xy);
  vec3 origin, dir;
  payload.t = -1.0;
  tracePrimaryRay(px, origin, dir);

  if (payload.t < 0.0) {
    imageStore(outDepth, px, vec4(kBackgroundDepth));
    imageStore(outNormals, px, vec4(0.0));
    imageStore(outAlbedo, px, vec4(0.0));
    imageStore(outMaterial, px, vec4(0.0));
    imageStore(outEmissive, px, vec4(0.0));
    imageStore(outId, px, uvec4(kBackgroundId));
    imageStore(outMotion, px, vec4(0.0));
    imageStore(outSpecular, px, vec4(0.0));
#ifndef NO_LAYERS
    imageStore(outLayers, px, uvec4(0u));
#endif
    return;
  }

  SurfacePoint sp;
  MaterialRecord m;
  surfaceAtHit(payload, origin, dir, sp, m);
  setRayCone(pixelSpreadAngle() * payload.t, sp.geometricNormal, dir);  // the mip the rasteriser picks
  GBufferValues gb = evaluateSurface(m, sp, origin);

  vec4 clip = frame.clipFromWorld * vec4(sp.position, 1.0);
  imageStore(outDepth, px, vec4(clip.z / clip.w));
  imageStore(outNormals, px, gb.normals);
  imageStore(outAlbedo, px, gb.albedo);
  imageStore(outMaterial, px, gb.material);
  imageStore(outEmissive, px, gb.emissive);
  imageStore(outSpecular, px, encodeSpecular(gb.specular));
#ifndef NO_LAYERS
  imageStore(outLayers, px, encodeLayers(gb.coat, gb.sheen));
#endif
  imageStore(outId, px, uvec4(payload.instance));
  InstanceRecord inst = Instances(frame.instances).i[payload.instance];
  GeometryRecord g = Geometries(frame.geometries).g[payload.geometry];
  vec3 prevWorld = previousWorldOnTriangle(inst, g, payload.primitive, payload.bary, sp.position);
  imageStore(outMotion, px, vec4(motionFromWorld(sp.position, prevWorld), 0.0, 0.0));
}

#endif
