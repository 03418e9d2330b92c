// The environment: an equirectangular HDR map in the bindless array (or the procedural sky), and
// its diffuse irradiance as cosine-convolved order-2 spherical harmonics (Ramamoorthi & Hanrahan
// 2001), projected here on the CPU once per scene.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/half.h"
#include "render/dfg.h"
#include "render/gpu_scene.h"
#include "rhi/upload.h"
#include "rhi/context.h"
#include "rhi/resources.h"
#include "shaders/shared/types.h"

namespace rayster::render {
namespace {

constexpr float kPi = 3.14159265358979f;

// Must match skyRadiance() in shaders/lib/environment.glsl.
glm::vec3 skyRadiance(const scene::Environment& e, glm::vec3 d) {
  if (d.y >= 0.0f) return glm::mix(e.horizon, e.zenith, std::sqrt(d.y));
  return glm::mix(e.horizon, e.ground, std::sqrt(std::min(-d.y * 4.0f, 1.0f)));
}

std::array<float, 9> shBasis(glm::vec3 d) {
  return {0.282095f,
          0.488603f * d.y,
          0.488603f * d.z,
          0.488603f * d.x,
          1.092548f * d.x * d.y,
          1.092548f * d.y * d.z,
          0.315392f * (3.0f * d.z * d.z - 1.0f),
          1.092548f * d.x * d.z,
          0.546274f * (d.x * d.x - d.y * d.y)};
}

// Direction of the centre of texel (x, y) of an equirect map; must match equirectUv() in GLSL.
glm::vec3 equirectDirection(float u, float v) {
  const float phi = (u - 0.5f) * 2.0f * kPi, theta = v * kPi;
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

// Cells of the importance-sampling distribution: the map's own resolution up to this (finer adds
// memory and search steps, not much variance reduction).
constexpr uint32_t kCdfMaxWidth = 512, kCdfMaxHeight = 256;
constexpr uint32_t kSkyCdfWidth = 64, kSkyCdfHeight = 32;  // the procedural sky is smooth

// A piecewise-constant distribution over w × h equirect cells ∝ luminance(radiance) × sinθ, laid out
// for shaders/lib/pt_lights.glsl: [cell probabilities (h×w)] [row CDFs (h×w, inclusive, each ends
// at 1)] [marginal CDF over rows (h, inclusive)]. `radiance(u, v)` is called at cell centres.
template <typename F>
std::vector<float> environmentCdf(uint32_t w, uint32_t h, F radiance) {
  std::vector<float> out(size_t(w) * h * 2 + h);
  float* prob = out.data();
  float* rows = prob + size_t(w) * h;
  float* marginal = rows + size_t(w) * h;
  std::vector<double> rowSum(h);
  double total = 0;
  for (uint32_t y = 0; y < h; ++y) {
    const float sinTheta = std::sin((y + 0.5f) / h * kPi);
    double sum = 0;
    for (uint32_t x = 0; x < w; ++x) {
      const glm::vec3 c = radiance((x + 0.5f) / w, (y + 0.5f) / h);
      // A small floor keeps every direction reachable (a black cell's light is still counted by BSDF rays).
      const double weight = (std::max(0.0f, 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z) + 1e-4) * sinTheta;
      sum += weight;
      rows[size_t(y) * w + x] = float(sum);
      prob[size_t(y) * w + x] = float(weight);
    }
    rowSum[y] = sum;
    total += sum;
  }
  double running = 0;
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      rows[size_t(y) * w + x] = rowSum[y] > 0 ? float(rows[size_t(y) * w + x] / rowSum[y]) : float(x + 1) / w;
      prob[size_t(y) * w + x] = float(prob[size_t(y) * w + x] / total);
    }
    rows[size_t(y) * w + w - 1] = 1.0f;
    running += rowSum[y];
    marginal[y] = float(running / total);
  }
  marginal[h - 1] = 1.0f;
  return out;
}

} // namespace

void uploadEnvironment(rhi::Context& ctx, const scene::Scene& scene, GpuScene& gs) {
  const scene::Environment& env = scene.environment;
  GpuEnvironment& out = gs.environment;
  out.kind = env.kind == scene::Environment::Kind::Map   ? gpu::kEnvironmentMap
             : env.kind == scene::Environment::Kind::Sky ? gpu::kEnvironmentSky
                                                         : gpu::kEnvironmentBlack;
  std::array<glm::vec3, 9> sh{};
  if (out.kind == gpu::kEnvironmentMap) {
    const uint32_t w = uint32_t(env.width), h = uint32_t(env.height);
    std::vector<uint16_t> halves(size_t(w) * h * 4);
    for (size_t i = 0; i < size_t(w) * h; ++i) {
      for (int c = 0; c < 3; ++c) halves[i * 4 + c] = floatToHalf(std::min(env.rgb[i * 3 + c], 65000.0f));
      halves[i * 4 + 3] = floatToHalf(1.0f);
    }
    gs.environmentMap = rhi::uploadImage(ctx, {VK_FORMAT_R16G16B16A16_SFLOAT, w, h, 1, 0},
                                         std::as_bytes(std::span(halves)), false, "environment");
    // Longitude wraps, latitude clamps at the poles.
    gs.samplers.emplace_back(ctx, VK_FILTER_LINEAR, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT,
                             VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, false);
    out.slot = gs.bindless->add(gs.environmentMap.view(), gs.samplers.back().handle());

    // Project at most ~256×128 texels: irradiance is smooth, more adds time, not accuracy.
    const uint32_t step = std::max(1u, std::max(w / 256, h / 128));
    double weightSum = 0;
    for (uint32_t y = 0; y < h; y += step)
      for (uint32_t x = 0; x < w; x += step) {
        const float u = (x + 0.5f) / w, v = (y + 0.5f) / h;
        const float dOmega = (2.0f * kPi * step / w) * (kPi * step / h) * std::sin(v * kPi);
        glm::vec3 d = equirectDirection(u, v);
        const size_t i = (size_t(y) * w + x) * 3;
        glm::vec3 radiance(env.rgb[i], env.rgb[i + 1], env.rgb[i + 2]);
        auto basis = shBasis(d);
        for (int k = 0; k < 9; ++k) sh[k] += radiance * (basis[k] * dOmega);
        weightSum += dOmega;
      }
    // Normalise the quadrature to exactly 4π so a constant map gives exactly its irradiance.
    for (auto& c : sh) c *= float(4.0 * kPi / weightSum);
  } else if (out.kind == gpu::kEnvironmentSky) {
    const int n = 64;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < 2 * n; ++x) {
        const float u = (x + 0.5f) / (2 * n), v = (y + 0.5f) / n;
        const float dOmega = (2.0f * kPi / (2 * n)) * (kPi / n) * std::sin(v * kPi);
        glm::vec3 d = equirectDirection(u, v);
        auto basis = shBasis(d);
        glm::vec3 radiance = skyRadiance(env, d);
        for (int k = 0; k < 9; ++k) sh[k] += radiance * (basis[k] * dOmega);
      }
  }
  // Convolve with the clamped cosine: A0 = π, A1 = 2π/3, A2 = π/4. Rotation about +Y is applied in
  // the shader to the lookup direction, so the map and its irradiance stay consistent.
  const float band[9] = {kPi, 2 * kPi / 3, 2 * kPi / 3, 2 * kPi / 3, kPi / 4, kPi / 4, kPi / 4, kPi / 4, kPi / 4};
  for (int k = 0; k < 9; ++k) out.irradianceSh[k] = sh[k] * band[k] * env.intensity;

  std::vector<float> cdf = {0.0f};  // a buffer must not be empty
  if (out.kind == gpu::kEnvironmentMap) {
    const uint32_t w = uint32_t(env.width), h = uint32_t(env.height);
    out.cdfWidth = std::min(w, kCdfMaxWidth);
    out.cdfHeight = std::min(h, kCdfMaxHeight);
    cdf = environmentCdf(out.cdfWidth, out.cdfHeight, [&](float u, float v) {
      const size_t i = (size_t(std::min(uint32_t(v * h), h - 1)) * w + std::min(uint32_t(u * w), w - 1)) * 3;
      return glm::vec3(env.rgb[i], env.rgb[i + 1], env.rgb[i + 2]);
    });
  } else if (out.kind == gpu::kEnvironmentSky) {
    out.cdfWidth = kSkyCdfWidth;
    out.cdfHeight = kSkyCdfHeight;
    cdf = environmentCdf(out.cdfWidth, out.cdfHeight,
                         [&](float u, float v) { return skyRadiance(env, equirectDirection(u, v)); });
  }
  gs.environmentCdf =
      rhi::createBufferWithData(ctx, std::as_bytes(std::span(cdf)), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "environment-cdf");
}

void uploadDfgTable(rhi::Context& ctx, GpuScene& gs) {
  const std::vector<glm::vec2> table = computeDfgTable();
  std::vector<uint16_t> halves;
  halves.reserve(table.size() * 2);
  for (glm::vec2 ab : table) {
    halves.push_back(floatToHalf(ab.x));
    halves.push_back(floatToHalf(ab.y));
  }
  gs.dfgTable = rhi::uploadImage(ctx, {VK_FORMAT_R16G16_SFLOAT, kDfgSize, kDfgSize, 1, 0},
                                 std::as_bytes(std::span(halves)), false, "dfg-table");
  gs.samplers.emplace_back(ctx, VK_FILTER_LINEAR, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                           VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, false);
  gs.dfgSlot = gs.bindless->add(gs.dfgTable.view(), gs.samplers.back().handle());
}

} // namespace rayster::render
