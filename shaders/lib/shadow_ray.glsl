#ifndef RAYSTER_SHADOW_RAY_GLSL
#define RAYSTER_SHADOW_RAY_GLSL
// The shadow ray of pixel `px` towards light `layer` (docs/techniques.md §9), shared by shadows.rgen and
// its raw-rate twin raw_shadows.rgen so both trace exactly the same rays. The includer declares
// depthTex and normalTex. Returns false when no ray is traced (background, light behind the surface).
bool shadowRay(ivec2 px, uint layer, out vec3 origin, out vec3 dir, out float tMax) {
  origin = vec3(0.0);
  dir = vec3(0.0, 1.0, 0.0);
  tMax = 0.0;
  float depth = texelFetch(depthTex, px, 0).r;
  if (isBackground(depth)) return false;
  vec2 uv = (vec2(px) + 0.5) / vec2(gl_LaunchSizeEXT.xy);
  vec3 p = worldFromDepth(frame.worldFromClip, uv, depth);
  vec4 n = texelFetch(normalTex, px, 0);
  vec3 ng = octDecode(n.zw);
  LightRecord light = loadLight(layer);

  uint rng = rngInit(uvec2(px), frame.frameIndex, frame.seed ^ kShadowStream ^ pcg(layer));
  vec2 u = vec2(rnd(rng), rnd(rng));
  float dist;
  dir = sampleLightDirection(light, p, u, dist);
  if (dot(dir, ng) <= 0.0) return false;
  // Offset along the geometric normal, by more than the error of P reconstructed from depth.
  float eps = gbufferRayOffset(frame.worldFromClip, uv, depth, p);
  origin = p + ng * eps;
  tMax = max(dist - eps, 0.0);
  return true;
}

#endif
