// The bindless texture array (set 1) and material texture lookups with KHR_texture_transform.
// The includer defines RAYSTER_SAMPLE(slot, uv): implicit LOD in fragment shaders. Ray tracing has
// no derivatives: there the LOD comes from the ray cone of the hit being shaded (gConeLod, set by
// lib/ray_cone.glsl's setRayCone), plus half the log2 of the texture's texel count; shaders that set
// no cone (the path tracer, diffuse bounces, any-hit alpha tests) sample the finest mip.
#ifndef RAYSTER_TEXTURES_GLSL
#define RAYSTER_TEXTURES_GLSL

layout(set = 1, binding = 0) uniform sampler2D textures[];

#ifndef RAYSTER_SAMPLE
// log2(cone width / |cos|) + 0.5·log2(uv area / world area) of the hit's triangle (Akenine-Möller et
// al., "Texture Level of Detail Strategies for Real-Time Ray Tracing", Ray Tracing Gems ch. 20).
float gConeLod = -1e4;
// `lodBias`: TextureSlot::lodBias, the texture's 0.5·log2(texels × |KHR_texture_transform scale|).
float coneLod(float lodBias) { return max(0.0, gConeLod + lodBias); }
#define RAYSTER_SAMPLE_BIASED(slot, uv, lodBias) textureLod(textures[nonuniformEXT(slot)], uv, coneLod(lodBias))
// A texture without a TextureSlot (none today): no density known, mip 0.
#define RAYSTER_SAMPLE(slot, uv) textureLod(textures[nonuniformEXT(slot)], uv, 0.0)
#else
#define RAYSTER_SAMPLE_BIASED(slot, uv, lodBias) RAYSTER_SAMPLE(slot, uv)
#endif

vec2 transformUv(TextureSlot t, vec2 uv0, vec2 uv1) {
  vec2 uv = (t.texCoord == 1u ? uv1 : uv0) * t.scale;
  float c = cos(t.rotation), s = sin(t.rotation);
  // glTF KHR_texture_transform: translation × rotation × scale, with the rotation matrix read in the
  // spec's row order (u' = c·u + s·v), which is what the TextureTransformTest sample model checks.
  return t.offset + vec2(c * uv.x + s * uv.y, -s * uv.x + c * uv.y);
}

#define SAMPLE_SLOT(t, uv0, uv1, fallback) \
  ((t).slot == kNoTexture ? (fallback) : RAYSTER_SAMPLE_BIASED((t).slot, transformUv((t), (uv0), (uv1)), (t).lodBias))

// An effect that records no pass leaves its input bound to a one-texel neutral image
// (render/neutral_images.h), and so is the G-buffer's layers target in a scene without a clear coat
// or sheen: read such inputs at min(pixel, size - 1), never outside the image (an out-of-bounds
// texelFetch is undefined: 0 on lavapipe, which made --ao off drop all ambient and environment light).
vec4 fetchNeutral(sampler2D t, ivec2 px) { return texelFetch(t, min(px, textureSize(t, 0) - 1), 0); }
uvec4 fetchNeutral(usampler2D t, ivec2 px) { return texelFetch(t, min(px, textureSize(t, 0) - 1), 0); }
vec4 fetchNeutralLayer(sampler2DArray t, ivec2 px, int layer) {
  return texelFetch(t, ivec3(min(px, textureSize(t, 0).xy - 1), layer), 0);
}

#endif
