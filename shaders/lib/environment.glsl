// Light from infinity: black, the procedural sky, or an equirectangular HDR map rotated about +Y;
// and its diffuse irradiance from order-2 spherical harmonics (render/gpu_environment.cpp).
// Needs lib/frame.glsl and lib/textures.glsl.
#ifndef RAYSTER_ENVIRONMENT_GLSL
#define RAYSTER_ENVIRONMENT_GLSL

// Must match skyRadiance() in render/gpu_environment.cpp.
vec3 skyRadiance(vec3 d) {
  if (d.y >= 0.0) return mix(frame.skyHorizon, frame.skyZenith, sqrt(d.y));
  return mix(frame.skyHorizon, frame.skyGround, sqrt(min(-d.y * 4.0, 1.0)));
}

vec3 rotateY(vec3 d, float angle) {
  float c = cos(angle), s = sin(angle);
  return vec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
}

// Must match equirectDirection() in render/gpu_environment.cpp (its inverse).
vec2 equirectUv(vec3 d) {
  return vec2(atan(d.x, -d.z) / (2.0 * kPi) + 0.5, acos(clamp(d.y, -1.0, 1.0)) / kPi);
}

vec3 environmentRadiance(vec3 dir) {
  vec3 d = rotateY(normalize(dir), -frame.environment.w);
  if (frame.environmentKind == kEnvironmentMap)
    return frame.environment.rgb * textureLod(textures[nonuniformEXT(frame.environmentSlot)], equirectUv(d), 0.0).rgb;
  if (frame.environmentKind == kEnvironmentSky) return frame.environment.rgb * skyRadiance(d);
  return vec3(0.0);
}

// Specular environment light along `dir` for GGX roughness `roughness`, from the prefiltered
// levels (render/gpu_environment.cpp); roughness 0 is the environment itself. Without prefiltered
// levels: the environment blurred towards its irradiance.
vec3 prefilteredLevel(vec2 uv, float level) {
  const float h = float(kPrefilteredWidth / 2u);
  float v = clamp(uv.y, 0.5 / h, 1.0 - 0.5 / h);
  vec2 at = vec2(uv.x, (level - 1.0 + v) / float(kPrefilteredLevels));
  return frame.environment.rgb * textureLod(textures[nonuniformEXT(frame.prefilteredSlot)], at, 0.0).rgb;
}

vec3 environmentIrradiance(vec3 normal);

vec3 environmentSpecular(vec3 dir, float roughness) {
  if (frame.prefilteredSlot == 0xFFFFFFFFu)
    return mix(environmentRadiance(dir), environmentIrradiance(dir) / kPi, roughness);
  vec2 uv = equirectUv(rotateY(normalize(dir), -frame.environment.w));
  float lod = clamp(roughness, 0.0, 1.0) * float(kPrefilteredLevels);
  float lo = floor(lod);
  vec3 a = lo < 1.0 ? environmentRadiance(dir) : prefilteredLevel(uv, lo);
  vec3 b = lo >= float(kPrefilteredLevels) ? a : prefilteredLevel(uv, lo + 1.0);
  return mix(a, b, lod - lo);
}

// Irradiance E(n) (W/m²-like) at a surface with normal n; Lambert radiance is albedo/π · E.
vec3 environmentIrradiance(vec3 normal) {
  vec3 n = rotateY(normal, -frame.environment.w);
  const float c[9] = float[9](0.282095, 0.488603, 0.488603, 0.488603, 1.092548, 1.092548, 0.315392, 1.092548, 0.546274);
  float basis[9] = float[9](c[0], c[1] * n.y, c[2] * n.z, c[3] * n.x, c[4] * n.x * n.y, c[5] * n.y * n.z,
                            c[6] * (3.0 * n.z * n.z - 1.0), c[7] * n.x * n.z, c[8] * (n.x * n.x - n.y * n.y));
  vec3 e = vec3(0.0);
  for (int k = 0; k < 9; ++k) e += frame.irradianceSh[k].rgb * basis[k];
  return max(e, vec3(0.0));
}

#endif
