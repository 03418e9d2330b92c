#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"

// Temporal anti-aliasing on linear HDR (docs/techniques.md §18): reproject the history with the motion
// of the closest texel in 3×3, sample it with Catmull–Rom, clip it to the current neighbourhood's
// variance box (γ = 1) then clamp it to its min/max, and blend with anti-firefly weights.
// Writes the next history, which is also the pass's output (ping-pong, no copy).
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D currentTex;  // this frame's HDR (nearest)
layout(set = 0, binding = 2) uniform sampler2D depthTex;    // G-buffer depth, reversed Z
layout(set = 0, binding = 3) uniform sampler2D historyTex;  // previous output (linear, clamp)
layout(set = 0, binding = 4) uniform sampler2D motionTex;   // uvCur − uvPrev; unused without kTaaMotion
layout(set = 0, binding = 5, rgba16f) uniform writeonly image2D outHistory;
layout(push_constant, scalar) uniform Push { TaaPush pc; };

const uint kTaaHistoryValid = 1u;  // off: first frame, cut, resize — output the current colour
const uint kTaaMotion = 2u;        // a motion image is bound; else camera motion from depth
const uint kTaaStill = 4u;         // nothing moved since the history began: a plain running mean

const float kGamma = 1.0;  // variance clip box μ ± γσ (Salvi)
const float kHalfSaturated = 65000.0;  // near the largest half float (65504)


ivec2 clampPixel(ivec2 p) { return clamp(p, ivec2(0), ivec2(pc.size) - 1); }

// Camera motion of a pixel from its depth: its world point, projected by this frame's and the
// previous frame's unjittered matrices. Depth was rendered with the jittered matrices, so the world
// point comes from worldFromClip at the pixel centre. A static camera gives exactly 0.
vec2 cameraMotion(ivec2 p, float depth) {
  vec2 uv = (vec2(p) + 0.5) / vec2(pc.size);
  vec4 world = frame.worldFromClip * vec4(uv * 2.0 - 1.0, depth, 1.0);
  vec4 cur = frame.unjitteredClipFromWorld * world;
  vec4 prev = frame.prevClipFromWorld * world;
  return (cur.xy / cur.w - prev.xy / prev.w) * 0.5;  // NDC → UV: ×0.5
}

// Catmull–Rom history fetch with 9 bilinear taps (the 4×4 kernel's middle two taps merged per axis).
vec3 sampleHistory(vec2 uv) {
  vec2 size = vec2(pc.size);
  vec2 pos = uv * size;
  vec2 t1 = floor(pos - 0.5) + 0.5;
  vec2 f = pos - t1;
  vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
  vec2 w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
  vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f));
  vec2 w3 = f * f * (-0.5 + 0.5 * f);
  vec2 w12 = w1 + w2;
  vec2 t0 = (t1 - 1.0) / size, t3 = (t1 + 2.0) / size, t12 = (t1 + w2 / w12) / size;
  vec3 c = vec3(0.0);
  c += textureLod(historyTex, vec2(t0.x, t0.y), 0.0).rgb * w0.x * w0.y;
  c += textureLod(historyTex, vec2(t12.x, t0.y), 0.0).rgb * w12.x * w0.y;
  c += textureLod(historyTex, vec2(t3.x, t0.y), 0.0).rgb * w3.x * w0.y;
  c += textureLod(historyTex, vec2(t0.x, t12.y), 0.0).rgb * w0.x * w12.y;
  c += textureLod(historyTex, vec2(t12.x, t12.y), 0.0).rgb * w12.x * w12.y;
  c += textureLod(historyTex, vec2(t3.x, t12.y), 0.0).rgb * w3.x * w12.y;
  c += textureLod(historyTex, vec2(t0.x, t3.y), 0.0).rgb * w0.x * w3.y;
  c += textureLod(historyTex, vec2(t12.x, t3.y), 0.0).rgb * w12.x * w3.y;
  c += textureLod(historyTex, vec2(t3.x, t3.y), 0.0).rgb * w3.x * w3.y;
  // The negative lobes can undershoot; the history was exposed with last frame's exposure.
  return max(c, vec3(0.0)) * frame.exposureRatio;
}

// Moves h towards the box centre until it lies inside centre ± extent.
vec3 clipToBox(vec3 h, vec3 centre, vec3 extent) {
  vec3 d = h - centre;
  vec3 units = abs(d) / max(extent, vec3(1e-5));
  float m = max(units.x, max(units.y, units.z));
  return m > 1.0 ? centre + d / m : h;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(pc.size)))) return;
  vec3 current = texelFetch(currentTex, p, 0).rgb;
  if ((pc.flags & kTaaHistoryValid) == 0u) {
    imageStore(outHistory, p, vec4(current, 1.0));
    return;
  }
  if ((pc.flags & kTaaStill) != 0u) {
    // A still view: the history is this pixel's mean so far, valid as it is. Clipping it to one
    // frame's neighbourhood and weighting by 1/(1 + L) would both pull it towards dark samples
    // (a bright light's anti-aliased edge, a noisy signal's rare bright samples).
    vec3 stored = texelFetch(historyTex, p, 0).rgb;
    // A history that saturated fp16 (an exposure still adapting to a very bright view) says nothing.
    float weight = max(stored.r, max(stored.g, stored.b)) >= kHalfSaturated ? 1.0 : pc.currentWeight;
    vec3 previous = max(stored, vec3(0.0)) * frame.exposureRatio;
    imageStore(outHistory, p, vec4(mix(previous, current, weight), 1.0));
    return;
  }

  // Neighbourhood moments and bounds, and the closest texel (reversed Z: largest depth).
  vec3 m1 = vec3(0.0), m2 = vec3(0.0), lo = current, hi = current;
  ivec2 closest = p;
  float closestDepth = -1.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      ivec2 q = clampPixel(p + ivec2(x, y));
      vec3 c = texelFetch(currentTex, q, 0).rgb;
      m1 += c;
      m2 += c * c;
      lo = min(lo, c);
      hi = max(hi, c);
      float d = texelFetch(depthTex, q, 0).r;
      if (d > closestDepth) {
        closestDepth = d;
        closest = q;
      }
    }
  vec3 mean = m1 / 9.0;
  vec3 sigma = sqrt(abs(m2 / 9.0 - mean * mean));

  // The G-buffer's motion covers object motion; the background (motion 0 there) moves with the camera.
  vec2 motion = (pc.flags & kTaaMotion) != 0u && !isBackground(closestDepth) ? texelFetch(motionTex, closest, 0).xy
                                                                             : cameraMotion(closest, closestDepth);
  vec2 uvPrev = (vec2(p) + 0.5) / vec2(pc.size) - motion;
  if (any(lessThan(uvPrev, vec2(0.0))) || any(greaterThan(uvPrev, vec2(1.0)))) {
    imageStore(outHistory, p, vec4(current, 1.0));  // off-screen: nothing to reproject
    return;
  }
  vec3 history = sampleHistory(uvPrev);
  history = clamp(clipToBox(history, mean, kGamma * sigma), lo, hi);

  // Anti-firefly weights 1/(1 + L): the blend of Reinhard-compressed colours, mapped back.
  float wc = pc.currentWeight / (1.0 + luminance(current));
  float wh = (1.0 - pc.currentWeight) / (1.0 + luminance(history));
  vec3 resolved = (current * wc + history * wh) / (wc + wh);
  imageStore(outHistory, p, vec4(resolved, 1.0));
}
