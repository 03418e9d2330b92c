// Rayster's KTX2 reader (core/ktx2.cpp, core/bcn.cpp) on files this test writes: uncompressed
// formats, zstd supercompression, BC1/BC3/BC4/BC5 blocks with hand-computed decodes and blocks
// from a small BC1 encoder below; malformed files (truncated, lying level index, wrong sizes) and
// Basis Universal payloads refused in one line; and KHR_texture_basisu / image/ktx2 in glTF.
#include <random>

#include <zstd.h>

#include <gtest/gtest.h>

#include "core/bcn.h"
#include "core/image_io.h"
#include "core/ktx2.h"
#include "core/log.h"
#include "tests/unit/gltf_test_util.h"
#include "tests/unit/ktx2_test_util.h"

namespace rayster::test {
namespace {

Result<Image8> decode(const std::vector<uint8_t>& file) { return decodeKtx2(file, 16384); }

std::vector<uint8_t> pixel(const Image8& image, int x, int y) {
  const uint8_t* p = image.pixel(x, y);
  return {p[0], p[1], p[2], p[3]};
}

void expectRefused(const Result<Image8>& image, const std::string& part) {
  ASSERT_FALSE(image.ok()) << "expected a refusal containing: " << part;
  EXPECT_NE(image.error().message.find(part), std::string::npos) << image.error().message;
  EXPECT_EQ(image.error().message.rfind("KTX2 ", 0), 0u) << image.error().message;
  EXPECT_EQ(image.error().message.find('\n'), std::string::npos);
}

TEST(Ktx2, UncompressedFormatsDecodeAsVulkanSamplesThem) {
  auto rgba = decode(writeKtx2({37, 2, 1}, {10, 20, 30, 40, 50, 60, 70, 80}));
  ASSERT_TRUE(rgba.ok()) << rgba.error().message;
  EXPECT_EQ(pixel(*rgba, 1, 0), (std::vector<uint8_t>{50, 60, 70, 80}));
  auto rgb = decode(writeKtx2({29, 1, 2}, {1, 2, 3, 4, 5, 6}));  // sRGB: same bytes, decided by use
  ASSERT_TRUE(rgb.ok()) << rgb.error().message;
  EXPECT_EQ(pixel(*rgb, 0, 1), (std::vector<uint8_t>{4, 5, 6, 255}));
  auto r = decode(writeKtx2({9, 3, 1}, {7, 8, 9}));  // no row padding in KTX2
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(pixel(*r, 2, 0), (std::vector<uint8_t>{9, 0, 0, 255}));
  auto rg = decode(writeKtx2({16, 1, 1}, {7, 8}));
  ASSERT_TRUE(rg.ok());
  EXPECT_EQ(pixel(*rg, 0, 0), (std::vector<uint8_t>{7, 8, 0, 255}));
  auto bgra = decode(writeKtx2({44, 1, 1}, {1, 2, 3, 4}));
  ASSERT_TRUE(bgra.ok());
  EXPECT_EQ(pixel(*bgra, 0, 0), (std::vector<uint8_t>{3, 2, 1, 4}));
  // RGBA16F: 0.5, 1.0, 2.0 (clamped), -1 (clamped) in half floats.
  auto half = decode(writeKtx2({97, 1, 1}, {0x00, 0x38, 0x00, 0x3C, 0x00, 0x40, 0x00, 0xBC}));
  ASSERT_TRUE(half.ok()) << half.error().message;
  EXPECT_EQ(pixel(*half, 0, 0), (std::vector<uint8_t>{128, 255, 255, 0}));
}

TEST(Ktx2, ZstdSupercompressionInflates) {
  std::vector<uint8_t> raw(16 * 16 * 4);
  for (size_t i = 0; i < raw.size(); ++i) raw[i] = uint8_t(i * 7);
  std::vector<uint8_t> packed(ZSTD_compressBound(raw.size()));
  packed.resize(ZSTD_compress(packed.data(), packed.size(), raw.data(), raw.size(), 3));
  Ktx2Spec spec{37, 16, 16};
  spec.scheme = 2;
  spec.uncompressedLength = raw.size();
  auto image = decode(writeKtx2(spec, packed));
  ASSERT_TRUE(image.ok()) << image.error().message;
  EXPECT_EQ(image->rgba, raw);

  spec.uncompressedLength = raw.size() + 4;  // a lie about the inflated size
  expectRefused(decode(writeKtx2(spec, packed)), "uncompressedByteLength 1028 is not the 1024 bytes");
  spec.uncompressedLength = raw.size();
  std::vector<uint8_t> garbage(packed.size(), 0x55);
  expectRefused(decode(writeKtx2(spec, garbage)), "level 0 zstd data is invalid");
  std::vector<uint8_t> cut(packed.begin(), packed.begin() + long(packed.size() / 2));
  expectRefused(decode(writeKtx2(spec, cut)), "zstd");
}

// One 4 × 4 block decoded: texel i takes palette entry i % 4 (BC1) or i % 8 (BC4).
TEST(Ktx2, Bc1BlocksDecodeToTheirHandComputedPalettes) {
  uint8_t out[16][4];
  // colour0 = pure red (0xF800) > colour1 = pure blue (0x001F): four colours, thirds between.
  const uint8_t four[8] = {0x00, 0xF8, 0x1F, 0x00, 0xE4, 0xE4, 0xE4, 0xE4};  // indices 0,1,2,3 per row
  decodeBc1(four, false, out);
  const uint8_t expectFour[4][4] = {{255, 0, 0, 255}, {0, 0, 255, 255}, {170, 0, 85, 255}, {85, 0, 170, 255}};
  for (int i = 0; i < 16; ++i)
    for (int k = 0; k < 4; ++k) EXPECT_EQ(out[i][k], expectFour[i % 4][k]) << i << " " << k;
  // colour0 <= colour1: three colours and black, transparent in BC1 RGBA.
  const uint8_t three[8] = {0x1F, 0x00, 0x00, 0xF8, 0xE4, 0xE4, 0xE4, 0xE4};
  decodeBc1(three, true, out);
  const uint8_t expectThree[4][4] = {{0, 0, 255, 255}, {255, 0, 0, 255}, {128, 0, 128, 255}, {0, 0, 0, 0}};
  for (int i = 0; i < 16; ++i)
    for (int k = 0; k < 4; ++k) EXPECT_EQ(out[i][k], expectThree[i % 4][k]) << i << " " << k;
  decodeBc1(three, false, out);  // BC1 RGB: the fourth colour is opaque black
  EXPECT_EQ(out[3][3], 255);
}

TEST(Ktx2, Bc4Bc5AndBc3ChannelsDecodeToTheirHandComputedRamps) {
  // 3-bit indices 0..7 for texels 0..7 and again for 8..15: 0o76543210 twice, 24 bits each.
  const uint8_t ramp[6] = {0x88, 0xC6, 0xFA, 0x88, 0xC6, 0xFA};
  uint8_t out[16][4];
  uint8_t bc4[8] = {200, 100};
  std::memcpy(bc4 + 2, ramp, 6);
  decodeBc4(bc4, out);
  // r0 > r1: r0, r1, then (6 r0 + r1) / 7 … (r0 + 6 r1) / 7, rounded.
  const int eight[8] = {200, 100, 186, 171, 157, 143, 129, 114};
  for (int i = 0; i < 16; ++i) {
    EXPECT_EQ(out[i][0], eight[i % 8]) << i;
    EXPECT_EQ(out[i][1], 0);
    EXPECT_EQ(out[i][3], 255);
  }
  uint8_t bc5[16] = {50, 150};
  std::memcpy(bc5 + 2, ramp, 6);
  bc5[8] = 200, bc5[9] = 100;
  std::memcpy(bc5 + 10, ramp, 6);
  decodeBc5(bc5, out);
  // r0 <= r1: r0, r1, four fifths between, then 0 and 255.
  const int six[8] = {50, 150, 70, 90, 110, 130, 0, 255};
  for (int i = 0; i < 16; ++i) {
    EXPECT_EQ(out[i][0], six[i % 8]) << i;
    EXPECT_EQ(out[i][1], eight[i % 8]) << i;
    EXPECT_EQ(out[i][2], 0);
  }
  // BC3: BC4-style alpha, and the colour block always in four-colour mode (even colour0 < colour1).
  uint8_t bc3[16] = {50, 150};
  std::memcpy(bc3 + 2, ramp, 6);
  const uint8_t colour[8] = {0x1F, 0x00, 0x00, 0xF8, 0xE4, 0xE4, 0xE4, 0xE4};
  std::memcpy(bc3 + 8, colour, 8);
  decodeBc3(bc3, out);
  EXPECT_EQ(out[2][0], 85);  // (2 blue + red) / 3, not the three-colour mode's midpoint
  EXPECT_EQ(out[3][3], 90);
  EXPECT_EQ(out[7][3], 255);
}

// A small BC1 encoder: endpoints at the block's colour box corners, each texel the nearest of the
// four palette colours. Enough to check that real encoded images decode to what was encoded.
std::vector<uint8_t> encodeBc1(const Image8& image) {
  std::vector<uint8_t> out;
  auto to565 = [](const int c[3]) { return uint16_t(((c[0] >> 3) << 11) | ((c[1] >> 2) << 5) | (c[2] >> 3)); };
  for (int by = 0; by < (image.height + 3) / 4; ++by)
    for (int bx = 0; bx < (image.width + 3) / 4; ++bx) {
      int lo[3] = {255, 255, 255}, hi[3] = {0, 0, 0};
      for (int t = 0; t < 16; ++t) {
        const uint8_t* p =
            image.pixel(std::min(bx * 4 + t % 4, image.width - 1), std::min(by * 4 + t / 4, image.height - 1));
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], int(p[k])), hi[k] = std::max(hi[k], int(p[k]));
      }
      uint16_t c0 = to565(hi), c1 = to565(lo);
      if (c0 == c1) c0 |= 0;  // a flat block: all indices 0
      if (c0 < c1) std::swap(c0, c1);
      uint8_t block[8] = {uint8_t(c0), uint8_t(c0 >> 8), uint8_t(c1), uint8_t(c1 >> 8), 0, 0, 0, 0};
      uint8_t palette[16][4];
      decodeBc1(block, false, palette);  // indices 0: palette[*] is colour 0; get all four below
      int colours[4][3];
      for (int e = 0; e < 4; ++e) {
        uint8_t probe[8];
        std::memcpy(probe, block, 4);
        std::memset(probe + 4, e * 0x55, 4);
        decodeBc1(probe, false, palette);
        for (int k = 0; k < 3; ++k) colours[e][k] = palette[0][k];
      }
      uint32_t indices = 0;
      for (int t = 0; t < 16; ++t) {
        const uint8_t* p =
            image.pixel(std::min(bx * 4 + t % 4, image.width - 1), std::min(by * 4 + t / 4, image.height - 1));
        int best = 0, bestError = INT32_MAX;
        for (int e = 0; e < 4; ++e) {
          int error = 0;
          for (int k = 0; k < 3; ++k) error += (p[k] - colours[e][k]) * (p[k] - colours[e][k]);
          if (error < bestError) best = e, bestError = error;
        }
        indices |= uint32_t(best) << (2 * t);
      }
      std::memcpy(block + 4, &indices, 4);
      out.insert(out.end(), block, block + 8);
    }
  return out;
}

TEST(Ktx2, Bc1EncodedGradientDecodesWithinTheFormatsPrecision) {
  // A gradient along x, every channel rising: each block's colours lie on its box diagonal, at 0,
  // 1/3, 2/3 and 1 of the way, which is BC1's palette, so only 5/6-bit endpoint rounding remains.
  Image8 image = Image8::make(10, 7);  // not a multiple of 4: edge blocks hang over
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      uint8_t* p = image.pixel(x, y);
      p[0] = uint8_t(x * 24), p[1] = uint8_t(x * 18 + 10 + y), p[2] = uint8_t(x * 9 + 40), p[3] = 255;
    }
  auto decoded = decode(writeKtx2({131, 10, 7}, encodeBc1(image)));
  ASSERT_TRUE(decoded.ok()) << decoded.error().message;
  ASSERT_EQ(decoded->width, 10);
  ASSERT_EQ(decoded->height, 7);
  int worst = 0;
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 10; ++x)
      for (int k = 0; k < 3; ++k)
        worst = std::max(worst, std::abs(int(decoded->pixel(x, y)[k]) - image.pixel(x, y)[k]));
  // 5-bit red and blue endpoints are within 4 levels, 6-bit green within 2, interpolation adds 1,
  // and green's y term (up to 6 levels inside a block) is off the diagonal: 4 + 1 + 3.
  EXPECT_LE(worst, 8);
}

// BC7 blocks from a small encoder: fields written in the specification's order, least
// significant bit first; the expected texels are computed by hand from its formulas.
class Bc7Writer {
 public:
  Bc7Writer& put(int value, int bits) {
    for (int i = 0; i < bits; ++i, ++at_)
      if ((value >> i) & 1) block[at_ >> 3] |= uint8_t(1 << (at_ & 7));
    return *this;
  }
  Bc7Writer& mode(int m) { return put(1 << m, m + 1); }
  uint8_t block[16] = {};

 private:
  int at_ = 0;
};

void expectTexel(const uint8_t out[16][4], int t, std::vector<int> rgba) {
  EXPECT_EQ((std::vector<int>{out[t][0], out[t][1], out[t][2], out[t][3]}), rgba) << "texel " << t;
}

TEST(Ktx2, Bc7ModesDecodeToTheirHandComputedTexels) {
  uint8_t out[16][4];
  {
    // Mode 6: one subset, 7-bit RGBA endpoints with a P-bit each, 4-bit indices (the anchor 3).
    Bc7Writer w;
    w.mode(6);
    for (int c : {10, 127}) w.put(c, 7);  // R of endpoint 0, 1
    for (int c : {20, 127}) w.put(c, 7);
    for (int c : {30, 127}) w.put(c, 7);
    for (int c : {127, 127}) w.put(c, 7);  // alpha
    w.put(0, 1).put(1, 1);                 // P-bits: endpoint 0 = (20, 40, 60, 254), endpoint 1 = 255
    for (int t = 0; t < 16; ++t) w.put(t, t == 0 ? 3 : 4);
    decodeBc7(w.block, out);
    expectTexel(out, 0, {20, 40, 60, 254});
    expectTexel(out, 15, {255, 255, 255, 255});
    // Index 5, weight 21: (43 e0 + 21 e1 + 32) >> 6.
    expectTexel(out, 5, {97, 111, 124, 254});
  }
  {
    // Mode 1, partition 0 (columns 2 and 3 are subset 1): subset 0 black, subset 1 white
    // (6 bits 63 and shared P-bit 1: 255); all indices 0.
    Bc7Writer w;
    w.mode(1).put(0, 6);
    for (int c = 0; c < 3; ++c) w.put(0, 6).put(0, 6).put(63, 6).put(63, 6);
    w.put(0, 1).put(1, 1);
    decodeBc7(w.block, out);
    expectTexel(out, 0, {0, 0, 0, 255});
    expectTexel(out, 2, {255, 255, 255, 255});
    expectTexel(out, 13, {0, 0, 0, 255});
    expectTexel(out, 15, {255, 255, 255, 255});
  }
  {
    // Mode 0, partition 0 of three subsets (rows 0011 0011 0221 2222): greys 1, 8 and 15 in 4 bits
    // with P-bits 0, 1, 1: (2 << 3) | (2 >> 2) = 16, (17 << 3) | (17 >> 2) = 140, 255.
    Bc7Writer w;
    w.mode(0).put(0, 4);
    for (int c = 0; c < 3; ++c) w.put(1, 4).put(1, 4).put(8, 4).put(8, 4).put(15, 4).put(15, 4);
    for (int p : {0, 0, 1, 1, 1, 1}) w.put(p, 1);
    decodeBc7(w.block, out);
    expectTexel(out, 0, {16, 16, 16, 255});
    expectTexel(out, 2, {140, 140, 140, 255});
    expectTexel(out, 9, {255, 255, 255, 255});
    expectTexel(out, 11, {140, 140, 140, 255});
  }
  {
    // Mode 5, rotation 2 (swap alpha and green): red 127 (7 bits: 255), alpha 100, indices 0.
    Bc7Writer w;
    w.mode(5).put(2, 2);
    w.put(127, 7).put(127, 7).put(0, 7).put(0, 7).put(0, 7).put(0, 7);
    w.put(100, 8).put(100, 8);
    decodeBc7(w.block, out);
    expectTexel(out, 7, {255, 100, 0, 0});
  }
  {
    // Mode 4, index selector 1: colour takes the 3-bit indices, alpha the 2-bit ones. Colour
    // 0 -> 31 (5 bits: 255), alpha 0 -> 63 (6 bits: 255); texel 1: 2-bit index 3, 3-bit index 2.
    Bc7Writer w;
    w.mode(4).put(0, 2).put(1, 1);
    for (int c = 0; c < 3; ++c) w.put(0, 5).put(31, 5);
    w.put(0, 6).put(63, 6);
    for (int t = 0; t < 16; ++t) w.put(t == 1 ? 3 : 0, t == 0 ? 1 : 2);
    for (int t = 0; t < 16; ++t) w.put(t == 1 ? 2 : 0, t == 0 ? 2 : 3);
    decodeBc7(w.block, out);
    // Colour: 3-bit index 2, weight 18: (18 × 255 + 32) >> 6 = 72; alpha: 2-bit index 3: 255.
    expectTexel(out, 1, {72, 72, 72, 255});
    expectTexel(out, 0, {0, 0, 0, 0});
  }
  const uint8_t reserved[16] = {};
  decodeBc7(reserved, out);
  expectTexel(out, 3, {0, 0, 0, 0});
  // Any 16 bytes are a block: decoding random ones reads nothing outside them.
  std::mt19937 rng(7);
  uint8_t random[16];
  for (int i = 0; i < 2000; ++i) {
    for (uint8_t& b : random) b = uint8_t(rng());
    decodeBc7(random, out);
  }
  // And through a KTX2 file (5 x 5: four blocks, three of them hanging over the edge).
  std::vector<uint8_t> blocks;
  for (int b = 0; b < 4; ++b) {
    Bc7Writer w;
    w.mode(6);
    for (int c = 0; c < 4; ++c) w.put(64 * (b % 2), 7).put(64 * (b % 2), 7);
    blocks.insert(blocks.end(), w.block, w.block + 16);
  }
  auto image = decode(writeKtx2({145, 5, 5}, blocks));
  ASSERT_TRUE(image.ok()) << image.error().message;
  EXPECT_EQ(pixel(*image, 0, 0), (std::vector<uint8_t>{0, 0, 0, 0}));
  // Block 3: every channel 64 in 7 bits with P-bit 0, 8 bits in all: 128.
  EXPECT_EQ(pixel(*image, 4, 4), (std::vector<uint8_t>{128, 128, 128, 128}));
}

TEST(Ktx2, MalformedFilesAreRefusedInOneLine) {
  const std::vector<uint8_t> good = writeKtx2({37, 2, 2}, std::vector<uint8_t>(16, 9));
  ASSERT_TRUE(decode(good).ok());
  expectRefused(decode({good.begin(), good.begin() + 50}), "truncated (50 bytes)");
  expectRefused(decode({good.begin(), good.end() - 3}), "level 0 (bytes");
  std::vector<uint8_t> pastEnd = good;
  pastEnd[80] = 0xF0;  // level 0's byteOffset far past the end
  expectRefused(decode(pastEnd), "lies outside the file");
  expectRefused(decode(writeKtx2({37, 2, 2}, std::vector<uint8_t>(12, 9))), "level 0 has 12 bytes");
  Ktx2Spec levels{37, 2, 2};
  levels.levelCount = 5;
  expectRefused(decode(writeKtx2(levels, std::vector<uint8_t>(16))), "levelCount 5 is more than a 2x2 texture has (2)");
  std::vector<uint8_t> shortIndex = writeKtx2(levels, {});
  shortIndex.resize(100);
  levels.levelCount = 2;
  std::vector<uint8_t> cutIndex = writeKtx2(levels, std::vector<uint8_t>(16));
  cutIndex.resize(110);
  expectRefused(decode(cutIndex), "level index (2 levels) runs past the end");
  expectRefused(decode(writeKtx2({37, 0, 2}, {})), "is 0x2");
  expectRefused(decode(writeKtx2({37, 100000, 2}, {})), "larger than Rayster accepts");
  Ktx2Spec cube{37, 2, 2};
  cube.faces = 6;
  expectRefused(decode(writeKtx2(cube, std::vector<uint8_t>(16))), "has 6 faces");
  Ktx2Spec array{37, 2, 2};
  array.layers = 3;
  expectRefused(decode(writeKtx2(array, std::vector<uint8_t>(16))), "array of 3 layers");
  expectRefused(decode(writeKtx2({147, 4, 4}, std::vector<uint8_t>(16))), "vkFormat 147 is not supported");
  expectRefused(decode(writeKtx2({145, 4, 4}, std::vector<uint8_t>(15))), "level 0 has 15 bytes");
  Ktx2Spec zlib{37, 2, 2};
  zlib.scheme = 3;
  expectRefused(decode(writeKtx2(zlib, std::vector<uint8_t>(16))), "supercompression scheme 3");
  expectRefused(decode(std::vector<uint8_t>(200, 0)), "identifier is missing");
}

TEST(Ktx2, BasisUniversalPayloadsAreRefusedNamingTheExtension) {
  Ktx2Spec etc1s{0, 4, 4};
  etc1s.scheme = 1;
  etc1s.colourModel = 163;
  expectRefused(decode(writeKtx2(etc1s, std::vector<uint8_t>(16))),
                "payload is Basis Universal ETC1S (BasisLZ) (KHR_texture_basisu)");
  Ktx2Spec uastc{0, 4, 4};
  uastc.colourModel = 166;
  expectRefused(decode(writeKtx2(uastc, std::vector<uint8_t>(16))), "payload is Basis Universal UASTC");
}

TEST(Ktx2, RandomCorruptionIsRefusedOrDecodedNeverACrash) {
  std::vector<uint8_t> raw(8 * 8 * 4, 77);
  std::vector<uint8_t> packed(ZSTD_compressBound(raw.size()));
  packed.resize(ZSTD_compress(packed.data(), packed.size(), raw.data(), raw.size(), 3));
  Ktx2Spec spec{37, 8, 8};
  spec.scheme = 2;
  spec.uncompressedLength = raw.size();
  const std::vector<std::vector<uint8_t>> bases = {writeKtx2(spec, packed),
                                                   writeKtx2({133, 8, 8}, std::vector<uint8_t>(32, 0xA5))};
  std::mt19937 rng(15);
  for (const auto& base : bases)
    for (int round = 0; round < 500; ++round) {
      std::vector<uint8_t> file = base;
      for (int k = 0; k < 3; ++k) file[rng() % file.size()] = uint8_t(rng());
      if (round % 5 == 0) file.resize(rng() % file.size());
      Result<Image8> image = decode(file);
      if (image.ok()) {
        EXPECT_EQ(image->rgba.size(), size_t(image->width) * size_t(image->height) * 4);
      }
    }
}

// ---- in glTF: KHR_texture_basisu with and without a fallback, and image/ktx2 as a plain image ----

std::vector<uint8_t> pngBytes(const TempDir& dir, uint8_t r, uint8_t g, uint8_t b) {
  Image8 image = Image8::make(2, 2);
  for (int i = 0; i < 4; ++i)
    image.rgba[size_t(i) * 4] = r, image.rgba[size_t(i) * 4 + 1] = g, image.rgba[size_t(i) * 4 + 2] = b,
                           image.rgba[size_t(i) * 4 + 3] = 255;
  const auto path = dir.path() / "fallback.png";
  EXPECT_TRUE(writePng(path, image).ok());
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

// The quad with a base colour texture: image 0 is a PNG (the fallback), image 1 a KTX2.
Doc texturedQuad(const TempDir& dir, const std::vector<uint8_t>& ktx2, bool withFallback, bool basisu = true) {
  Doc d = quadDoc();
  d.j["images"] = Json::array({{{"bufferView", d.view(pngBytes(dir, 0, 255, 0))}, {"mimeType", "image/png"}},
                               {{"bufferView", d.view(ktx2)}, {"mimeType", "image/ktx2"}}});
  Json texture = Json::object();
  if (basisu) {
    texture["extensions"]["KHR_texture_basisu"] = {{"source", 1}};
    if (withFallback) texture["source"] = 0;
    d.j["extensionsUsed"] = {"KHR_texture_basisu"};
    if (!withFallback) d.j["extensionsRequired"] = {"KHR_texture_basisu"};
  } else {
    texture["source"] = 1;
  }
  d.j["textures"] = Json::array({texture});
  d.j["materials"] =
      Json::array({{{"name", "paint"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  primitive(d)["material"] = 0;
  return d;
}

TEST(Ktx2, GltfTexturesReadKtx2ThroughBasisuOrAsAPlainImage) {
  TempDir dir;
  const std::vector<uint8_t> red = writeKtx2({43, 1, 1}, {255, 0, 0, 255});
  for (bool fallback : {true, false}) {
    auto scene = loadBytes(dir, texturedQuad(dir, red, fallback).glb(), "basisu.glb");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const scene::ImageData& image = scene->images.at(scene->textures.at(0).image);
    EXPECT_EQ(image.width, 1) << "the KTX2 image, not the 2x2 PNG fallback";
    EXPECT_EQ(image.rgba, (std::vector<uint8_t>{255, 0, 0, 255}));
  }
  auto plain = loadBytes(dir, texturedQuad(dir, red, false, false).gltf(), "plain.gltf");
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  EXPECT_EQ(plain->images.at(plain->textures.at(0).image).rgba, (std::vector<uint8_t>{255, 0, 0, 255}));
}

TEST(Ktx2, GltfBasisPayloadFallsBackToTheSourceOrIsRefused) {
  TempDir dir;
  Ktx2Spec uastc{0, 4, 4};
  uastc.colourModel = 166;
  const std::vector<uint8_t> basis = writeKtx2(uastc, std::vector<uint8_t>(16));
  auto fallback = loadBytes(dir, texturedQuad(dir, basis, true).glb(), "fallback.glb");
  ASSERT_TRUE(fallback.ok()) << fallback.error().message;
  const scene::ImageData& image = fallback->images.at(fallback->textures.at(0).image);
  EXPECT_EQ(image.width, 2) << "the PNG fallback";
  EXPECT_EQ(image.rgba[1], 255);
  auto refused = loadBytes(dir, texturedQuad(dir, basis, false).glb(), "basis.glb");
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("basis.glb: textures[0] KHR_texture_basisu image 1: KTX2 payload is Basis "
                                         "Universal UASTC (KHR_texture_basisu)"),
            std::string::npos)
      << refused.error().message;
  // A broken KTX2 used as a plain image is refused with the KTX2 cause too.
  auto broken = loadBytes(dir, texturedQuad(dir, writeKtx2({37, 2, 2}, {1, 2, 3}), false, false).glb(), "broken.glb");
  ASSERT_FALSE(broken.ok());
  EXPECT_NE(broken.error().message.find("textures[0] image 1: KTX2 level 0 has 3 bytes"), std::string::npos)
      << broken.error().message;
}

}  // namespace
}  // namespace rayster::test
