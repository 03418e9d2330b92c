#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"
#define RAYSTER_SAMPLE(slot, uv) texture(textures[nonuniformEXT(slot)], uv)
#include "lib/textures.glsl"
#include "lib/surface.glsl"
#include "lib/sphere.glsl"
#include "lib/motion.glsl"
#include "lib/gbuffer_out.glsl"

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) flat in uint inSphere;
layout(location = 2) flat in uvec2 inDraw;  // instance, geometry

void main() {
  InstanceRecord inst = Instances(frame.instances).i[inDraw.x];
  GeometryRecord g = Geometries(frame.geometries).g[inDraw.y];
  SphereRecord s = Spheres(g.vertexAddress).s[inSphere];
  MaterialRecord m = Materials(frame.materials).m[s.material];
  // The same ray as a traced primary: from the camera through this pixel's centre.
  vec2 uv = gl_FragCoord.xy / vec2(frame.size);
  vec3 origin = frame.cameraPosition.xyz;
  vec3 dir = cameraRayDirection(frame.worldFromClip, uv, origin);
  mat4 objectFromWorld = inverse(inst.worldFromObject);
  vec3 objOrigin = (objectFromWorld * vec4(origin, 1.0)).xyz;
  vec3 objDir = (objectFromWorld * vec4(dir, 0.0)).xyz;
  float t = intersectSphere(s.center, s.radius, objOrigin, objDir, 0.0, 1e30);
  if (t < 0.0) discard;
  vec3 n, objNormal;
  vec2 tex;
  vec4 tangent;
  sphereAttributes(s.center, objOrigin + t * objDir, objNormal, tex, tangent);
  if (alphaRejects(m, tex, tex, 1.0, alphaNoise(uvec2(gl_FragCoord.xy)))) discard;
  vec3 worldPos = origin + t * dir;
  n = (inst.normalFromObject * vec4(objNormal, 0.0)).xyz;
  vec4 worldTangent = vec4((inst.worldFromObject * vec4(tangent.xyz, 0.0)).xyz, tangent.w);
  vec4 clip = frame.clipFromWorld * vec4(worldPos, 1.0);
  gl_FragDepth = clip.z / clip.w;
  writeGBuffer(evaluateSurface(m, SurfacePoint(worldPos, n, worldTangent, n, tex, tex, vec4(1.0)), origin), inDraw.x,
              motionFromWorld(worldPos, previousWorld(inst, worldPos)));
}
