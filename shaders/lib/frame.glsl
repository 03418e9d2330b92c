// Binding 0 of set 0 in every pass: the frame's constants.
#ifndef RAYSTER_FRAME_GLSL
#define RAYSTER_FRAME_GLSL
layout(set = 0, binding = 0, scalar) uniform FrameBlock { FrameConstants frame; };

// Light sources are pre-exposed (docs/techniques.md §20): lights and emission are read × frame.exposure (and
// the host scales ambient, environment and its SH the same way), so every radiance a pass computes
// and stores is already exposed. fp16 targets and the firefly clamps then work in display-relative
// units, whatever the scale of the scene's light units (a 100 000 lux sun or a 3 W bulb).
LightRecord loadLight(uint i) {
  LightRecord l = Lights(frame.lights).l[i];
  l.radiance *= frame.exposure;
  return l;
}
vec3 exposedEmission(MaterialRecord m) { return m.emissive * frame.exposure; }
// Whether lights cast shadows (shared/types.h kEffectShadows): off, a pass's lightVisibility() is
// never called (lib/shading.glsl, lib/one_light.glsl) and the raw twins trace no shadow rays.
bool shadowRaysOn() { return (frame.effectFlags & kEffectShadows) != 0u; }
#endif
