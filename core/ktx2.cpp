// KTX 2.0 reader (https://registry.khronos.org/KTX/specs/2.0/ktxspec.v2.html): the header, the
// level index and level 0, checked against each other and the file's size before any read.
#include "core/ktx2.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include <zstd.h>

#include "core/bcn.h"

namespace rayster {
namespace {

constexpr uint8_t kIdentifier[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
constexpr size_t kHeaderBytes = 80;  // identifier, 9 header words, the index (4 words and 2 longs)
constexpr size_t kLevelEntryBytes = 24;

// Supercompression schemes.
constexpr uint32_t kNone = 0, kBasisLz = 1, kZstd = 2, kZlib = 3;
// Data Format Descriptor colour models of Basis Universal payloads.
constexpr uint8_t kModelEtc1s = 163, kModelUastc = 166;

Error ktxError(std::string message) { return Error{ExitCode::BadInput, "KTX2 " + std::move(message)}; }

uint32_t u32(const uint8_t* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}
uint64_t u64(const uint8_t* p) {
  uint64_t v;
  std::memcpy(&v, p, 8);
  return v;
}

enum class Kind { Plain, Half, Bc1, Bc1Alpha, Bc3, Bc4, Bc5, Bc7 };

struct Format {
  Kind kind = Kind::Plain;
  int channels = 0;       // Plain: bytes per texel (1-4); Half: 4 channels of 2 bytes
  bool bgr = false;       // Plain: stored B, G, R(, A)
  size_t blockBytes = 0;  // BCn: bytes per 4 × 4 block
};

std::optional<Format> formatOf(uint32_t vkFormat) {
  switch (vkFormat) {
    case 9:   // R8_UNORM
    case 15:  // R8_SRGB
      return Format{Kind::Plain, 1};
    case 16:  // R8G8_UNORM
    case 22:  // R8G8_SRGB
      return Format{Kind::Plain, 2};
    case 23:  // R8G8B8_UNORM
    case 29:  // R8G8B8_SRGB
      return Format{Kind::Plain, 3};
    case 30:  // B8G8R8_UNORM
    case 36:  // B8G8R8_SRGB
      return Format{Kind::Plain, 3, true};
    case 37:  // R8G8B8A8_UNORM
    case 43:  // R8G8B8A8_SRGB
      return Format{Kind::Plain, 4};
    case 44:  // B8G8R8A8_UNORM
    case 50:  // B8G8R8A8_SRGB
      return Format{Kind::Plain, 4, true};
    case 97:  // R16G16B16A16_SFLOAT
      return Format{Kind::Half, 4};
    case 131:  // BC1_RGB_UNORM_BLOCK
    case 132:  // BC1_RGB_SRGB_BLOCK
      return Format{Kind::Bc1, 0, false, 8};
    case 133:  // BC1_RGBA_UNORM_BLOCK
    case 134:  // BC1_RGBA_SRGB_BLOCK
      return Format{Kind::Bc1Alpha, 0, false, 8};
    case 137:  // BC3_UNORM_BLOCK
    case 138:  // BC3_SRGB_BLOCK
      return Format{Kind::Bc3, 0, false, 16};
    case 139:  // BC4_UNORM_BLOCK
      return Format{Kind::Bc4, 0, false, 8};
    case 141:  // BC5_UNORM_BLOCK
      return Format{Kind::Bc5, 0, false, 16};
    case 145:  // BC7_UNORM_BLOCK
    case 146:  // BC7_SRGB_BLOCK
      return Format{Kind::Bc7, 0, false, 16};
    default:
      return std::nullopt;
  }
}

float halfToFloat(uint16_t h) {
  const int exponent = (h >> 10) & 31, mantissa = h & 1023;
  const float sign = (h & 0x8000) ? -1.0f : 1.0f;
  if (exponent == 0) return sign * std::ldexp(float(mantissa), -24);
  if (exponent == 31) return mantissa ? NAN : sign * INFINITY;
  return sign * std::ldexp(float(mantissa | 1024), exponent - 25);
}

uint8_t unorm8(float v) {
  if (!(v > 0.0f)) return 0;  // NaN and negatives
  if (v >= 1.0f) return 255;
  return uint8_t(std::lround(v * 255.0f));
}

void decodePlain(const uint8_t* src, const Format& f, Image8& image) {
  const size_t texels = size_t(image.width) * size_t(image.height);
  for (size_t i = 0; i < texels; ++i) {
    uint8_t* out = image.rgba.data() + 4 * i;
    if (f.kind == Kind::Half) {
      for (int k = 0; k < 4; ++k) {
        uint16_t h;
        std::memcpy(&h, src + 8 * i + 2 * size_t(k), 2);
        out[k] = unorm8(halfToFloat(h));
      }
      continue;
    }
    const uint8_t* in = src + size_t(f.channels) * i;
    out[0] = out[1] = out[2] = 0;  // as Vulkan samples absent channels
    out[3] = 255;
    for (int k = 0; k < f.channels; ++k) out[k] = in[k];
    if (f.bgr) std::swap(out[0], out[2]);
  }
}

void decodeBlocks(const uint8_t* src, const Format& f, Image8& image) {
  const int bw = (image.width + 3) / 4, bh = (image.height + 3) / 4;
  uint8_t texels[16][4];
  for (int by = 0; by < bh; ++by)
    for (int bx = 0; bx < bw; ++bx) {
      const uint8_t* block = src + (size_t(by) * size_t(bw) + size_t(bx)) * f.blockBytes;
      switch (f.kind) {
        case Kind::Bc1:
        case Kind::Bc1Alpha:
          decodeBc1(block, f.kind == Kind::Bc1Alpha, texels);
          break;
        case Kind::Bc3:
          decodeBc3(block, texels);
          break;
        case Kind::Bc4:
          decodeBc4(block, texels);
          break;
        case Kind::Bc5:
          decodeBc5(block, texels);
          break;
        default:
          decodeBc7(block, texels);
          break;
      }
      // Blocks on the right and bottom edges may hang over the image: their extra texels are dropped.
      for (int y = 0; y < 4 && by * 4 + y < image.height; ++y)
        for (int x = 0; x < 4 && bx * 4 + x < image.width; ++x)
          std::memcpy(image.pixel(bx * 4 + x, by * 4 + y), texels[y * 4 + x], 4);
    }
}

// What level 0 of a `width` × `height` texture of format `f` takes, in bytes.
uint64_t levelBytes(const Format& f, uint32_t width, uint32_t height) {
  if (f.blockBytes) return uint64_t((width + 3) / 4) * uint64_t((height + 3) / 4) * f.blockBytes;
  return uint64_t(width) * height * (f.kind == Kind::Half ? 8u : uint64_t(f.channels));
}

std::string basisRefusal(const char* payload) {
  return fmt::format(
      "payload is Basis Universal {} (KHR_texture_basisu); Rayster has no Basis transcoder (none is packaged in "
      "Debian): re-encode the texture as BC7 or uncompressed KTX2, or PNG",
      payload);
}

}  // namespace

bool isKtx2(std::span<const uint8_t> bytes) {
  return bytes.size() >= sizeof kIdentifier && std::memcmp(bytes.data(), kIdentifier, sizeof kIdentifier) == 0;
}

Result<Image8> decodeKtx2(std::span<const uint8_t> bytes, int maxSide) {
  if (!isKtx2(bytes)) return ktxError("identifier is missing (not a KTX 2.0 file)");
  if (bytes.size() < kHeaderBytes) return ktxError(fmt::format("file is truncated ({} bytes)", bytes.size()));
  const uint8_t* p = bytes.data();
  const uint32_t vkFormat = u32(p + 12), width = u32(p + 20), height = u32(p + 24), depth = u32(p + 28),
                 layers = u32(p + 32), faces = u32(p + 36), levelCount = u32(p + 40), scheme = u32(p + 44);
  const uint32_t dfdOffset = u32(p + 48), dfdLength = u32(p + 52);
  if (width == 0 || height == 0) return ktxError(fmt::format("is {}x{}: 1D textures are not images", width, height));
  if (width > uint32_t(maxSide) || height > uint32_t(maxSide))
    return ktxError(fmt::format("is {}x{}, larger than Rayster accepts ({} per side)", width, height, maxSide));
  if (depth > 1) return ktxError(fmt::format("is a 3D texture (depth {})", depth));
  if (layers > 1) return ktxError(fmt::format("is an array of {} layers; a glTF image is one", layers));
  if (faces != 1) return ktxError(fmt::format("has {} faces; a glTF image is one (not a cube map)", faces));
  const uint32_t maxLevels = 1 + uint32_t(std::floor(std::log2(double(std::max(width, height)))));
  if (levelCount > maxLevels)
    return ktxError(
        fmt::format("levelCount {} is more than a {}x{} texture has ({})", levelCount, width, height, maxLevels));
  const size_t levels = std::max<uint32_t>(levelCount, 1);
  if (bytes.size() < kHeaderBytes + levels * kLevelEntryBytes)
    return ktxError(fmt::format("level index ({} levels) runs past the end of the file", levels));

  // Basis Universal first: its payloads have no Vulkan format (ETC1S, UASTC) or BasisLZ.
  uint8_t colourModel = 0;
  if (dfdLength >= 16 && uint64_t(dfdOffset) + dfdLength <= bytes.size()) colourModel = p[dfdOffset + 12];
  if (scheme == kBasisLz || colourModel == kModelEtc1s) return ktxError(basisRefusal("ETC1S (BasisLZ)"));
  if (colourModel == kModelUastc) return ktxError(basisRefusal("UASTC"));
  const std::optional<Format> format = formatOf(vkFormat);
  if (!format)
    return ktxError(fmt::format(
        "vkFormat {} is not supported (Rayster reads 8-bit R/RG/RGB/RGBA/BGR/BGRA, RGBA16F, BC1, BC3, BC4, BC5, BC7)",
        vkFormat));
  if (scheme != kNone && scheme != kZstd)
    return ktxError(fmt::format("supercompression scheme {} is not supported (none or Zstandard){}", scheme,
                                scheme == kZlib ? ": zlib" : ""));

  const uint8_t* entry = p + kHeaderBytes;  // level 0, the largest
  const uint64_t offset = u64(entry), length = u64(entry + 8), uncompressed = u64(entry + 16);
  if (offset > bytes.size() || length > bytes.size() - offset)
    return ktxError(fmt::format("level 0 (bytes {} to {}) lies outside the file ({} bytes)", offset, offset + length,
                                bytes.size()));
  const uint64_t expected = levelBytes(*format, width, height);
  Image8 image = Image8::make(int(width), int(height));
  std::vector<uint8_t> inflated;
  const uint8_t* level = p + offset;
  if (scheme == kNone) {
    if (length != expected)
      return ktxError(fmt::format("level 0 has {} bytes, a {}x{} texture of vkFormat {} needs {}", length, width,
                                  height, vkFormat, expected));
  } else {
    if (uncompressed != expected)
      return ktxError(fmt::format("level 0 uncompressedByteLength {} is not the {} bytes a {}x{} texture needs",
                                  uncompressed, expected, width, height));
    inflated.resize(size_t(expected));
    const size_t got = ZSTD_decompress(inflated.data(), inflated.size(), level, size_t(length));
    if (ZSTD_isError(got)) return ktxError(fmt::format("level 0 zstd data is invalid: {}", ZSTD_getErrorName(got)));
    if (got != expected) return ktxError(fmt::format("level 0 zstd data inflates to {} bytes, not {}", got, expected));
    level = inflated.data();
  }
  if (format->blockBytes)
    decodeBlocks(level, *format, image);
  else
    decodePlain(level, *format, image);
  return image;
}

}  // namespace rayster
