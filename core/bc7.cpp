// BC7 (BPTC UNORM) blocks, as the Khronos Data Format Specification 1.4 §BPTC defines them:
// eight modes of one to three subsets, each with two endpoints (with P-bits), 2- to 4-bit indices
// and, in modes 4 and 5, separate alpha indices and a channel rotation.
#include <cstring>
#include <utility>

#include "core/bcn.h"

namespace rayster {
namespace {

// The specification's partition tables (bptcP2subset, bptcP3subset; 2 bits per texel, texel 0 in
// the lowest bits) and anchor indices (bptcA2index, bptcA32index, bptcA33index), read from its
// tables. Two of its bold "anchor" markings disagree with its anchor tables (2-subset partition
// 35, 3-subset partition 1); the anchor tables are what decoders use.
constexpr uint32_t kPartitions2[64] = {
    0x50505050, 0x40404040, 0x54545454, 0x54505040, 0x50404000, 0x55545450, 0x55545040, 0x54504000,
    0x50400000, 0x55555450, 0x55544000, 0x54400000, 0x55555440, 0x55550000, 0x55555500, 0x55000000,
    0x55150100, 0x00004054, 0x15010000, 0x00405054, 0x00004050, 0x15050100, 0x05010000, 0x40505054,
    0x00404050, 0x05010100, 0x14141414, 0x05141450, 0x01155440, 0x00555500, 0x15014054, 0x05414150,
    0x44444444, 0x55005500, 0x11441144, 0x05055050, 0x05500550, 0x11114444, 0x41144114, 0x44111144,
    0x15055054, 0x01055040, 0x05041050, 0x05455150, 0x14414114, 0x50050550, 0x41411414, 0x00141400,
    0x00041504, 0x00105410, 0x10541000, 0x04150400, 0x50410514, 0x41051450, 0x05415014, 0x14054150,
    0x41050514, 0x41505014, 0x40011554, 0x54150140, 0x50505500, 0x00555050, 0x15151010, 0x54540404};
constexpr uint32_t kPartitions3[64] = {
    0xAA685050, 0x6A5A5040, 0x5A5A4200, 0x5450A0A8, 0xA5A50000, 0xA0A05050, 0x5555A0A0, 0x5A5A5050,
    0xAA550000, 0xAA555500, 0xAAAA5500, 0x90909090, 0x94949494, 0xA4A4A4A4, 0xA9A59450, 0x2A0A4250,
    0xA5945040, 0x0A425054, 0xA5A5A500, 0x55A0A0A0, 0xA8A85454, 0x6A6A4040, 0xA4A45000, 0x1A1A0500,
    0x0050A4A4, 0xAAA59090, 0x14696914, 0x69691400, 0xA08585A0, 0xAA821414, 0x50A4A450, 0x6A5A0200,
    0xA9A58000, 0x5090A0A8, 0xA8A09050, 0x24242424, 0x00AA5500, 0x24924924, 0x24499224, 0x50A50A50,
    0x500AA550, 0xAAAA4444, 0x66660000, 0xA5A0A5A0, 0x50A050A0, 0x69286928, 0x44AAAA44, 0x66666600,
    0xAA444444, 0x54A854A8, 0x95809580, 0x96969600, 0xA85454A8, 0x80959580, 0xAA141414, 0x96960000,
    0xAAAA1414, 0xA05050A0, 0xA0A5A5A0, 0x96000000, 0x40804080, 0xA9A8A9A8, 0xAAAAAA44, 0x2A4A5254};
constexpr uint8_t kAnchor2[64] = {15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 2,  8, 2, 2, 8,
                                  8,  15, 2,  8,  2,  2,  8,  8,  2,  2,  15, 15, 6,  8,  2,  8,  15, 15, 2, 8, 2, 2,
                                  2,  15, 15, 6,  6,  2,  6,  8,  15, 15, 2,  2,  15, 15, 15, 15, 15, 2,  2, 15};
constexpr uint8_t kAnchor3Second[64] = {
    3, 3,  15, 15, 8, 3,  15, 15, 8,  8, 6,  6, 6,  5,  3,  3,  3, 3,  8, 15, 3, 3, 6, 10, 5, 8,  8, 6,  8,  5,  15, 15,
    8, 15, 3,  5,  6, 10, 8,  15, 15, 3, 15, 5, 15, 15, 15, 15, 3, 15, 5, 5,  5, 8, 5, 10, 5, 10, 8, 13, 15, 12, 3,  3};
constexpr uint8_t kAnchor3Third[64] = {15, 8, 8,  3,  15, 15, 3,  8,  15, 15, 15, 15, 15, 15, 15, 8,
                                       15, 8, 15, 3,  15, 8,  15, 8,  3,  15, 6,  10, 15, 15, 10, 8,
                                       15, 3, 15, 10, 10, 8,  9,  10, 6,  15, 8,  15, 3,  6,  6,  8,
                                       15, 3, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 3,  15, 15, 8};

struct Mode {
  int subsets, partitionBits, rotationBits, selectorBits, colourBits, alphaBits, endpointPBits, sharedPBits, indexBits,
      secondaryIndexBits;
};
// Table "Mode-dependent BPTC parameters": NS, PB, RB, ISB, CB, AB, EPB, SPB, IB, IB2.
constexpr Mode kModes[8] = {{3, 4, 0, 0, 4, 0, 1, 0, 3, 0}, {2, 6, 0, 0, 6, 0, 0, 1, 3, 0},
                            {3, 6, 0, 0, 5, 0, 0, 0, 2, 0}, {2, 6, 0, 0, 7, 0, 1, 0, 2, 0},
                            {1, 0, 2, 1, 5, 6, 0, 0, 2, 3}, {1, 0, 2, 0, 7, 8, 0, 0, 2, 2},
                            {1, 0, 0, 0, 7, 7, 1, 0, 4, 0}, {2, 6, 0, 0, 5, 5, 1, 0, 2, 0}};

constexpr int kWeights2[4] = {0, 21, 43, 64};
constexpr int kWeights3[8] = {0, 9, 18, 27, 37, 46, 55, 64};
constexpr int kWeights4[16] = {0, 4, 9, 13, 17, 21, 26, 30, 34, 38, 43, 47, 51, 55, 60, 64};

class Bits {
 public:
  explicit Bits(const uint8_t* block) : block_(block) {}
  int read(int count) {
    int v = 0;
    for (int i = 0; i < count; ++i, ++at_)
      if (at_ < 128) v |= ((block_[at_ >> 3] >> (at_ & 7)) & 1) << i;
    return v;
  }

 private:
  const uint8_t* block_;
  int at_ = 0;
};

// An endpoint channel of `bits` bits (P-bit included) to 8 bits: shifted up, its top bits
// replicated below.
int expand(int value, int bits) { return bits >= 8 ? value : (value << (8 - bits)) | (value >> (2 * bits - 8)); }

int weight(int index, int bits) {
  return bits == 2 ? kWeights2[index] : bits == 3 ? kWeights3[index] : kWeights4[index];
}

int interpolate(int e0, int e1, int w) { return ((64 - w) * e0 + w * e1 + 32) >> 6; }

}  // namespace

void decodeBc7(const uint8_t block[16], uint8_t out[16][4]) {
  int modeIndex = 0;
  while (modeIndex < 8 && !((block[0] >> modeIndex) & 1)) ++modeIndex;
  if (modeIndex == 8) {  // reserved: every channel of every texel is 0
    std::memset(out, 0, 64);
    return;
  }
  const Mode& m = kModes[modeIndex];
  Bits bits(block);
  bits.read(modeIndex + 1);
  const int partition = bits.read(m.partitionBits);
  const int rotation = bits.read(m.rotationBits);
  const int selector = bits.read(m.selectorBits);

  // Endpoints: channel by channel, subset by subset, endpoint 0 then 1.
  const int endpoints = 2 * m.subsets;
  int e[6][4] = {};
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < endpoints; ++i) e[i][c] = bits.read(m.colourBits);
  for (int i = 0; i < endpoints; ++i) e[i][3] = m.alphaBits ? bits.read(m.alphaBits) : 255;
  int pBits[6] = {};
  if (m.endpointPBits)
    for (int i = 0; i < endpoints; ++i) pBits[i] = bits.read(1);
  if (m.sharedPBits)
    for (int s = 0; s < m.subsets; ++s) pBits[2 * s] = pBits[2 * s + 1] = bits.read(1);
  const bool hasP = m.endpointPBits || m.sharedPBits;
  for (int i = 0; i < endpoints; ++i) {
    for (int c = 0; c < 3; ++c)
      e[i][c] = hasP ? expand((e[i][c] << 1) | pBits[i], m.colourBits + 1) : expand(e[i][c], m.colourBits);
    if (m.alphaBits) e[i][3] = hasP ? expand((e[i][3] << 1) | pBits[i], m.alphaBits + 1) : expand(e[i][3], m.alphaBits);
  }

  // Which subset each texel is in, and the subsets' anchor texels (their index has one bit less).
  int subset[16] = {};
  int anchors[3] = {0, -1, -1};
  if (m.subsets == 2) {
    for (int t = 0; t < 16; ++t) subset[t] = int((kPartitions2[partition] >> (2 * t)) & 3);
    anchors[1] = kAnchor2[partition];
  } else if (m.subsets == 3) {
    for (int t = 0; t < 16; ++t) subset[t] = int((kPartitions3[partition] >> (2 * t)) & 3);
    anchors[1] = kAnchor3Second[partition];
    anchors[2] = kAnchor3Third[partition];
  }
  auto isAnchor = [&](int t) { return t == anchors[0] || t == anchors[1] || t == anchors[2]; };
  int primary[16], secondary[16] = {};
  for (int t = 0; t < 16; ++t) primary[t] = bits.read(m.indexBits - (isAnchor(t) ? 1 : 0));
  if (m.secondaryIndexBits)
    for (int t = 0; t < 16; ++t) secondary[t] = bits.read(m.secondaryIndexBits - (t == 0 ? 1 : 0));

  for (int t = 0; t < 16; ++t) {
    const int* e0 = e[2 * subset[t]];
    const int* e1 = e[2 * subset[t] + 1];
    // Colour and alpha share the primary indices, except in modes 4 and 5 (the selector of mode 4
    // swaps which of its two index sets is colour's).
    int colourIndex = primary[t], colourBits = m.indexBits, alphaIndex = primary[t], alphaBits = m.indexBits;
    if (m.secondaryIndexBits) {
      alphaIndex = secondary[t], alphaBits = m.secondaryIndexBits;
      if (selector) std::swap(colourIndex, alphaIndex), std::swap(colourBits, alphaBits);
    }
    int rgba[4];
    for (int c = 0; c < 3; ++c) rgba[c] = interpolate(e0[c], e1[c], weight(colourIndex, colourBits));
    rgba[3] = interpolate(e0[3], e1[3], weight(alphaIndex, alphaBits));
    if (rotation) std::swap(rgba[3], rgba[rotation - 1]);
    for (int c = 0; c < 4; ++c) out[t][c] = uint8_t(rgba[c]);
  }
}

}  // namespace rayster
