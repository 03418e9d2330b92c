#version 460
#include "lib/common.glsl"

// Skinning and morph targets (render/deform.cpp, docs/techniques.md §5b): one vertex of one
// deforming (instance, primitive) per invocation. The rest vertex gets its morph targets' deltas,
// weighted; then, where skinned, the weighted sum of its joints' matrices (weights normalised to a
// sum of 1; a vertex without weight stays where it is) takes it to world space. Normals go through
// the inverse transpose, tangents through the matrix; both are renormalised. Last frame's position
// is kept for the motion vectors first. scene::deformPrimitive() is the same on the CPU.
layout(local_size_x = kDeformGroupSize) in;
layout(push_constant, scalar) uniform Push { DeformPush pc; };

layout(buffer_reference, scalar) buffer OutVertices { Vertex v[]; };
layout(buffer_reference, scalar) buffer PrevPositions { vec3 p[]; };
layout(buffer_reference, scalar) readonly buffer Influences { SkinInfluence s[]; };
layout(buffer_reference, scalar) readonly buffer Joints { mat4 m[]; };
layout(buffer_reference, scalar) readonly buffer Deltas { vec3 d[]; };
layout(buffer_reference, scalar) readonly buffer Weights { float w[]; };

vec3 normalizedOr(vec3 v, vec3 fallback) {
  float l = length(v);
  return l > 0.0 && !isinf(l) && !isnan(l) ? v / l : fallback;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.vertexCount) return;
  Vertex v = Vertices(pc.restVertices).v[i];
  OutVertices out_ = OutVertices(pc.outVertices);
  PrevPositions prev = PrevPositions(pc.prevPositions);

  uint n = pc.vertexCount;
  for (uint t = 0u; t < pc.targetCount; ++t) {
    float w = Weights(pc.weights).w[t];
    if (w == 0.0) continue;
    Deltas d = Deltas(pc.targets);
    uint base = t * 3u * n;
    v.position += w * d.d[base + i];
    v.normal += w * d.d[base + n + i];
    v.tangent.xyz += w * d.d[base + 2u * n + i];
  }

  if (pc.influences != 0ul) {
    mat4 sum = mat4(0.0);
    float total = 0.0;
    for (uint s = 0u; s < pc.influenceSets; ++s) {
      SkinInfluence inf = Influences(pc.influences).s[s * n + i];
      uint joints[4] = uint[4](inf.joints.x & 0xFFFFu, inf.joints.x >> 16, inf.joints.y & 0xFFFFu, inf.joints.y >> 16);
      for (int k = 0; k < 4; ++k) {
        float w = inf.weights[k];
        if (w == 0.0) continue;
        sum += w * Joints(pc.joints).m[joints[k]];
        total += w;
      }
    }
    if (total > 0.0) {
      mat4 m = sum / total;
      v.position = (m * vec4(v.position, 1.0)).xyz;
      mat3 linear = mat3(m);
      v.normal = transpose(inverse(linear)) * v.normal;
      v.tangent.xyz = linear * v.tangent.xyz;
    }
  }
  v.normal = normalizedOr(v.normal, vec3(0.0, 0.0, 1.0));
  v.tangent.xyz = normalizedOr(v.tangent.xyz, vec3(1.0, 0.0, 0.0));

  prev.p[i] = pc.keepPrevious != 0u ? out_.v[i].position : v.position;
  out_.v[i] = v;
}
