// The bindless texture array (set 1) and material texture lookups with KHR_texture_transform.
// The includer defines RAYSTER_SAMPLE(slot, uv): implicit LOD in fragment shaders; LOD 0 where no
// derivatives exist (ray tracing), so traced surfaces use the finest mip.
#ifndef RAYSTER_TEXTURES_GLSL
#define RAYSTER_TEXTURES_GLSL

layout(set = 1, binding = 0) uniform sampler2D textures[];

#ifndef RAYSTER_SAMPLE
#define RAYSTER_SAMPLE(slot, uv) textureLod(textures[nonuniformEXT(slot)], uv, 0.0)
#endif

vec2 transformUv(TextureSlot t, vec2 uv0, vec2 uv1) {
  vec2 uv = (t.texCoord == 1u ? uv1 : uv0) * t.scale;
  float c = cos(t.rotation), s = sin(t.rotation);
  // glTF KHR_texture_transform: translation × rotation × scale, with the rotation matrix read in the
  // spec's row order (u' = c·u + s·v), which is what the TextureTransformTest sample model checks.
  return t.offset + vec2(c * uv.x + s * uv.y, -s * uv.x + c * uv.y);
}

#define SAMPLE_SLOT(t, uv0, uv1, fallback) \
  ((t).slot == kNoTexture ? (fallback) : RAYSTER_SAMPLE((t).slot, transformUv((t), (uv0), (uv1))))

#endif
