#pragma once
// Exposure (docs/techniques.md §20): fixed (--exposure EV, --ev100 N) or automatic (--exposure auto,
// the default) from a histogram of the scene's luminance, metered on the GPU every frame
// (render/passes/exposure.cpp) or on the host from the path tracer's mean. The exposure is applied
// where light enters the frame (pre-exposure, shaders/lib/frame.glsl), so the value chosen for a
// frame is also what every fp16 target and firefly clamp of that frame works relative to.
#include <cstdint>
#include <optional>
#include <span>

#include "render/renderer.h"

namespace rayster::scene {
struct Scene;
struct Camera;
}  // namespace rayster::scene

namespace rayster::render {

// The photographic relation (ISO 100, reflected-light meter constant K = 12.5, 1.2 headroom of the
// saturation-based sensor): a scene whose key luminance is L cd/m² has EV100 = log2(L · 100 / 12.5),
// and EV100 maps to the linear multiplier 1 / (1.2 · 2^EV100).
float ev100FromLuminance(float luminance);
float exposureFromEv100(float ev100);
float ev100FromExposure(float exposure);

// Auto exposure's range, and how much of the histogram it ignores at each end.
inline constexpr float kAutoEv100Min = -12.0f, kAutoEv100Max = 24.0f;
inline constexpr float kMeterIgnoreDark = 0.10f;    // of the non-black pixels: the darkest 10 %
inline constexpr float kMeterIgnoreBright = 0.05f;  // and the brightest 5 % (highlights, the sun)
// Adaptation rates (1/s) of EV += (target − EV)·(1 − e^(−Δt·rate)): the eye-like lag of a viewer
// or a sequence; a cut or the start of a shot snaps to the target.
inline constexpr float kAdaptTowardsDark = 3.0f, kAdaptTowardsBright = 1.5f;

// The EV100 the luminance histograms of a frame (shared/exposure.h: surfaces, then background)
// meter: the geometric mean of the pixels between the ignored ends, black ones left out, of the
// surfaces (or of everything, where surfaces cover less than kExposureMinSurface of the frame).
// Nothing lit: no reading.
std::optional<float> meterHistogram(std::span<const uint32_t> histograms);
// One step of temporal adaptation over `dtSeconds`.
float adaptEv100(float current, float target, float dtSeconds);
// A first guess before anything is metered, from the lights alone: the illuminance they give at the
// camera's target (suns, point and spot lights by the inverse square law, ambient and environment),
// seen on an 18 % grey surface. Scenes lit only by emission guess exposure 1 (EV100 ≈ −0.26).
float estimateEv100(const scene::Scene& scene, const scene::Camera& camera, float environmentIrradiance);

// The exposure of a run, frame by frame.
class ExposureControl {
 public:
  // Fixed modes take their value; auto starts from `guessEv100` unless it already metered a frame
  // (a restarted viewer run keeps its adapted exposure).
  void begin(const RenderSettings& s, float guessEv100);
  // The next begin() starts from its guess, as a new renderer's first run does (Renderer::restartHistories).
  void forget() { metered_ = false; }
  bool automatic() const { return mode_ == ExposureMode::Auto; }
  // This frame's exposure, and its ratio to the previous frame's (what histories written last
  // frame are multiplied by when read: FrameConstants::exposureRatio). Call once per frame.
  void beginFrame(bool cut);
  float exposure() const { return used_; }  // of the frame begun last (what its HDR images hold)
  float ratio() const { return ratio_; }
  float ev100() const { return ev100_; }
  // A frame's histogram (taken at exposure()): snaps the next frame's exposure to its reading or
  // adapts it towards it. Returns the reading's distance from the frame's exposure, in EV (0
  // without a reading).
  float meter(std::span<const uint32_t> bins, float dtSeconds, bool snap);

 private:
  ExposureMode mode_ = ExposureMode::Auto;
  float compensation_ = 0.0f;
  float ev100_ = 0.0f, exposure_ = 1.0f, used_ = 1.0f, ratio_ = 1.0f;
  bool metered_ = false;
};

}  // namespace rayster::render
