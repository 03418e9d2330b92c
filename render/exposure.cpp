#include "render/exposure.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>

#include "scene/scene.h"
#include "shaders/shared/exposure.h"

namespace rayster::render {

namespace {
constexpr float kMeterK = 12.5f;      // reflected-light meter calibration
constexpr float kSaturation = 1.2f;   // headroom of the saturation-based exposure
constexpr float kGreyAlbedo = 0.18f;  // what the first guess assumes every surface reflects
float luminanceOf(glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }
// The log2 luminance at the centre of bin b (1 .. kExposureBins − 1).
float binLog2(uint32_t b) {
  return gpu::kExposureMinLog2 +
         float(b - 1) / float(gpu::kExposureBins - 2) * (gpu::kExposureMaxLog2 - gpu::kExposureMinLog2);
}
}  // namespace

float ev100FromLuminance(float luminance) { return std::log2(luminance * 100.0f / kMeterK); }
float exposureFromEv100(float ev100) { return 1.0f / (kSaturation * std::exp2(ev100)); }
float ev100FromExposure(float exposure) { return -std::log2(kSaturation * exposure); }

std::optional<float> meterHistogram(std::span<const uint32_t> histograms) {
  const size_t n = gpu::kExposureBins;
  std::vector<double> bins(n, 0.0);
  double surface = 0, all = 0;
  for (size_t i = 0; i < histograms.size(); ++i) {
    all += histograms[i];
    if (i < n) surface += histograms[i];
  }
  const bool surfacesOnly = surface >= gpu::kExposureMinSurface * all;
  for (size_t i = 0; i < histograms.size(); ++i)
    if (i < n || !surfacesOnly) bins[i % n] += histograms[i];
  double lit = 0;
  for (size_t b = 1; b < n; ++b) lit += bins[b];
  if (lit <= 0) return std::nullopt;
  // Keep the pixels whose rank lies in [lo, hi): partial bins count by the part inside.
  const double lo = kMeterIgnoreDark * lit, hi = (1.0 - kMeterIgnoreBright) * lit;
  double rank = 0, weight = 0, sum = 0;
  for (size_t b = 1; b < n; ++b) {
    const double from = rank, to = rank + bins[b];
    rank = to;
    const double kept = std::max(0.0, std::min(to, hi) - std::max(from, lo));
    weight += kept;
    sum += kept * binLog2(uint32_t(b));
  }
  if (weight <= 0) return std::nullopt;
  const float ev = ev100FromLuminance(float(std::exp2(sum / weight)));
  return std::clamp(ev, kAutoEv100Min, kAutoEv100Max);
}

float adaptEv100(float current, float target, float dtSeconds) {
  const float rate = target < current ? kAdaptTowardsDark : kAdaptTowardsBright;
  return current + (target - current) * (1.0f - std::exp(-dtSeconds * rate));
}

float estimateEv100(const scene::Scene& scene, const scene::Camera& camera, float environmentIrradiance) {
  const scene::Aabb b = scene.bounds();
  const float minDistance = b.valid() ? 0.05f * glm::length(b.max - b.min) : 0.1f;
  double illuminance = environmentIrradiance + glm::pi<float>() * luminanceOf(scene.ambient);
  for (const scene::Light& l : scene.lights) {
    const float power = l.intensity * luminanceOf(l.color);
    if (l.type == scene::LightType::Directional) {
      illuminance += power;
    } else {
      const float d = std::max(glm::length(l.position - camera.target), minDistance);
      illuminance += power / (d * d);
    }
  }
  if (!(illuminance > 0.0)) return ev100FromExposure(1.0f);
  return std::clamp(ev100FromLuminance(float(kGreyAlbedo * illuminance / glm::pi<double>())), kAutoEv100Min,
                    kAutoEv100Max);
}

void ExposureControl::begin(const RenderSettings& s, float guessEv100) {
  const bool wasMetered = metered_ && mode_ == ExposureMode::Auto;
  mode_ = s.exposureMode;
  compensation_ = s.exposureCompensation;
  switch (mode_) {
    case ExposureMode::Ev:
      exposure_ = std::exp2(s.exposureEv);
      ev100_ = ev100FromExposure(exposure_);
      break;
    case ExposureMode::Ev100:
      ev100_ = s.ev100;
      exposure_ = exposureFromEv100(ev100_);
      break;
    case ExposureMode::Auto:
      if (!wasMetered) {
        ev100_ = guessEv100;
        metered_ = false;
      }
      exposure_ = exposureFromEv100(ev100_ - compensation_);
      break;
  }
  used_ = exposure_;
  ratio_ = 1.0f;
}

void ExposureControl::beginFrame(bool cut) {
  ratio_ = cut ? 1.0f : exposure_ / used_;
  used_ = exposure_;
}

float ExposureControl::meter(std::span<const uint32_t> bins, float dtSeconds, bool snap) {
  if (mode_ != ExposureMode::Auto) return 0.0f;
  const std::optional<float> target = meterHistogram(bins);
  if (!target) return 0.0f;
  const float distance = std::abs(*target - compensation_ - ev100FromExposure(used_));
  ev100_ = snap || !metered_ ? *target : adaptEv100(ev100_, *target, dtSeconds);
  metered_ = true;
  exposure_ = exposureFromEv100(ev100_ - compensation_);
  return distance;
}

}  // namespace rayster::render
