// The surface a radiance ray hit: position, normals, tangent, UVs and material, for triangles
// (from the vertices) and analytic spheres. Shared by traced primaries and the bounce loop.
#ifndef RAYSTER_HIT_SURFACE_GLSL
#define RAYSTER_HIT_SURFACE_GLSL

// 0.5·log2(uv area / world area) of the surface surfaceAtHit found last (the texel density ray
// cones need: lib/ray_cone.glsl); very negative where the surface has no texture coordinates.
float gHitUvDensity = -1e4;

// sp.geometricNormal keeps the triangle's front side (outward for closed meshes), unflipped.
void surfaceAtHit(PrimaryPayload payload, vec3 origin, vec3 dir, out SurfacePoint sp, out MaterialRecord m) {
  InstanceRecord inst = Instances(frame.instances).i[payload.instance];
  GeometryRecord g = Geometries(frame.geometries).g[payload.geometry];
  if (g.kind == kGeometrySpheres) {
    SphereRecord s = Spheres(g.vertexAddress).s[payload.primitive];
    m = Materials(frame.materials).m[s.material];
    sp.position = origin + payload.t * dir;
    vec3 objPos = (inverse(inst.worldFromObject) * vec4(sp.position, 1.0)).xyz;
    vec3 objNormal;
    vec2 tex;
    vec4 tangent;
    sphereAttributes(s.center, objPos, objNormal, tex, tangent);
    sp.normal = (inst.normalFromObject * vec4(objNormal, 0.0)).xyz;
    sp.geometricNormal = sp.normal;
    sp.tangent = vec4((inst.worldFromObject * vec4(tangent.xyz, 0.0)).xyz, tangent.w);
    sp.uv0 = tex;
    sp.uv1 = tex;
    sp.color = vec4(1.0);
    // The equirectangular UVs' unit square covers the sphere's 4πr² (evenly enough for a LOD).
    float r = s.radius * length(inst.worldFromObject[0].xyz);
    gHitUvDensity = r > 0.0 ? -0.5 * log2(4.0 * kPi * r * r) : -1e4;
  } else {
    m = Materials(frame.materials).m[g.material];
    Indices idx = Indices(g.indexAddress);
    Vertices vtx = Vertices(g.vertexAddress);
    uint base = payload.primitive * 3u;
    Vertex v0 = vtx.v[idx.i[base]], v1 = vtx.v[idx.i[base + 1u]], v2 = vtx.v[idx.i[base + 2u]];
    vec3 w = vec3(1.0 - payload.bary.x - payload.bary.y, payload.bary.x, payload.bary.y);
    vec3 p0, p1, p2;
    trianglePositions(g, inst, payload.primitive, p0, p1, p2);
    // Interpolating the triangle's world positions is more precise than origin + t·dir.
    sp.position = p0 * w.x + p1 * w.y + p2 * w.z;
    sp.normal = (inst.normalFromObject * vec4(v0.normal * w.x + v1.normal * w.y + v2.normal * w.z, 0.0)).xyz;
    vec4 t = v0.tangent * w.x + v1.tangent * w.y + v2.tangent * w.z;
    sp.tangent = vec4((inst.worldFromObject * vec4(t.xyz, 0.0)).xyz, v0.tangent.w);
    sp.geometricNormal = windingNormal(inst, p0, p1, p2);
    sp.uv0 = v0.uv0 * w.x + v1.uv0 * w.y + v2.uv0 * w.z;
    sp.uv1 = v0.uv1 * w.x + v1.uv1 * w.y + v2.uv1 * w.z;
    sp.color = vertexColor(g, payload.primitive, w);
    vec2 du = v1.uv0 - v0.uv0, dv = v2.uv0 - v0.uv0;
    float uvArea = abs(du.x * dv.y - du.y * dv.x), worldArea = length(cross(p1 - p0, p2 - p0));
    gHitUvDensity = uvArea > 0.0 && worldArea > 0.0 ? 0.5 * log2(uvArea / worldArea) : -1e4;
  }
}

#endif
