// The environment: an equirectangular HDR map in the bindless array (or the procedural sky), and
// its diffuse irradiance as cosine-convolved order-2 spherical harmonics (Ramamoorthi & Hanrahan
// 2001), projected here on the CPU once per scene.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/half.h"
#include "render/dfg.h"
#include "render/gpu_scene.h"
#include "rhi/context.h"
#include "rhi/resources.h"
#include "rhi/upload.h"
#include "shaders/shared/sheen.h"
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

// The environment (without its intensity) on an equirect grid of w × w/2 texel centres: the map
// box-filtered down, or the sky evaluated.
std::vector<glm::vec3> environmentGrid(const scene::Environment& env, uint32_t w) {
  const uint32_t h = w / 2;
  std::vector<glm::vec3> grid(size_t(w) * h, glm::vec3(0.0f));
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      glm::vec3& out = grid[size_t(y) * w + x];
      if (env.kind == scene::Environment::Kind::Sky) {
        out = skyRadiance(env, equirectDirection((x + 0.5f) / w, (y + 0.5f) / h));
        continue;
      }
      const uint32_t x0 = x * env.width / w, x1 = std::max(x0 + 1, (x + 1) * env.width / w);
      const uint32_t y0 = y * env.height / h, y1 = std::max(y0 + 1, (y + 1) * env.height / h);
      for (uint32_t sy = y0; sy < y1; ++sy)
        for (uint32_t sx = x0; sx < x1; ++sx) {
          const size_t i = (size_t(sy) * env.width + sx) * 3;
          out += glm::vec3(env.rgb[i], env.rgb[i + 1], env.rgb[i + 2]);
        }
      out /= float((x1 - x0) * (y1 - y0));
    }
  return grid;
}

// GGX-prefiltered environment (split sum, Karis 2013, with n = v = the lookup direction): level k
// of gpu::kPrefilteredLevels is roughness k/N, each a kPrefilteredWidth-wide equirect, stacked
// vertically. Brute-force quadrature over a coarse grid: the smooth lobes need no more, and the
// narrow ones blend with the exact environment (roughness 0) in the shader.
std::vector<uint16_t> prefilterEnvironment(const scene::Environment& env) {
  const uint32_t w = gpu::kPrefilteredWidth, h = w / 2, levels = gpu::kPrefilteredLevels;
  struct Source {
    std::vector<glm::vec3> radiance, dir;
    std::vector<float> dOmega;
  };
  auto makeSource = [&](uint32_t sw) {
    Source s;
    s.radiance = environmentGrid(env, sw);
    const uint32_t sh = sw / 2;
    for (uint32_t y = 0; y < sh; ++y)
      for (uint32_t x = 0; x < sw; ++x) {
        const float u = (x + 0.5f) / sw, v = (y + 0.5f) / sh;
        s.dir.push_back(equirectDirection(u, v));
        s.dOmega.push_back((2.0f * kPi / sw) * (kPi / sh) * std::sin(v * kPi));
      }
    return s;
  };
  // Rough lobes are wide: a coarser source integrates them as well, four times faster.
  const Source fine = makeSource(w), coarse = makeSource(w / 2);
  std::vector<uint16_t> halves(size_t(w) * h * levels * 4);
  for (uint32_t level = 1; level <= levels; ++level) {
    const float roughness = float(level) / float(levels), a2 = std::pow(roughness, 4.0f);
    const Source& src = level <= 2 ? fine : coarse;
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) {
        const glm::vec3 r = equirectDirection((x + 0.5f) / w, (y + 0.5f) / h);
        glm::vec3 sum(0.0f);
        float weightSum = 0.0f;
        for (size_t i = 0; i < src.dir.size(); ++i) {
          const float nl = glm::dot(r, src.dir[i]);
          if (nl <= 0.0f) continue;
          const float nh2 = 0.5f * (1.0f + nl);  // (n·h)² with h halfway between n and l
          const float denom = nh2 * (a2 - 1.0f) + 1.0f;
          const float weight = a2 / (denom * denom) * nl * src.dOmega[i];
          sum += src.radiance[i] * weight;
          weightSum += weight;
        }
        const glm::vec3 value = weightSum > 0.0f ? sum / weightSum : glm::vec3(0.0f);
        const size_t o = ((size_t(level - 1) * h + y) * w + x) * 4;
        for (int c = 0; c < 3; ++c) halves[o + c] = floatToHalf(std::min(value[c], 65000.0f));
        halves[o + 3] = floatToHalf(1.0f);
      }
  }
  return halves;
}

}  // namespace

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
  gs.environmentCdf = rhi::createBufferWithData(ctx, std::as_bytes(std::span(cdf)), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                "environment-cdf");
  if (out.kind == gpu::kEnvironmentBlack) return;
  const std::vector<uint16_t> levels = prefilterEnvironment(env);
  gs.environmentPrefiltered = rhi::uploadImage(ctx,
                                               {VK_FORMAT_R16G16B16A16_SFLOAT, gpu::kPrefilteredWidth,
                                                gpu::kPrefilteredWidth / 2 * gpu::kPrefilteredLevels, 1, 0},
                                               std::as_bytes(std::span(levels)), false, "environment-prefiltered");
  // Longitude wraps; the shader keeps latitude inside each level.
  gs.samplers.emplace_back(ctx, VK_FILTER_LINEAR, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT,
                           VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, false);
  out.prefilteredSlot = gs.bindless->add(gs.environmentPrefiltered.view(), gs.samplers.back().handle());
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
  // The sheen albedo table (shaders/shared/sheen.h) beside it, with the same linear clamped sampler:
  // its filter is the table's bilinear interpolation.
  std::vector<uint16_t> sheen;
  for (float e : gpu::kSheenAlbedo) sheen.push_back(floatToHalf(e));
  gs.sheenTable = rhi::uploadImage(ctx, {VK_FORMAT_R16_SFLOAT, gpu::kSheenTableSize, gpu::kSheenTableSize, 1, 0},
                                   std::as_bytes(std::span(sheen)), false, "sheen-albedo-table");
  gs.sheenSlot = gs.bindless->add(gs.sheenTable.view(), gs.samplers.back().handle());
}

}  // namespace rayster::render
