#pragma once
// Block-compressed (BCn) texel blocks decoded to RGBA8, as Vulkan samples them: 4 × 4 texels per
// block, row-major into out[16][4]. Channels a format lacks read as Vulkan gives them (green and
// blue 0, alpha 255). Every 8- or 16-byte pattern is a valid block, so these cannot fail.
#include <cstdint>

namespace rayster {

void decodeBc1(const uint8_t block[8], bool withAlpha, uint8_t out[16][4]);  // alpha: BC1 RGBA's 1-bit alpha
void decodeBc3(const uint8_t block[16], uint8_t out[16][4]);
void decodeBc4(const uint8_t block[8], uint8_t out[16][4]);   // unsigned: red only
void decodeBc5(const uint8_t block[16], uint8_t out[16][4]);  // unsigned: red and green
void decodeBc7(const uint8_t block[16], uint8_t out[16][4]);  // core/bc7.cpp

}  // namespace rayster
