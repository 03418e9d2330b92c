// BC1, BC3, BC4 and BC5 blocks, as the Khronos Data Format Specification (§ S3TC and RGTC)
// defines them. Interpolated values are rounded to nearest, which is within
// the one-step tolerance the specification allows hardware.
#include "core/bcn.h"

#include <cstring>

namespace rayster {
namespace {

uint16_t u16(const uint8_t* p) { return uint16_t(p[0] | (p[1] << 8)); }

void rgb565(uint16_t c, int out[3]) {
  const int r = (c >> 11) & 31, g = (c >> 5) & 63, b = c & 31;
  out[0] = (r << 3) | (r >> 2);
  out[1] = (g << 2) | (g >> 4);
  out[2] = (b << 3) | (b >> 2);
}

// The colour half of BC1/BC2/BC3. `fourColours`: BC2/BC3 always interpolate four colours; BC1 only
// when colour0 > colour1, else three and a black (transparent with alpha) one.
void colourBlock(const uint8_t* block, bool fourColours, bool withAlpha, uint8_t out[16][4]) {
  const uint16_t c0 = u16(block), c1 = u16(block + 2);
  int palette[4][4];
  rgb565(c0, palette[0]);
  rgb565(c1, palette[1]);
  palette[0][3] = palette[1][3] = palette[2][3] = palette[3][3] = 255;
  const bool four = fourColours || c0 > c1;
  for (int k = 0; k < 3; ++k) {
    const int a = palette[0][k], b = palette[1][k];
    if (four) {
      palette[2][k] = (2 * a + b + 1) / 3;
      palette[3][k] = (a + 2 * b + 1) / 3;
    } else {
      palette[2][k] = (a + b + 1) / 2;
      palette[3][k] = 0;
    }
  }
  if (!four && withAlpha) palette[3][3] = 0;
  uint32_t indices;
  std::memcpy(&indices, block + 4, 4);  // little-endian, as every platform Rayster runs on
  for (int i = 0; i < 16; ++i) {
    const int* c = palette[(indices >> (2 * i)) & 3];
    for (int k = 0; k < 4; ++k) out[i][k] = uint8_t(c[k]);
  }
}

// An unsigned BC4 block (also BC3's alpha and each BC5 channel) into channel `channel` of out.
void channelBlock(const uint8_t* block, int channel, uint8_t out[16][4]) {
  const int r0 = block[0], r1 = block[1];
  int values[8] = {r0, r1};
  if (r0 > r1) {
    for (int k = 1; k < 7; ++k) values[k + 1] = ((7 - k) * r0 + k * r1 + 3) / 7;
  } else {
    for (int k = 1; k < 5; ++k) values[k + 1] = ((5 - k) * r0 + k * r1 + 2) / 5;
    values[6] = 0;
    values[7] = 255;
  }
  uint64_t bits = 0;
  for (int i = 0; i < 6; ++i) bits |= uint64_t(block[2 + i]) << (8 * i);
  for (int i = 0; i < 16; ++i) out[i][channel] = uint8_t(values[(bits >> (3 * i)) & 7]);
}

void clear(uint8_t out[16][4]) {
  for (int i = 0; i < 16; ++i) out[i][0] = out[i][1] = out[i][2] = 0, out[i][3] = 255;
}

}  // namespace

void decodeBc1(const uint8_t block[8], bool withAlpha, uint8_t out[16][4]) {
  colourBlock(block, false, withAlpha, out);
}

void decodeBc3(const uint8_t block[16], uint8_t out[16][4]) {
  colourBlock(block + 8, true, false, out);
  channelBlock(block, 3, out);
}

void decodeBc4(const uint8_t block[8], uint8_t out[16][4]) {
  clear(out);
  channelBlock(block, 0, out);
}

void decodeBc5(const uint8_t block[16], uint8_t out[16][4]) {
  clear(out);
  channelBlock(block, 0, out);
  channelBlock(block + 8, 1, out);
}

}  // namespace rayster
