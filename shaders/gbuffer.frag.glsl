#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"
#define RAYSTER_SAMPLE(slot, uv) texture(textures[nonuniformEXT(slot)], uv)
#include "lib/textures.glsl"
#include "lib/surface.glsl"
#include "lib/motion.glsl"
#include "lib/gbuffer_out.glsl"


layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inTangent;
layout(location = 3) in vec2 inUv0;
layout(location = 4) in vec2 inUv1;
layout(location = 5) in vec3 inPrevWorldPos;
layout(location = 6) flat in uvec2 inDraw;  // instance, geometry
layout(location = 7) in vec4 inColor;

void main() {
  InstanceRecord inst = Instances(frame.instances).i[inDraw.x];
  GeometryRecord g = Geometries(frame.geometries).g[inDraw.y];
  MaterialRecord m = Materials(frame.materials).m[g.material];
  // Single-sided materials show no back faces (glTF doubleSided false). gl_FrontFacing comes from
  // the screen winding, which a mirroring instance turns.
  bool mirrored = determinant(mat3(inst.worldFromObject)) < 0.0;
  if ((m.flags & kMaterialDoubleSided) == 0u && gl_FrontFacing == mirrored) discard;
  if (alphaRejects(m, inUv0, inUv1, inColor.a, alphaNoise(uvec2(gl_FragCoord.xy)))) discard;
  // The geometric normal from the triangle itself, exactly as the traced producer computes it.
  vec3 p0, p1, p2;
  trianglePositions(g, inst, uint(gl_PrimitiveID), p0, p1, p2);
  SurfacePoint sp = SurfacePoint(inWorldPos, inNormal, inTangent, windingNormal(inst, p0, p1, p2), inUv0, inUv1, inColor);
  writeGBuffer(evaluateSurface(m, sp, frame.cameraPosition.xyz), inDraw.x, motionFromWorld(inWorldPos, inPrevWorldPos));
}
