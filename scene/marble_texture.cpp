// A procedural marble for the Whitted scene's floor. The scene model has no procedural
// materials, so the marble is baked into a texture: Perlin's classic recipe (Perlin 1985),
// sin() veins displaced by turbulence, built on gradient noise that is periodic over the image
// so the texture tiles without seams.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include <glm/gtc/constants.hpp>

#include "scene/builtin_parts.h"

namespace rayster::scene::builtin {
namespace {

// Lattice cells across the image for the first octave: low enough for broad, slow veins.
constexpr int kBaseCells = 4;
constexpr int kOctaves = 6;
// How far turbulence pushes the veins, in radians of the vein sine: enough to make them wander,
// little enough that they stay long flowing lines (much more and they break into islands).
constexpr float kVeinWarp = 4.0f;
// Vein stripes across the image along u and v (integers, so the stripes tile too); the
// diagonal keeps them from reading as a regular pattern.
constexpr int kVeinsU = 2, kVeinsV = 3;
// Larger: thinner, sharper veins.
constexpr float kVeinSharpness = 10.0f;

// sRGB-encoded colours (the texture is sampled as sRGB): warm white stone, blue-grey veins.
constexpr glm::vec3 kStone{0.93f, 0.91f, 0.87f};
constexpr glm::vec3 kStoneShade{0.82f, 0.80f, 0.77f};
constexpr glm::vec3 kVein{0.38f, 0.40f, 0.45f};

uint32_t hash(uint32_t x, uint32_t y) {
  // A 2D integer hash (a lowbias32-style mix); quality matters more than speed here.
  uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u;
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return h;
}

// 16 unit gradients evenly around the circle: a table lookup instead of cos/sin per corner keeps
// the 1024^2 bake well under a second, and 16 directions show no visible axis bias.
const std::array<glm::vec2, 16> kGradients = [] {
  std::array<glm::vec2, 16> g{};
  for (size_t i = 0; i < g.size(); ++i) {
    const float a = glm::two_pi<float>() * (float(i) + 0.5f) / float(g.size());
    g[i] = glm::vec2(std::cos(a), std::sin(a));
  }
  return g;
}();

// Gradient (Perlin) noise in [-1, 1]-ish, periodic with `period` lattice cells in x and y.
float gradientNoise(float x, float y, int period) {
  const float fx = std::floor(x), fy = std::floor(y);
  const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);
  const float tx = x - fx, ty = y - fy;
  const auto corner = [&](int dx, int dy) {
    const auto wrap = [period](int i) { return static_cast<uint32_t>(((i % period) + period) % period); };
    const glm::vec2 g = kGradients[hash(wrap(ix + dx), wrap(iy + dy)) & 15u];
    return g.x * (tx - dx) + g.y * (ty - dy);
  };
  // Quintic fade: continuous second derivative, so no grid creases show in the veins.
  const auto fade = [](float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); };
  const float u = fade(tx), v = fade(ty);
  const float bottom = corner(0, 0) + (corner(1, 0) - corner(0, 0)) * u;
  const float top = corner(0, 1) + (corner(1, 1) - corner(0, 1)) * u;
  return (bottom + (top - bottom) * v) * 1.41421356f;  // gradient noise peaks at ~1/sqrt(2)
}

// Perlin's turbulence: a sum of |noise| octaves, each twice the frequency and half the weight.
float turbulence(float u, float v) {
  float sum = 0.0f, weight = 0.5f;
  int cells = kBaseCells;
  for (int o = 0; o < kOctaves; ++o, cells *= 2, weight *= 0.5f)
    sum += weight * std::fabs(gradientNoise(u * cells, v * cells, cells));
  return sum;
}

uint8_t toByte(float x) { return static_cast<uint8_t>(std::clamp(x, 0.0f, 1.0f) * 255.0f + 0.5f); }

}  // namespace

ImageData makeMarbleImage(int size) {
  RAYSTER_ASSERT(size > 0, "marble image needs a positive size");
  ImageData img;
  img.name = "marble";
  img.width = img.height = size;
  img.rgba.resize(size_t(size) * size_t(size) * 4);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float u = (x + 0.5f) / size, v = (y + 0.5f) / size;
      const float phase = glm::two_pi<float>() * (kVeinsU * u + kVeinsV * v) + kVeinWarp * turbulence(u, v);
      const float closeness = 1.0f - std::fabs(std::sin(phase));
      // A sharp dark core plus a faint wide halo, as mineral veins bleed into the stone.
      const float vein = 0.8f * std::pow(closeness, kVeinSharpness) + 0.12f * closeness * closeness;
      // Broad cloudy shading in the stone itself, from the low octaves only.
      const float cloud = 0.5f + 0.5f * gradientNoise(u * kBaseCells * 2, v * kBaseCells * 2, kBaseCells * 2);
      const glm::vec3 stone = kStoneShade + (kStone - kStoneShade) * cloud;
      const glm::vec3 colour = stone + (kVein - stone) * vein;
      uint8_t* px = &img.rgba[(size_t(y) * size + x) * 4];
      px[0] = toByte(colour.r);
      px[1] = toByte(colour.g);
      px[2] = toByte(colour.b);
      px[3] = 255;
    }
  }
  return img;
}

}  // namespace rayster::scene::builtin
