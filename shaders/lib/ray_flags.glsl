// The flags every scene ray starts from; a pass adds its own (terminate on first hit, ...).
// Needs GL_EXT_ray_tracing and lib/frame.glsl.
#ifndef RAYSTER_RAY_FLAGS_GLSL
#define RAYSTER_RAY_FLAGS_GLSL

// Back faces of single-sided materials are culled: the TLAS leaves facing culling on for instances
// whose triangles all cull (render/gpu_scene.cpp), and any-hit rejects the rest. Rays are forced
// opaque unless some geometry needs its any-hit shader.
uint sceneRayFlags() {
  return gl_RayFlagsCullBackFacingTrianglesEXT | ((frame.sceneFlags & kSceneAnyHit) != 0u ? 0u : gl_RayFlagsOpaqueEXT);
}

#endif
