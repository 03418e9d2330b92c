// Motion vectors (docs/techniques.md §2): uvCurrent − uvPrevious from unjittered matrices, so a static
// scene has exactly zero motion under TAA jitter; the history of a pixel is fetched at uv − motion.
#ifndef RAYSTER_MOTION_GLSL
#define RAYSTER_MOTION_GLSL

vec2 uvFromClip(vec4 clip) { return clip.xy / clip.w * 0.5 + 0.5; }

// A surface point now at `world`, last frame at `prevWorld` (the same object point under the
// previous transform).
vec2 motionFromWorld(vec3 world, vec3 prevWorld) {
  return uvFromClip(frame.unjitteredClipFromWorld * vec4(world, 1.0)) -
         uvFromClip(frame.prevClipFromWorld * vec4(prevWorld, 1.0));
}

// The previous position of a point of instance `inst` now at `world`.
vec3 previousWorld(InstanceRecord inst, vec3 world) {
  // A static instance: exactly the same point, so static motion is exactly 0, not a rounding error.
  if (inst.prevWorldFromObject == inst.worldFromObject) return world;
  return (inst.prevWorldFromObject * (inverse(inst.worldFromObject) * vec4(world, 1.0))).xyz;
}

// The previous position of the point of triangle `primitive` of geometry `g` (instance `inst`) at
// barycentrics `bary`, now at `world`: deforming geometry interpolates its vertices' last positions.
vec3 previousWorldOnTriangle(InstanceRecord inst, GeometryRecord g, uint primitive, vec2 bary, vec3 world) {
  if (g.kind != kGeometryTriangles || g.prevPositionAddress == 0ul) return previousWorld(inst, world);
  Indices idx = Indices(g.indexAddress);
  Positions prev = Positions(g.prevPositionAddress);
  uint base = primitive * 3u;
  vec3 p = prev.p[idx.i[base]] * (1.0 - bary.x - bary.y) + prev.p[idx.i[base + 1u]] * bary.x +
           prev.p[idx.i[base + 2u]] * bary.y;
  return (inst.prevWorldFromObject * vec4(p, 1.0)).xyz;
}

// Camera motion of the background (infinitely far: rotation only) at a pixel's unjittered uv.
vec2 backgroundMotion(vec2 uv) {
  vec4 far = inverse(frame.unjitteredClipFromWorld) * vec4(uv * 2.0 - 1.0, kBackgroundDepth, 1.0);
  vec3 dir = far.xyz / far.w - frame.cameraPosition.xyz;
  vec4 prev = frame.prevClipFromWorld * vec4(dir, 0.0);
  vec4 cur = frame.unjitteredClipFromWorld * vec4(dir, 0.0);
  return uvFromClip(cur) - uvFromClip(prev);
}

#endif
