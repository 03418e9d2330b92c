#include "core/image.h"

#include <cstddef>

#include "core/error.h"

namespace rayster {
namespace {
size_t offsetOf(int width, int height, int x, int y) {
  // Out-of-range access is a programmer error; checking here keeps it from corrupting memory.
  RAYSTER_ASSERT(x >= 0 && y >= 0 && x < width && y < height, "pixel out of range");
  return (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4;
}
}  // namespace

float* ImageF::pixel(int x, int y) { return rgba.data() + offsetOf(width, height, x, y); }
const float* ImageF::pixel(int x, int y) const { return rgba.data() + offsetOf(width, height, x, y); }

ImageF ImageF::make(int w, int h) {
  RAYSTER_ASSERT(w >= 0 && h >= 0, "negative image size");
  ImageF image;
  image.width = w;
  image.height = h;
  image.rgba.assign(static_cast<size_t>(w) * static_cast<size_t>(h) * 4, 0.0f);
  return image;
}

uint8_t* Image8::pixel(int x, int y) { return rgba.data() + offsetOf(width, height, x, y); }
const uint8_t* Image8::pixel(int x, int y) const { return rgba.data() + offsetOf(width, height, x, y); }

Image8 Image8::make(int w, int h) {
  RAYSTER_ASSERT(w >= 0 && h >= 0, "negative image size");
  Image8 image;
  image.width = w;
  image.height = h;
  image.rgba.assign(static_cast<size_t>(w) * static_cast<size_t>(h) * 4, 0);
  return image;
}

}  // namespace rayster
