// The specular path's scattering events and its first ray from a G-buffer pixel (docs/techniques.md §12,
// §13), shared by specular.rgen and its raw-rate twin raw_specular.rgen so both trace the same first
// rays. The includer declares depthTex, normalTex, albedoTex, materialTex, emissiveTex and
// specularGbufTex (the G-buffer's KHR_materials_specular target). Needs
// lib/brdf.glsl, lib/dfg.glsl, lib/light_ray.glsl, lib/specular_weight.glsl and shared/vndf.h.
#ifndef RAYSTER_SPECULAR_PATH_GLSL
#define RAYSTER_SPECULAR_PATH_GLSL

#include "lib/specular_scatter.glsl"

// The reflection off an opaque G-buffer surface, demodulated (docs/techniques.md §13): no Fresnel (lighting
// applies F0·A + B). At most mirrorRoughness rough: the mirror direction, weight 1; rougher: one GGX
// VNDF sample (Heitz 2018) weighted G2/G1 / (A + B), whose mean is 1. False when the sample leaves
// below the surface (weight 0).
bool firstReflection(inout vec3 dir, out vec3 origin, out vec3 beta, vec3 p, vec3 n, vec3 ng, float roughness,
                     uvec2 px) {
  vec3 next;
  beta = vec3(1.0);
  if (roughness <= frame.mirrorRoughness) {
    next = reflect(dir, n);
  } else {
    // Its own stream: the rest of the path draws the same numbers as the mirror path would.
    uint lobeRng = rngInit(px, frame.frameIndex, frame.seed ^ kGlossyStream);
    vec3 t, b;
    orthonormalBasis(n, t, b);
    vec3 v = -dir;
    vec3 vt = normalize(vec3(dot(v, t), dot(v, b), max(dot(v, n), 1e-4)));  // tangent frame, N = +z
    float alpha = roughness * roughness;
    vec3 h = sampleGgxVndf(vt, alpha, vec2(rnd(lobeRng), rnd(lobeRng)));
    vec3 lt = reflect(-vt, h);
    if (lt.z <= 0.0) return false;
    vec2 ab = dfgTerms(max(dot(n, v), 1e-4), roughness);
    beta = vec3(smithG2OverG1(vt.z, lt.z, alpha) / max(ab.x + ab.y, 1e-4));
    next = t * lt.x + b * lt.y + n * lt.z;
  }
  origin = p + (dot(next, ng) > 0.0 ? ng : -ng) * hitRayOffset(p);
  dir = normalize(next);
  return true;
}

// A glossy pixel of the half-rate checkerboard that is not traced this frame: off its turn, with a
// 4-neighbour on the same kind of surface whose turn it is (the fill pass reads that one).
bool halfRateSkips(ivec2 px, float depth, vec4 mat) {
  if (halfRateTurn(px) || !halfRateGlossy(depth, mat)) return false;
  ivec2 size = textureSize(depthTex, 0);
  const ivec2 kNeighbours[4] = ivec2[](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
  for (int k = 0; k < 4; ++k) {
    ivec2 q = px + kNeighbours[k];
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
    if (halfRateGlossy(texelFetch(depthTex, q, 0).r, texelFetch(materialTex, q, 0))) return true;
  }
  return false;
}

// The first ray of pixel px's specular path. False when none is traced; `result` is then what the
// pass writes: 0 on pixels the pass does not trace, (0, 0, 0, 1) when a glossy sample leaves below the
// surface, (0, 0, 0, kHalfRateSkipped) off the pixel's half-rate turn. Else the ray (origin, dir),
// its throughput, `glossy` (a VNDF sample of a rough lobe rather than a mirror or glass event) and
// the path's random stream.
bool specularFirstRay(ivec2 px, out vec3 origin, out vec3 dir, out vec3 beta, out bool glossy, out vec4 result,
                      out uint rng) {
  origin = vec3(0.0);
  dir = vec3(0.0, 1.0, 0.0);
  beta = vec3(0.0);
  glossy = false;
  result = vec4(0.0);
  rng = 0u;
  float depth = texelFetch(depthTex, px, 0).r;
  vec4 mat = texelFetch(materialTex, px, 0);
  if (isBackground(depth) || tracedSpecularWeight(mat.r, mat.b) <= 0.0) return false;
  if (halfRateSkips(px, depth, mat)) {
    result = vec4(0.0, 0.0, 0.0, kHalfRateSkipped);
    return false;
  }
  vec2 uv = (vec2(px) + 0.5) / vec2(gl_LaunchSizeEXT.xy);
  vec3 p = worldFromDepth(frame.worldFromClip, uv, depth);
  vec4 nn = texelFetch(normalTex, px, 0);
  vec3 n = octDecode(nn.xy), ng = octDecode(nn.zw);
  vec3 baseColor = srgbToLinear(texelFetch(albedoTex, px, 0).rgb);
  float ior;
  bool thin;
  unpackIor(mat.a, ior, thin);
  // Entering with the 7-bit ior and leaving with the exact one would make a slab a prism.
  ior = texelFetch(emissiveTex, px, 0).a;
  vec4 specular = decodeSpecular(texelFetch(specularGbufTex, px, 0));
  rng = rngInit(uvec2(px), frame.frameIndex, frame.seed ^ kSpecularStream);

  dir = normalize(p - frame.cameraPosition.xyz);
  beta = vec3(1.0);
  // The G-buffer surface: P comes from quantised depth, so step off by its reconstruction error.
  float nextDepth = uintBitsToFloat(floatBitsToUint(depth) + 1u);
  float depthError = distance(p, worldFromDepth(frame.worldFromClip, uv, nextDepth));
  if (mat.b > 0.0) {
    scatter(dir, origin, beta, p, n, ng, true, baseColor, mat.g, mat.b, ior, thin, specular, rng);
  } else if (!firstReflection(dir, origin, beta, p, n, ng, mat.r, uvec2(px))) {
    result = vec4(0.0, 0.0, 0.0, 1.0);  // the sample left below the surface
    return false;
  } else {
    glossy = mat.r > frame.mirrorRoughness;
  }
  origin += (origin - p) / max(length(origin - p), 1e-12) * 4.0 * depthError;
  return true;
}

#endif
