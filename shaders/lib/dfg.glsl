// The split-sum DFG table (render/dfg.h) from the bindless array: (A, B) with F0·A + F90·B the
// directional albedo of the GGX specular lobe at (n·v, perceptual roughness).
// Needs lib/frame.glsl and lib/textures.glsl.
#ifndef RAYSTER_DFG_GLSL
#define RAYSTER_DFG_GLSL

vec2 dfgTerms(float nv, float roughness) {
  const float n = float(kDfgSize);
  vec2 uv = (clamp(vec2(nv, roughness), 0.0, 1.0) * (n - 1.0) + 0.5) / n;  // texel centres at the ends
  return textureLod(textures[nonuniformEXT(frame.dfgSlot)], uv, 0.0).rg;
}

// With KHR_materials_specular's F90 (a dielectric lobe of strength s reflects F90 = s at grazing
// angles): F0·A + F90·B.
vec3 specularAlbedo(vec3 f0, vec3 f90, float nv, float roughness) {
  vec2 ab = dfgTerms(nv, roughness);
  return f0 * ab.x + f90 * ab.y;
}

#endif
