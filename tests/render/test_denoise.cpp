// The denoiser kernels on lavapipe, validation on, through the render graph, on small synthetic
// G-buffers uploaded from the CPU: each kernel against the CPU reference (denoise_reference.h),
// then what a denoiser must keep: constant input stays constant, no bleeding across a depth edge,
// a static camera's temporal output is the exact mean, a reset drops the history, no NaN/Inf.
#include "render/pipelines.h"
#include "tests/render/denoise_fixture.h"

namespace rayster::render::denoise_test {
namespace {

namespace ref = test::ref;
constexpr uint32_t kMoving = gpu::kDenoiseMoving, kReset = gpu::kDenoiseReset;
TemporalState stateOf(uint32_t flags) { return {(flags & kMoving) != 0, (flags & kReset) != 0}; }

TEST_F(Denoise, SurfaceMatchesCpu) {
  const ref::GBufferCpu g = makeGBuffer();
  Frame fr(*this);
  auto& bytes = fr.download(fr.surface("surface", g));
  fr.run();
  const auto gpu = surfacesOf(bytes);
  const auto cpu = ref::surfaces(g, kNear, kFar);
  for (size_t i = 0; i < kPixels; ++i) {
    ASSERT_EQ(gpu[i].id, cpu[i].id) << i;
    ASSERT_EQ(gpu[i].sharp, cpu[i].sharp) << i;
    EXPECT_NEAR(gpu[i].z, cpu[i].z, 1e-5f * cpu[i].z) << i;
    EXPECT_NEAR(gpu[i].zGrad, cpu[i].zGrad, 1e-4f) << i;
    if (!cpu[i].sky()) {
      EXPECT_GT(glm::dot(gpu[i].n, cpu[i].n), 0.99999f) << i;
    }
  }
  EXPECT_NEAR(cpu[kW * 5 + 3].z, 2.0f + 0.3f + 0.25f, 1e-4f) << "linear depth from reversed Z";
  EXPECT_TRUE(cpu[kW * 13 + 12].sharp) << "the mirror pixels (right plane, rows ≥ 12) are flagged sharp";
  EXPECT_FALSE(cpu[kW * 5 + 3].sharp);
  EXPECT_NEAR(cpu[kW * 5 + 3].zGrad, 0.15f, 1e-4f) << "slope = |dz/dx| + |dz/dy|";
}

// Inputs of one temporal step: this frame's and the last frame's surfaces (the boundary between the
// planes moved: a disocclusion), a fractional motion, and random histories.
struct TemporalCase {
  ref::GBufferCpu cur = makeGBuffer(0), prev = makeGBuffer(2);
  std::vector<vec2> motion = fractionalMotion();
};

TEST_F(Denoise, ShadowTemporalMatchesCpu) {
  for (uint32_t flags : {kMoving, 0u, kReset}) {
    TemporalCase c;
    const std::vector<float> raw = visibilityNoise(1);
    std::vector<float> hist = noise(kPixels * (kLights + 1), 2);
    for (size_t i = kPixels * kLights; i < hist.size(); ++i) hist[i] = std::floor(hist[i] * 40.0f);
    Frame fr(*this);
    SurfacePair s{fr.surface("cur", c.cur), fr.surface("prev", c.prev)};
    auto motion = fr.uploadHalves("motion", kMotionFormat, 1, motionFloats(c.motion));
    auto rawImg = fr.uploadHalves("raw", VK_FORMAT_R16_SFLOAT, kLights, raw);
    auto histImg = fr.upload("hist", kShadowHistoryFormat, kLights + 1, hist);
    auto next = fr.graph.createImage("next", shadowHistoryDesc(kSize, kLights));
    const ShadowDenoised t =
        shadowTemporal(fr.graph, inputs(), s, motion, rawImg, {histImg, next}, kLights, stateOf(flags));
    auto& out = fr.download(t.temporal);
    auto& varBytes = fr.download(t.variance);
    auto& curBytes = fr.download(s.current);
    auto& prevBytes = fr.download(s.previous);
    fr.run();
    const auto cur = surfacesOf(curBytes), prev = surfacesOf(prevBytes);
    const ref::Frame f{kW, kH, cur, prev, c.motion, flags};
    std::vector<float> variance;
    const std::vector<float> expected = ref::shadowTemporal(f, raw, hist, kLights, &variance);
    expectNear(floatsOf(out), expected, 1e-5f, flags == kMoving ? "moving" : flags ? "reset" : "static");
    expectNear(halvesOf(varBytes), variance, 1e-3f, "variance");
    // The disoccluded columns (x = 8, 9 were the left plane) restart: n = 1, value = raw.
    EXPECT_EQ(expected[kPixels * kLights + kW * 5 + 8], 1.0f);
    EXPECT_GT(expected[kPixels * kLights + kW * 5 + 4], flags == kReset ? 0.0f : 1.0f);
  }
}

TEST_F(Denoise, ShadowAtrousMatchesCpu) {
  const ref::GBufferCpu g = makeGBuffer();
  const std::vector<float> input = visibilityNoise(3);
  std::vector<float> variance = noise(kPixels * kLights, 11, 0.0f, 0.1f);
  for (size_t i = 0; i < variance.size(); i += 3) variance[i] = 0.0f;  // converged: edges stay sharp
  for (float& v : variance) v = viaHalf(v);
  for (uint32_t step : {1u, 2u, 4u, 8u}) {
    Frame fr(*this);
    auto surface = fr.surface("surface", g);
    auto in = fr.uploadHalves("in", VK_FORMAT_R16_SFLOAT, kLights, input);
    auto var = fr.uploadHalves("var", VK_FORMAT_R16_SFLOAT, kLights, variance);
    auto out = createShadowImage(fr.graph, kSize, kLights, "out");
    auto& bytes = fr.download(shadowAtrous(fr.graph, inputs(), surface, in, var, out, kLights, step));
    auto& sBytes = fr.download(surface);
    fr.run();
    const auto cur = surfacesOf(sBytes);
    const std::vector<vec2> motion(kPixels, vec2(0));
    const ref::Frame f{kW, kH, cur, cur, motion, 0};
    expectNear(halvesOf(bytes), ref::shadowAtrous(f, input, variance, kLights, int(step)), 1e-3f, "shadow à-trous");
  }
}

// One SVGF temporal pass (integration and variance estimate) against the reference; histories
// of `maxLength` samples at most (short ones exercise the spatial variance estimate).
void svgfTemporalCase(Denoise& t, uint32_t flags, float maxLength, uint32_t seed, const DenoiseInputs& in) {
  TemporalCase c;
  const std::vector<vec4> raw = radianceNoise(seed);
  std::vector<vec4> colorHist = vec4sOf(noise(kPixels * 4, seed + 1, 0.0f, 2.0f));
  std::vector<vec2> momentsHist(kPixels);
  const std::vector<float> r = noise(kPixels * 3, seed + 2);
  for (size_t i = 0; i < kPixels; ++i) {
    const float mu = r[i * 3] * 2.0f;
    momentsHist[i] = vec2(mu, mu * mu + r[i * 3 + 1]);
    colorHist[i].a = std::floor(r[i * 3 + 2] * maxLength);  // the history length n
  }
  Denoise::Frame fr(t);
  SurfacePair s{fr.surface("cur", c.cur), fr.surface("prev", c.prev)};
  auto motion = fr.uploadHalves("motion", kMotionFormat, 1, motionFloats(c.motion));
  auto rawImg = fr.uploadHalves("raw", VK_FORMAT_R16G16B16A16_SFLOAT, 1, flatten(raw));
  auto colorPrev = fr.upload("color", kSvgfColorHistoryFormat, 1, flatten(colorHist));
  auto momentsPrev = fr.upload("moments", kSvgfMomentsHistoryFormat, 1, flatten(momentsHist));
  auto colorNext = fr.graph.createImage("color-next", svgfColorHistoryDesc(kSize));
  auto momentsNext = fr.graph.createImage("moments-next", svgfMomentsHistoryDesc(kSize));
  auto work = createSvgfImage(fr.graph, kSize, "work");
  auto& workBytes = fr.download(svgfTemporal(fr.graph, in, "test", s, motion, rawImg, {colorPrev, colorNext},
                                             {momentsPrev, momentsNext}, work, stateOf(flags)));
  auto& colorBytes = fr.download(colorNext);
  auto& momentBytes = fr.download(momentsNext);
  auto& curBytes = fr.download(s.current);
  auto& prevBytes = fr.download(s.previous);
  fr.run();
  const auto cur = surfacesOf(curBytes), prev = surfacesOf(prevBytes);
  const ref::Frame f{kW, kH, cur, prev, c.motion, flags};
  std::vector<vec4> color, working;
  std::vector<vec2> moments;
  ref::svgfTemporal(f, raw, colorHist, momentsHist, color, moments, working);
  expectNear(floatsOf(colorBytes), flatten(color), 1e-5f, "colour");
  expectNear(floatsOf(momentBytes), flatten(moments), 1e-5f, "moments");
  expectNear(halvesOf(workBytes), flatten(working), 1e-3f, "variance");
}

TEST_F(Denoise, SvgfTemporalMatchesCpu) {
  for (uint32_t flags : {kMoving, 0u, kReset}) svgfTemporalCase(*this, flags, 40.0f, 4, inputs());
}

TEST_F(Denoise, SvgfVarianceMatchesCpu) {
  // n from 1 to 8 after the update: both the temporal and the spatial estimate.
  for (uint32_t flags : {kMoving, 0u}) svgfTemporalCase(*this, flags, 8.0f, 7, inputs());
}

TEST_F(Denoise, SvgfAtrousMatchesCpu) {
  const ref::GBufferCpu g = makeGBuffer();
  std::vector<vec4> input = radianceNoise(9);
  for (vec4& v : input) v.a = viaHalf(v.a * 0.15f);  // variance
  for (uint32_t step : {1u, 2u, 4u, 8u}) {
    for (bool history : {false, true}) {
      Frame fr(*this);
      auto surface = fr.surface("surface", g);
      auto in = fr.uploadHalves("in", kSvgfWorkingFormat, 1, flatten(input));
      auto out = createSvgfImage(fr.graph, kSize, "out");
      auto hist = history ? fr.graph.createImage("hist", svgfColorHistoryDesc(kSize)) : graph::ImageHandle{};
      auto& bytes = fr.download(svgfAtrous(fr.graph, inputs(), "test", surface, in, out, step, hist));
      std::vector<uint8_t>* histBytes = history ? &fr.download(hist) : nullptr;
      auto& sBytes = fr.download(surface);
      fr.run();
      const auto cur = surfacesOf(sBytes);
      const std::vector<vec2> motion(kPixels, vec2(0));
      const ref::Frame f{kW, kH, cur, cur, motion, 0};
      const std::vector<vec4> expected = ref::svgfAtrous(f, input, roughness(g), int(step));
      expectNear(halvesOf(bytes), flatten(expected), 1e-3f, "svgf à-trous");
      if (histBytes) {
        std::vector<vec4> h = vec4sOf(floatsOf(*histBytes)), e = expected;
        for (size_t i = 0; i < kPixels; ++i) h[i].a = e[i].a = 0.0f;  // history alpha is n, not the variance
        expectNear(flatten(h), flatten(e), 1e-3f, "history");
      }
      // Mirror pixels (right plane, rows ≥ 12) keep their value: the spatial filter skips them.
      EXPECT_NEAR(expected[kW * 13 + 12].r, input[kW * 13 + 12].r, 1e-6f);
    }
  }
}

// The hybrid denoises AO as the shadow denoiser's last layer (renderer_frame.cpp): each layer is
// filtered on its own (only the geometry weights and the history length are shared), so layers
// denoised beside the most layers there can be (every shadowed light and AO) equal the same layers
// denoised by a run of their own, over frames with history, static and moving.
TEST_F(Denoise, ShadowLayersAreDenoisedIndependently) {
  constexpr uint32_t kAll = gpu::kMaxShadowDenoiseLayers;
  static_assert(kAll == gpu::kMaxShadowLights + 1);
  const ref::GBufferCpu g = makeGBuffer();
  for (uint32_t f = 0; f < 4; ++f) {
    std::vector<float> all = noise(kPixels * kAll, 700 + f);
    for (float& x : all) x = viaHalf(x);
    // The pair: the first and the last layer of `all`.
    std::vector<float> pair(all.begin(), all.begin() + kPixels);
    pair.insert(pair.end(), all.end() - kPixels, all.end());
    Frame fr(*this);
    const auto surfaceHistory = fr.graph.history("surface", surfaceDesc(kSize));
    const SurfacePair s{fr.surface("surface", g, surfaceHistory.next), surfaceHistory.previous};
    auto motion = fr.uploadHalves("motion", kMotionFormat, 1, std::vector<float>(kPixels * 2, 0.0f));
    auto run = [&](const std::vector<float>& v, uint32_t layers, const std::string& name) {
      auto raw = fr.uploadHalves(name + "-raw", VK_FORMAT_R16_SFLOAT, layers, v);
      const auto h = fr.graph.history(name, shadowHistoryDesc(kSize, layers));
      const ShadowDenoised d =
          denoiseShadows(fr.graph, inputs(), s, motion, raw, {h.previous, h.next}, {f >= 2, f == 0}, name);
      return std::pair{&fr.download(d.temporal), &fr.download(d.denoised)};
    };
    const auto [allTemporal, allDenoised] = run(all, kAll, "all");
    const auto [pairTemporal, pairDenoised] = run(pair, 2, "pair");
    fr.run();
    const std::vector<float> a = halvesOf(*allDenoised), p = halvesOf(*pairDenoised);
    const std::vector<float> at = floatsOf(*allTemporal), pt = floatsOf(*pairTemporal);
    ASSERT_EQ(a.size(), kPixels * kAll);
    ASSERT_EQ(at.size(), kPixels * (kAll + 1));
    for (size_t i = 0; i < kPixels; ++i) {
      ASSERT_EQ(a[i], p[i]) << "first layer, frame " << f << " texel " << i;
      ASSERT_EQ(a[kPixels * (kAll - 1) + i], p[kPixels + i]) << "last layer, frame " << f << " texel " << i;
      ASSERT_EQ(at[kPixels * (kAll - 1) + i], pt[kPixels + i]) << "last temporal, frame " << f << " texel " << i;
      ASSERT_EQ(at[kPixels * kAll + i], pt[kPixels * 2 + i]) << "history length, frame " << f << " texel " << i;
    }
    // Not a trivial pass-through: the filter changed the noisy input somewhere.
    size_t changed = 0;
    for (size_t i = kW; i < kPixels; ++i) changed += a[kPixels * (kAll - 1) + i] != all[kPixels * (kAll - 1) + i];
    EXPECT_GT(changed, kPixels / 2) << "frame " << f;
  }
}

// ---- the whole denoisers over several frames, with histories ----

struct Outputs {
  std::vector<float> shadowTemporal, shadowDenoised;  // L (+1) layers
  std::vector<vec4> radianceTemporal, radianceDenoised;
};

// One frame of both denoisers, with histories carried from the frame before (graph/history.h).
class DenoiseRun {
 public:
  Outputs frame(Denoise::Frame& fr, const ref::GBufferCpu& g, const std::vector<float>& visibility,
                const std::vector<vec4>& radiance, TemporalState state, const DenoiseInputs& in) {
    const auto surface = fr.graph.history("surface", surfaceDesc(kSize));
    const auto shadow = fr.graph.history("shadow", shadowHistoryDesc(kSize, kLights));
    const auto color = fr.graph.history("color", svgfColorHistoryDesc(kSize));
    const auto moments = fr.graph.history("moments", svgfMomentsHistoryDesc(kSize));
    SurfacePair s{fr.surface("surface", g, surface.next), surface.previous};
    auto motion = fr.uploadHalves("motion", kMotionFormat, 1, std::vector<float>(kPixels * 2, 0.0f));  // static
    auto vis = fr.uploadHalves("vis", VK_FORMAT_R16_SFLOAT, kLights, visibility);
    auto rad = fr.uploadHalves("rad", VK_FORMAT_R16G16B16A16_SFLOAT, 1, flatten(radiance));
    ShadowDenoised sh = denoiseShadows(fr.graph, in, s, motion, vis, {shadow.previous, shadow.next}, state);
    RadianceDenoised rd = denoiseRadiance(fr.graph, in, "reflection", s, motion, rad, {color.previous, color.next},
                                          {moments.previous, moments.next}, state);
    auto& a = fr.download(sh.temporal);
    auto& b = fr.download(sh.denoised);
    auto& c = fr.download(rd.temporal);
    auto& d = fr.download(rd.denoised);
    fr.run();
    return {floatsOf(a), halvesOf(b), vec4sOf(floatsOf(c)), vec4sOf(halvesOf(d))};
  }
};

class DenoiseFrames : public Denoise {
 protected:
  Outputs frame(const ref::GBufferCpu& g, const std::vector<float>& vis, const std::vector<vec4>& rad,
                TemporalState st) {
    if (!run_) run_ = std::make_unique<DenoiseRun>();
    Frame fr(*this);
    return run_->frame(fr, g, vis, rad, st, inputs());
  }
  std::unique_ptr<DenoiseRun> run_;
};

void expectAllFinite(const Outputs& o) {
  for (float v : o.shadowTemporal) ASSERT_TRUE(std::isfinite(v));
  for (float v : o.shadowDenoised) ASSERT_TRUE(std::isfinite(v));
  for (const vec4& v : o.radianceTemporal) ASSERT_TRUE(std::isfinite(v.r + v.g + v.b + v.a));
  for (const vec4& v : o.radianceDenoised) ASSERT_TRUE(std::isfinite(v.r + v.g + v.b + v.a));
}

TEST_F(DenoiseFrames, ConstantInputStaysConstant) {
  const ref::GBufferCpu g = makeGBuffer();
  const std::vector<float> vis(kPixels * kLights, 0.75f);
  const std::vector<vec4> rad(kPixels, vec4(0.5f, 0.25f, 1.0f, 1.0f));
  for (int f = 0; f < 4; ++f) {
    const Outputs o = frame(g, vis, rad, {f >= 2, f == 0});
    expectAllFinite(o);
    for (size_t i = 0; i < kPixels * kLights; ++i) ASSERT_NEAR(o.shadowDenoised[i], 0.75f, 1e-3f) << f << " " << i;
    for (size_t i = 0; i < kPixels; ++i) {
      const vec4 v = o.radianceDenoised[i];
      ASSERT_NEAR(v.r, 0.5f, 1e-3f) << f << " " << i;
      ASSERT_NEAR(v.g, 0.25f, 1e-3f) << f << " " << i;
      ASSERT_NEAR(v.b, 1.0f, 1e-3f) << f << " " << i;
      ASSERT_NEAR(v.a, 0.0f, 1e-6f) << "constant input has no variance";
    }
  }
}

TEST_F(DenoiseFrames, NoBleedingAcrossADepthEdge) {
  // Two planes facing the camera, same id and normal, z = 2 (x < 8, lit) and z = 5 (x ≥ 8, dark):
  // only the depth weight separates them.
  ref::GBufferCpu g = makeGBuffer(0, /*sameIdAndNormal*/ true, /*flat*/ true);
  for (size_t i = 0; i < kPixels; ++i) g.material[i * 4] = 128;
  std::vector<float> vis(kPixels * kLights);
  std::vector<vec4> rad(kPixels);
  for (int l = 0; l < kLights; ++l)
    for (size_t i = 0; i < kPixels; ++i) vis[l * kPixels + i] = i % kW < 8 ? 1.0f : 0.0f;
  const std::vector<float> n = noise(kPixels, 10, 0.9f, 1.1f);  // a little noise: the luminance weight sees variance
  for (size_t i = 0; i < kPixels; ++i) rad[i] = i % kW < 8 ? vec4(viaHalf(n[i]), 1, 1, 1) : vec4(0, 0, 0, 1);
  for (int f = 0; f < 3; ++f) {
    const Outputs o = frame(g, vis, rad, {true, f == 0});
    expectAllFinite(o);
    for (int l = 0; l < kLights; ++l)
      for (size_t i = 0; i < kPixels; ++i)
        ASSERT_NEAR(o.shadowDenoised[l * kPixels + i], vis[l * kPixels + i], 1e-3f) << i;
    for (size_t i = kW; i < kPixels; ++i) {
      if (i % kW >= 8)
        ASSERT_EQ(o.radianceDenoised[i].r + o.radianceDenoised[i].g, 0.0f) << "bled into " << i;
      else
        ASSERT_GT(o.radianceDenoised[i].g, 0.999f) << "darkened at " << i;
    }
  }
}

TEST_F(DenoiseFrames, StaticCameraTemporalOutputIsTheMean) {
  const ref::GBufferCpu g = makeGBuffer();
  std::vector<float> visSum(kPixels * kLights, 0.0f);
  std::vector<vec4> radSum(kPixels, vec4(0));
  constexpr int kFrames = 7;
  for (int f = 0; f < kFrames; ++f) {
    const std::vector<float> vis = visibilityNoise(100 + f);
    const std::vector<vec4> rad = radianceNoise(200 + f);
    for (size_t i = 0; i < vis.size(); ++i) visSum[i] += vis[i];
    for (size_t i = 0; i < rad.size(); ++i) radSum[i] += rad[i];
    const Outputs o = frame(g, vis, rad, {false, f == 0});
    expectAllFinite(o);
    // Row 0 is sky: no surface, no history (it shows its raw value).
    for (size_t i = 0; i < kPixels * kLights; ++i) {
      if (i % kPixels < kW) continue;
      ASSERT_NEAR(o.shadowTemporal[i], visSum[i] / float(f + 1), 1e-5f) << "frame " << f << " texel " << i;
    }
    for (size_t i = kW; i < kPixels; ++i) {
      ASSERT_EQ(o.shadowTemporal[kPixels * kLights + i], float(f + 1)) << "history length";
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(o.radianceTemporal[i][c], radSum[i][c] / float(f + 1), 1e-5f) << f << " " << i;
    }
  }
}

TEST_F(DenoiseFrames, ResetDropsTheHistory) {
  const ref::GBufferCpu g = makeGBuffer();
  for (int f = 0; f < 3; ++f) frame(g, visibilityNoise(300 + f), radianceNoise(400 + f), {f > 0, f == 0});
  for (bool moving : {false, true}) {
    const std::vector<float> vis = visibilityNoise(500);
    const std::vector<vec4> rad = radianceNoise(600);
    const Outputs o = frame(g, vis, rad, {moving, /*reset*/ true});
    expectAllFinite(o);
    for (size_t i = 0; i < kPixels * kLights; ++i) ASSERT_EQ(o.shadowTemporal[i], vis[i]) << i;
    for (size_t i = 0; i < kPixels; ++i) {
      ASSERT_EQ(o.shadowTemporal[kPixels * kLights + i], 1.0f);
      if (!moving) {  // while moving, à-trous iteration 1 replaces the colour history (SVGF)
        for (int c = 0; c < 3; ++c) ASSERT_EQ(o.radianceTemporal[i][c], rad[i][c]) << i;
      }
    }
  }
}

TEST_F(DenoiseFrames, NoNanOrInfOnExtremeInputs) {
  // Black everywhere but one very bright pixel, zero variance around it, sky pixels, both modes.
  const ref::GBufferCpu g = makeGBuffer();
  std::vector<vec4> rad(kPixels, vec4(0));
  rad[kW * 6 + 5] = vec4(60000.0f, 0, 1000.0f, 1);
  const std::vector<float> vis(kPixels * kLights, 0.0f);
  for (int f = 0; f < 5; ++f) expectAllFinite(frame(g, vis, rad, {f % 2 == 1, f == 0}));
}

}  // namespace
}  // namespace rayster::render::denoise_test
