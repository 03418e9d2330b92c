// The depth pyramid's layout (shared/types.h): the levels packed one after another, level 0 first.
#ifndef RAYSTER_HIZ_GLSL
#define RAYSTER_HIZ_GLSL

layout(buffer_reference, scalar) buffer Hiz { float d[]; };

uvec2 hizLevelSize(uvec2 size, uint level) { return max((size + (1u << level) - 1u) >> level, uvec2(1u)); }

uint hizLevelOffset(uvec2 size, uint level) {
  uint offset = 0u;
  for (uint k = 0u; k < level; ++k) {
    uvec2 s = hizLevelSize(size, k);
    offset += s.x * s.y;
  }
  return offset;
}

uint hizLevels(uvec2 size) {
  uint levels = 1u;
  while (max(size.x, size.y) > (1u << (levels - 1u))) ++levels;
  return levels;
}
#endif
