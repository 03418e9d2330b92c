#pragma once
// Writes KTX2 files in tests (tests/unit/test_ktx2.cpp, tests/render/test_transform_corpus.cpp).
#include <algorithm>
#include <cstdint>
#include <optional>
#include <vector>

namespace rayster::test {

struct Ktx2Spec {
  uint32_t vkFormat = 37;
  uint32_t width = 1, height = 1, depth = 0, layers = 0, faces = 1, levelCount = 1, scheme = 0;
  uint8_t colourModel = 1;                     // KHR_DF_MODEL_RGBSDA
  std::optional<uint64_t> uncompressedLength;  // default: the payload's size (scheme 0) or given
};

inline void put32(std::vector<uint8_t>& out, uint32_t v) {
  out.insert(out.end(), {uint8_t(v), uint8_t(v >> 8), uint8_t(v >> 16), uint8_t(v >> 24)});
}
inline void put64(std::vector<uint8_t>& out, uint64_t v) {
  put32(out, uint32_t(v));
  put32(out, uint32_t(v >> 32));
}

// A KTX2 file: header, index, level index (level 0 real, smaller levels empty), a minimal DFD
// (the basic block's header, no samples) and the level 0 payload.
inline std::vector<uint8_t> writeKtx2(const Ktx2Spec& s, const std::vector<uint8_t>& payload) {
  std::vector<uint8_t> out = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
  for (uint32_t v : {s.vkFormat, 1u, s.width, s.height, s.depth, s.layers, s.faces, s.levelCount, s.scheme})
    put32(out, v);
  const uint32_t levels = std::max(s.levelCount, 1u);
  const uint32_t dfdOffset = 80 + 24 * levels, dfdLength = 28;
  put32(out, dfdOffset);
  put32(out, dfdLength);
  put32(out, 0);  // no key/value data
  put32(out, 0);
  put64(out, 0);  // no supercompression global data
  put64(out, 0);
  const uint64_t dataOffset = dfdOffset + dfdLength;
  for (uint32_t l = 0; l < levels; ++l) {
    put64(out, l == 0 ? dataOffset : dataOffset + payload.size());
    put64(out, l == 0 ? payload.size() : 0);
    put64(out, l == 0 ? s.uncompressedLength.value_or(payload.size()) : 0);
  }
  put32(out, dfdLength);
  put32(out, 0);                 // vendor 0 (Khronos), descriptor type 0 (basic)
  put32(out, 2u | (24u << 16));  // version 2, block size 24
  out.insert(out.end(), {s.colourModel, 1, 2, 0});
  put32(out, 0);
  put64(out, 0);
  out.insert(out.end(), payload.begin(), payload.end());
  return out;
}

}  // namespace rayster::test
