// Ray cones for texture LOD at ray hits (docs/techniques.md §26b; Akenine-Möller et al., Ray
// Tracing Gems ch. 20): each camera ray carries a cone whose spread is one pixel's angle; at a hit at
// cone width w, seen at angle θ, textures are sampled at lod = Δ + log2(w / |cos θ|), Δ the
// triangle's texel density (lib/hit_surface.glsl) with the texture's size (lib/textures.glsl). So the
// traced G-buffer samples the mips the rasteriser's derivatives pick, and reflections of a textured
// floor are as filtered as the floor. Mirrors are treated as flat: the spread stays one pixel's
// angle along the path (no curvature term), and glossy lobes do not widen the cone.
#ifndef RAYSTER_RAY_CONE_GLSL
#define RAYSTER_RAY_CONE_GLSL

// The angle between the camera rays of two vertically adjacent pixels at the image centre (sin of
// it, which is the angle to within 1e-7 at any field of view worth rendering).
float pixelSpreadAngle() {
  vec3 o = frame.cameraPosition.xyz;
  vec2 c = vec2(0.5);
  vec3 a = cameraRayDirection(frame.worldFromClip, c, o);
  vec3 b = cameraRayDirection(frame.worldFromClip, c + vec2(0.0, 1.0 / float(frame.size.y)), o);
  return length(cross(a, b));
}

// Sets the LOD of the textures evaluateSurface() samples next: the cone is `width` wide where the
// ray `dir` met the surface of geometric normal `ng` that surfaceAtHit() just returned.
void setRayCone(float width, vec3 ng, vec3 dir) {
  float c = abs(dot(normalize(ng), dir));
  gConeLod = gHitUvDensity + log2(max(width, 1e-20) / max(c, 1e-3));
}

#endif
