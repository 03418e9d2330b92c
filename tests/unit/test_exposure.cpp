// Auto exposure's host side (render/exposure.h): the photographic relations, the meter's reading of
// a histogram, temporal adaptation, and the per-frame control of fixed and automatic modes.

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "render/exposure.h"
#include "scene/scene.h"
#include "shaders/shared/exposure.h"

using namespace rayster;
using namespace rayster::render;

namespace {

constexpr size_t kBins = gpu::kExposureBins;
// Half a bin, in EV: how far a reading may sit from the luminance its pixels share.
constexpr float kHalfBin = 0.5f * (gpu::kExposureMaxLog2 - gpu::kExposureMinLog2) / float(kBins - 2);

// Surface and background histograms with `count` pixels of each luminance listed.
struct Frame {
  std::vector<uint32_t> bins = std::vector<uint32_t>(gpu::kExposureHistograms * kBins, 0u);
  Frame& surface(float luminance, uint32_t count) {
    bins[gpu::exposureBin(luminance)] += count;
    return *this;
  }
  Frame& background(float luminance, uint32_t count) {
    bins[kBins + gpu::exposureBin(luminance)] += count;
    return *this;
  }
};

}  // namespace

TEST(Exposure, PhotographicRelations) {
  // EV100 15 (a sunny day): 1 / (1.2 · 2^15).
  EXPECT_FLOAT_EQ(exposureFromEv100(15.0f), 1.0f / (1.2f * 32768.0f));
  EXPECT_NEAR(ev100FromExposure(exposureFromEv100(7.5f)), 7.5f, 1e-5f);
  // A key luminance of 12.5 / 100 cd/m² is EV100 0.
  EXPECT_NEAR(ev100FromLuminance(0.125f), 0.0f, 1e-6f);
}

TEST(Exposure, BinsCoverTheRangeAndCatchNonFiniteValues) {
  EXPECT_EQ(gpu::exposureBin(0.0f), 0u);
  EXPECT_EQ(gpu::exposureBin(std::numeric_limits<float>::quiet_NaN()), 0u);
  EXPECT_EQ(gpu::exposureBin(std::exp2(gpu::kExposureMinLog2) * 0.9f), 0u);
  EXPECT_EQ(gpu::exposureBin(std::exp2(gpu::kExposureMinLog2)), 1u);
  EXPECT_EQ(gpu::exposureBin(std::exp2(gpu::kExposureMaxLog2)), kBins - 1);
  EXPECT_EQ(gpu::exposureBin(std::numeric_limits<float>::infinity()), kBins - 1);
  EXPECT_LT(gpu::exposureBin(1.0f), gpu::exposureBin(2.0f));
}

TEST(Exposure, MeterReadsTheLuminanceTheFrameShares) {
  for (float l : {1e-3f, 1.0f, 250.0f, 3e4f}) {
    const auto ev = meterHistogram(Frame().surface(l, 1000).bins);
    ASSERT_TRUE(ev.has_value());
    EXPECT_NEAR(*ev, ev100FromLuminance(l), kHalfBin + 1e-4f) << l;
  }
}

TEST(Exposure, MeterIgnoresHighlightsBlackAndTheSky) {
  const float key = ev100FromLuminance(10.0f);
  // 3 % of the pixels are the sun's highlight a million times brighter: within the ignored 5 %.
  EXPECT_NEAR(*meterHistogram(Frame().surface(10.0f, 970).surface(1e7f, 30).bins), key, kHalfBin + 1e-4f);
  // Black pixels (bin 0) do not pull the reading down.
  EXPECT_NEAR(*meterHistogram(Frame().surface(10.0f, 100).surface(0.0f, 900).bins), key, kHalfBin + 1e-4f);
  // Half the frame is a sky 100× brighter: the surfaces decide.
  EXPECT_NEAR(*meterHistogram(Frame().surface(10.0f, 500).background(1000.0f, 500).bins), key, kHalfBin + 1e-4f);
  // A frame of sky alone (surfaces under 5 %) meters the sky.
  EXPECT_NEAR(*meterHistogram(Frame().surface(10.0f, 10).background(1000.0f, 990).bins), ev100FromLuminance(1000.0f),
              kHalfBin + 1e-4f);
  // Nothing lit: no reading.
  EXPECT_FALSE(meterHistogram(Frame().surface(0.0f, 1000).bins).has_value());
  EXPECT_FALSE(meterHistogram(Frame().bins).has_value());
}

TEST(Exposure, MeterIsTheGeometricMeanBetweenTheIgnoredEnds) {
  // 500 pixels at L = 1 and 500 at 16: the darkest 100 and the brightest 50 are ignored, so 400 at
  // log2 L = 0 and 450 at 4 remain: log2 of the mean is 4 · 450 / 850.
  const auto ev = meterHistogram(Frame().surface(1.0f, 500).surface(16.0f, 500).bins);
  EXPECT_NEAR(*ev, ev100FromLuminance(std::exp2(4.0f * 450.0f / 850.0f)), kHalfBin);
}

TEST(Exposure, AdaptationMovesTowardsTheTargetFasterIntoTheDark) {
  const float dt = 1.0f / 60.0f;
  float up = 0.0f, down = 0.0f;
  for (int f = 0; f < 30; ++f) {
    const float before = up;
    up = adaptEv100(up, 4.0f, dt);
    down = adaptEv100(down, -4.0f, dt);
    EXPECT_GT(up, before);
    EXPECT_LT(up, 4.0f);
  }
  // After 0.5 s: 1 − e^(−rate · 0.5) of the way.
  EXPECT_NEAR(up, 4.0f * (1.0f - std::exp(-kAdaptTowardsBright * 0.5f)), 1e-3f);
  EXPECT_NEAR(down, -4.0f * (1.0f - std::exp(-kAdaptTowardsDark * 0.5f)), 1e-3f);
  EXPECT_GT(-down, up);
}

TEST(Exposure, FixedModesTakeTheirValue) {
  ExposureControl c;
  RenderSettings s;
  s.exposureMode = ExposureMode::Ev;
  s.exposureEv = -2.0f;
  c.begin(s, 9.0f);
  c.beginFrame(true);
  EXPECT_FALSE(c.automatic());
  EXPECT_FLOAT_EQ(c.exposure(), 0.25f);
  EXPECT_EQ(c.meter(Frame().surface(100.0f, 10).bins, 1.0f, true), 0.0f);  // no reading changes it
  c.beginFrame(false);
  EXPECT_FLOAT_EQ(c.exposure(), 0.25f);
  EXPECT_FLOAT_EQ(c.ratio(), 1.0f);

  s.exposureMode = ExposureMode::Ev100;
  s.ev100 = 12.0f;
  c.begin(s, 0.0f);
  c.beginFrame(true);
  EXPECT_FLOAT_EQ(c.exposure(), exposureFromEv100(12.0f));
}

TEST(Exposure, AutoStartsFromTheGuessSnapsThenAdaptsAndReportsTheRatio) {
  ExposureControl c;
  RenderSettings s;  // auto by default
  ASSERT_EQ(s.exposureMode, ExposureMode::Auto);
  c.begin(s, 3.0f);
  c.beginFrame(true);
  EXPECT_TRUE(c.automatic());
  EXPECT_FLOAT_EQ(c.exposure(), exposureFromEv100(3.0f));
  // The first reading snaps; its distance is from the exposure the frame was taken at.
  const float target = ev100FromLuminance(1000.0f);
  EXPECT_NEAR(c.meter(Frame().surface(1000.0f, 100).bins, 1.0f / 60.0f, false), std::abs(target - 3.0f), 0.2f);
  c.beginFrame(false);
  EXPECT_NEAR(c.ev100(), target, kHalfBin + 1e-3f);
  EXPECT_NEAR(c.ratio(), exposureFromEv100(c.ev100()) / exposureFromEv100(3.0f), 1e-4f);
  // Later readings adapt over dt: one frame moves a small step, and histories scale by the ratio.
  const float before = c.ev100();
  c.meter(Frame().surface(1.0f, 100).bins, 1.0f / 60.0f, false);
  c.beginFrame(false);
  EXPECT_LT(c.ev100(), before);
  EXPECT_GT(c.ev100(), before - 1.0f);
  EXPECT_GT(c.ratio(), 1.0f);  // darker scene: the exposure rises
  // A cut resets the ratio (the histories restart).
  c.beginFrame(true);
  EXPECT_FLOAT_EQ(c.ratio(), 1.0f);
  // Compensation brightens by its EV.
  s.exposureCompensation = 1.0f;
  const float metered = c.ev100();
  c.begin(s, 0.0f);  // a restarted run keeps the metered exposure
  c.beginFrame(true);
  EXPECT_NEAR(c.exposure(), 2.0f * exposureFromEv100(metered), 1e-6f);
}

TEST(Exposure, GuessFromTheLights) {
  scene::Scene scene;
  scene::Camera cam;
  cam.target = glm::vec3(0.0f);
  scene::Light sun;
  sun.type = scene::LightType::Directional;
  sun.intensity = 100000.0f;
  scene.lights.push_back(sun);
  // 100 000 lux on 18 % grey: L = 0.18 · 1e5 / π cd/m².
  EXPECT_NEAR(estimateEv100(scene, cam, 0.0f), ev100FromLuminance(0.18f * 1e5f / 3.14159265f), 1e-3f);
  scene.lights.clear();
  EXPECT_NEAR(exposureFromEv100(estimateEv100(scene, cam, 0.0f)), 1.0f, 1e-5f);  // emission only: exposure 1
}
