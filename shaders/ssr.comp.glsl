#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/textures.glsl"
#include "lib/environment.glsl"
#include "lib/brdf.glsl"

// Raster mode's specular light (what the specular pass traces in the hybrid frame), in the same
// units the lighting pass expects: opaque surfaces get the reflected radiance (demodulated, the
// lighting pass multiplies it by the lobe's albedo); glass gets reflection and refraction combined.
// Reflections march the depth buffer along the mirror direction (linear steps growing with
// distance, then a binary refinement) and read the lit image of a first lighting pass; rays that
// leave the screen or pass behind everything see the environment (blurred with roughness).
// Refraction is approximate: the lit image at a screen-space offset along the refracted direction,
// stepping on while that pixel is glass itself, else the environment.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D depthTex;
layout(set = 0, binding = 2) uniform sampler2D normalTex;
layout(set = 0, binding = 3) uniform sampler2D albedoTex;
layout(set = 0, binding = 4) uniform sampler2D materialTex;
layout(set = 0, binding = 5) uniform sampler2D emissiveTex;  // .a: the exact ior
layout(set = 0, binding = 6) uniform sampler2D litTex;
layout(set = 0, binding = 7, rgba16f) uniform writeonly image2D outSpecular;
layout(set = 0, binding = 8) uniform sampler2D specularGbufTex;  // encodeSpecular(): F0 tint, strength

const int kSteps = 48;             // march samples along a reflected ray
const int kRefineSteps = 6;        // binary search between the last two samples
const float kReachFraction = 1.5;  // ray length as a fraction of the distance to the camera
const float kEdgeFade = 0.08;      // uv margin over which hits fade to the environment at screen edges
const float kMinPixels = 2.0;      // screen distance before a sample may hit
const float kRefractionDepth = 0.05;  // refracted lookup step, as a fraction of the camera distance
const int kRefractionSteps = 8;       // steps before the refracted lookup gives up for the environment

float viewW(vec3 p) { return (frame.clipFromWorld * vec4(p, 1.0)).w; }

// Screen uv of the first depth-buffer surface along the ray, or (-1, -1). Surfaces within a pixel or
// two of the start, or facing away from the ray (the start's own plane seen at a grazing angle
// through the depth buffer's quantisation), are not hits.
vec2 marchScreen(vec3 origin, vec3 dir, float reach, float jitter) {
  float tPrev = 0.0;
  vec4 c0 = frame.clipFromWorld * vec4(origin, 1.0);
  vec2 uv0 = c0.xy / c0.w * 0.5 + 0.5;
  for (int i = 1; i <= kSteps; ++i) {
    float f = (float(i) - jitter) / float(kSteps);
    float t = reach * f * f;
    vec3 q = origin + dir * t;
    vec4 c = frame.clipFromWorld * vec4(q, 1.0);
    if (c.w <= 0.0) break;
    vec2 uv = c.xy / c.w * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) break;
    float d = textureLod(depthTex, uv, 0.0).r;
    if (isBackground(d)) {
      tPrev = t;
      continue;
    }
    float sceneW = viewW(worldFromDepth(frame.worldFromClip, uv, d));
    float thickness = max(2.0 * (t - tPrev), 0.02 * c.w);
    bool nearStart = length((uv - uv0) * vec2(frame.size)) < kMinPixels;
    bool facing = dot(octDecode(textureLod(normalTex, uv, 0.0).xy), dir) < 0.0;
    if (!nearStart && facing && c.w > sceneW && c.w - sceneW < thickness) {
      float lo = tPrev, hi = t;
      for (int k = 0; k < kRefineSteps; ++k) {
        float mid = 0.5 * (lo + hi);
        vec4 cm = frame.clipFromWorld * vec4(origin + dir * mid, 1.0);
        vec2 um = cm.xy / cm.w * 0.5 + 0.5;
        float dm = textureLod(depthTex, um, 0.0).r;
        if (!isBackground(dm) && cm.w > viewW(worldFromDepth(frame.worldFromClip, um, dm))) hi = mid;
        else lo = mid;
      }
      vec4 ch = frame.clipFromWorld * vec4(origin + dir * hi, 1.0);
      return ch.xy / ch.w * 0.5 + 0.5;
    }
    tPrev = t;
  }
  return vec2(-1.0);
}

vec3 reflected(vec3 p, vec3 ng, vec3 r, float roughness, float reach, float jitter) {
  vec3 env = environmentSpecular(r, roughness);
  vec2 hit = marchScreen(p + ng * 1e-3 * reach, r, reach, jitter);
  if (hit.x < 0.0) return env;
  vec2 edge = min(hit, 1.0 - hit);
  float fade = smoothstep(0.0, kEdgeFade, min(edge.x, edge.y));
  return mix(env, textureLod(litTex, hit, 0.0).rgb, fade);
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), frame.size))) return;
  float depth = texelFetch(depthTex, px, 0).r;
  vec4 mat = texelFetch(materialTex, px, 0);
  float roughness = mat.r, transmission = mat.b;
  bool specular = transmission > 0.0 || roughness <= frame.glossyThreshold + 0.1;
  if (isBackground(depth) || !specular) {
    imageStore(outSpecular, px, vec4(0.0));
    return;
  }
  vec2 uv = (vec2(px) + 0.5) / vec2(frame.size);
  vec3 p = worldFromDepth(frame.worldFromClip, uv, depth);
  vec4 nn = texelFetch(normalTex, px, 0);
  vec3 n = octDecode(nn.xy), ng = octDecode(nn.zw);
  vec3 v = normalize(frame.cameraPosition.xyz - p);
  float camDist = distance(frame.cameraPosition.xyz, p);
  float reach = kReachFraction * camDist;
  float jitter = fract(52.9829189 * fract(dot(vec2(px), vec2(0.06711056, 0.00583715)) + 0.618 * float(frame.frameIndex)));
  vec3 r = reflect(-v, n);
  vec3 refl = reflected(p, ng, r, roughness, reach, jitter);
  if (transmission <= 0.0) {
    imageStore(outSpecular, px, vec4(refl, 1.0));
    return;
  }
  // Glass: Schlick's Fresnel at the exact ior (tinted and scaled by KHR_materials_specular), the
  // rest refracted and tinted by the base colour.
  float ior = max(texelFetch(emissiveTex, px, 0).a, 1.0);
  float f0 = pow((ior - 1.0) / (ior + 1.0), 2.0);
  float nv = max(dot(n, v), 0.0);
  float schlick = f0 + (1.0 - f0) * pow(1.0 - nv, 5.0);
  vec3 t = refract(-v, n, 1.0 / ior);
  vec3 refr;
  vec3 fresnel;
  if (dot(t, t) == 0.0) {
    fresnel = vec3(1.0);  // total internal reflection
    refr = vec3(0.0);
  } else {
    fresnel = specularGlassFresnel(schlick, ior, decodeSpecular(texelFetch(specularGbufTex, px, 0)));
    // Step further along the refracted direction until the offset leaves the glass.
    refr = environmentRadiance(t);
    for (int k = 1; k <= kRefractionSteps; ++k) {
      vec4 c = frame.clipFromWorld * vec4(p + t * (kRefractionDepth * float(k) * camDist), 1.0);
      vec2 u = c.xy / c.w * 0.5 + 0.5;
      if (c.w <= 0.0 || any(lessThan(u, vec2(0.0))) || any(greaterThan(u, vec2(1.0)))) break;
      float d = textureLod(depthTex, u, 0.0).r;
      if (isBackground(d)) break;
      if (textureLod(materialTex, u, 0.0).b > 0.0) continue;
      refr = textureLod(litTex, u, 0.0).rgb;
      break;
    }
  }
  vec3 tint = srgbToLinear(texelFetch(albedoTex, px, 0).rgb);
  float reflected = max(fresnel.r, max(fresnel.g, fresnel.b));  // refraction takes what max(F) leaves
  vec3 radiance = fresnel * refl + (1.0 - reflected) * transmission * tint * refr;
  imageStore(outSpecular, px, vec4(radiance, 1.0));
}
