#pragma once
// CPU images: what the renderer reads back from the GPU and what tests and `rayster compare`
// look at. Always RGBA, row-major, top row first, so a pixel index never needs a channel count.
#include <cstdint>
#include <vector>

namespace rayster {

// Linear radiance (or any float AOV), 4 floats per pixel.
struct ImageF {
  int width = 0, height = 0;
  std::vector<float> rgba;

  float* pixel(int x, int y);
  const float* pixel(int x, int y) const;
  bool empty() const { return width <= 0 || height <= 0; }
  static ImageF make(int w, int h);  // zero-filled
};

// Display-referred 8-bit image (sRGB-encoded when it came from writeImage/readPng), 4 bytes per pixel.
struct Image8 {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;

  uint8_t* pixel(int x, int y);
  const uint8_t* pixel(int x, int y) const;
  bool empty() const { return width <= 0 || height <= 0; }
  static Image8 make(int w, int h);  // zero-filled
};

}  // namespace rayster
