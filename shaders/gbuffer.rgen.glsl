#version 460
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/ray_flags.glsl"
#include "lib/textures.glsl"
#include "lib/surface.glsl"
#include "lib/sphere.glsl"
#include "lib/primary_payload.glsl"
#include "lib/hit_surface.glsl"
#include "lib/motion.glsl"

// Traced primary rays (--primary rt): writes the same G-buffer as the raster pass. Depth goes to
// R32F (D32 is no storage format) as the same clip-space depth the rasteriser would produce.
layout(set = 0, binding = 1) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = 2, r32f) uniform writeonly image2D outDepth;
layout(set = 0, binding = 3, rgba16_snorm) uniform writeonly image2D outNormals;
layout(set = 0, binding = 4, rgba8) uniform writeonly image2D outAlbedo;
layout(set = 0, binding = 5, rgba8) uniform writeonly image2D outMaterial;
layout(set = 0, binding = 6, rgba16f) uniform writeonly image2D outEmissive;
layout(set = 0, binding = 7, r32ui) uniform writeonly uimage2D outId;
layout(set = 0, binding = 8, rg16f) uniform writeonly image2D outMotion;
layout(set = 0, binding = 9, rgba8) uniform writeonly image2D outSpecular;

layout(location = 0) rayPayloadEXT PrimaryPayload payload;

void main() {
  ivec2 px = ivec2(gl_LaunchIDEXT.xy);
  vec2 uv = (vec2(px) + 0.5) / vec2(gl_LaunchSizeEXT.xy);
  vec3 origin = frame.cameraPosition.xyz;
  vec3 dir = cameraRayDirection(frame.worldFromClip, uv, origin);

  payload.t = -1.0;
  uint flags = sceneRayFlags();
  traceRayEXT(tlas, flags, kMaskVisible | kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, 1e30, 0);

  if (payload.t < 0.0) {
    imageStore(outDepth, px, vec4(kBackgroundDepth));
    imageStore(outNormals, px, vec4(0.0));
    imageStore(outAlbedo, px, vec4(0.0));
    imageStore(outMaterial, px, vec4(0.0));
    imageStore(outEmissive, px, vec4(0.0));
    imageStore(outId, px, uvec4(kBackgroundId));
    imageStore(outMotion, px, vec4(0.0));
    imageStore(outSpecular, px, vec4(0.0));
    return;
  }

  SurfacePoint sp;
  MaterialRecord m;
  surfaceAtHit(payload, origin, dir, sp, m);
  GBufferValues gb = evaluateSurface(m, sp, origin);

  vec4 clip = frame.clipFromWorld * vec4(sp.position, 1.0);
  imageStore(outDepth, px, vec4(clip.z / clip.w));
  imageStore(outNormals, px, gb.normals);
  imageStore(outAlbedo, px, gb.albedo);
  imageStore(outMaterial, px, gb.material);
  imageStore(outEmissive, px, gb.emissive);
  imageStore(outSpecular, px, encodeSpecular(gb.specular));
  imageStore(outId, px, uvec4(payload.instance));
  InstanceRecord inst = Instances(frame.instances).i[payload.instance];
  imageStore(outMotion, px, vec4(motionFromWorld(sp.position, previousWorld(inst, sp.position)), 0.0, 0.0));
}
