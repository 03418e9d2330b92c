// One specular scattering event (a mirror or metal reflection, or glass reflecting or refracting by
// Fresnel), shared by the specular path (lib/specular_path.glsl, docs/techniques.md §12) and the
// probe rays (probe_trace.rgen: their specular chains, §16b). Needs lib/common.glsl, lib/brdf.glsl
// and lib/light_ray.glsl.
#ifndef RAYSTER_SPECULAR_SCATTER_GLSL
#define RAYSTER_SPECULAR_SCATTER_GLSL

// One specular event at a surface. `n`, `ng` face the incoming ray; `entering`: the ray is outside
// the object (for closed meshes, by the triangle's winding); `specular`: KHR_materials_specular's
// F0 tint and strength (GBufferValues::specular). Updates the ray and the throughput.
void scatter(inout vec3 dir, inout vec3 origin, inout vec3 beta, vec3 p, vec3 n, vec3 ng, bool entering,
             vec3 baseColor, float metallic, float transmission, float ior, bool thinWalled, vec4 specular,
             inout uint rng) {
  float cosI = clamp(dot(-dir, n), 0.0, 1.0);
  vec3 next;
  if (transmission <= 0.0) {
    // Opaque: the mirror lobe with Schlick Fresnel (metals tint it with their base colour).
    SurfaceBsdf b = makeBsdf(baseColor, metallic, 0.0, specular, ior);
    beta *= fresnelSchlick(b.f0, b.f90, cosI);
    next = reflect(dir, n);
  } else {
    float etaI = entering ? 1.0 : ior;  // glass in air; GLSL refract() wants etaI / etaT
    float etaT = entering ? ior : 1.0;
    float f = thinWalled ? fresnelDielectric(cosI, 1.0, ior) : fresnelDielectric(cosI, etaI, etaT);
    vec3 fr = specularGlassFresnel(f, ior, specular);
    float pr = max(fr.r, max(fr.g, fr.b));
    if (rnd(rng) < pr) {
      beta *= fr / pr;         // chosen with probability max(F): 1 unless the reflection is tinted
      next = reflect(dir, n);
    } else {
      // Chosen with probability 1−F; the diffuse share (1−transmission) is the lighting pass's.
      beta *= transmission * baseColor;
      next = thinWalled ? dir : refract(dir, n, etaI / etaT);
      if (dot(next, next) == 0.0) next = reflect(dir, n);  // unreachable when f == 1 under TIR
    }
  }
  // Leave from the side the new ray goes to.
  origin = p + (dot(next, ng) > 0.0 ? ng : -ng) * hitRayOffset(p);
  dir = normalize(next);
}

#endif
