// Quarter-rate one-bounce indirect diffuse (--indirect-rate quarter, lib/indirect_ray.glsl): one pixel
// of each 2×2 block traces per frame, rotating so that every pixel traces once in 4 frames; the fill
// pass leaves no hole in the raw image; the traced pixels trace exactly the full rate's rays; a static
// camera's denoised indirect light converges to the full rate's.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/image_io.h"
#include "render/renderer.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

constexpr float kSkipped = 0.25f;  // raw_indirect.rgen's mark of a pixel another pixel of its block traced

// `frames` frames of `scene` at w × h with the one-bounce path's indirect light on; the AOVs by name.
std::map<std::string, ImageF> render(const std::filesystem::path& dir, const std::string& scene, int w, int h,
                                     const std::string& args, const std::vector<std::string>& aovs) {
  return renderAovs(dir,
                    scene + " --primary raster --indirect on --gi path --size " + std::to_string(w) + "x" +
                        std::to_string(h) + " " + args,
                    aovs);
}

float at(const ImageF& img, int x, int y, int c = 0) { return img.pixel(x, y)[c]; }

TEST(IndirectRate, PassesReportOneInvocationPerBlockAtQuarterRate) {
  // The rays a pass declares (--json "rays"): a bounce ray and a shadow ray per invocation; full rate
  // one invocation per pixel, quarter one per 2×2 block, rounded up on an odd-sized image.
  auto dir = testDir();
  for (const auto& [rate, invocations] : {std::pair{"full", 63ull * 47}, std::pair{"quarter", 32ull * 24}}) {
    const auto json = dir / (std::string(rate) + ".json");
    RunResult r = runRayster(
        "render builtin:cornell --size 63x47 --frames 1 --indirect on --gi path --raw-rays --indirect-rate " +
        std::string(rate) + " --json " + json.string() + " -o " + (dir / "out.png").string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(json));
    int found = 0;
    for (const auto& p : j["passes"])
      if (p["name"] == "rt-indirect" || p["name"] == "raw-rt-indirect") {
        EXPECT_EQ(p["rays"].get<uint64_t>(), invocations * 2) << rate << " " << p["name"];
        ++found;
      }
    EXPECT_EQ(found, 2) << rate;
  }
}

TEST(IndirectRate, QuarterTracesOnePixelPerBlockAndEveryPixelOverFourFrames) {
  // Frames 1..4 of the Cornell box at quarter and full rate. raw-indirect (the raw twin, which
  // replays rt-indirect's rays) marks the skipped pixels; exactly one pixel per 2×2 block is not
  // skipped, at the same position in every block, and the 4 frames' positions are the 4 pixels of a
  // block. Where it traces, the quarter rate's raw image and twin equal the full rate's bit for bit
  // (same rays, same random numbers); everywhere, the raw image is finite and its alpha is the full
  // rate's (1 on geometry, 0 on the background): the fill left no pixel unwritten.
  auto dir = testDir();
  constexpr int kW = 32, kH = 24;  // 384 blocks: the pattern is per block, the same at any size
  std::set<std::pair<int, int>> positions;
  size_t traced = 0, filled = 0;
  for (int frames = 1; frames <= 4; ++frames) {
    // A fixed exposure: the two rates' images differ a little, so would their metered exposures, and
    // the raw images are compared bit for bit.
    const std::string args = "--raw-rays --exposure 0 --frames " + std::to_string(frames);
    auto quarter =
        render(dir, "builtin:cornell", kW, kH, args + " --indirect-rate quarter", {"indirect-raw", "raw-indirect"});
    auto full =
        render(dir, "builtin:cornell", kW, kH, args + " --indirect-rate full", {"indirect-raw", "raw-indirect"});
    ASSERT_EQ(quarter.size(), 2u);
    ASSERT_EQ(full.size(), 2u);
    std::set<std::pair<int, int>> offsets;
    for (int by = 0; by < kH / 2; ++by)
      for (int bx = 0; bx < kW / 2; ++bx) {
        int inBlock = 0;
        for (int k = 0; k < 4; ++k) {
          const int x = 2 * bx + (k & 1), y = 2 * by + (k >> 1);
          const float r = at(quarter["raw-indirect"], x, y);
          ASSERT_TRUE(r == kSkipped || r == 0.0f || r == 0.5f || r == 1.0f) << r;
          ASSERT_NE(at(full["raw-indirect"], x, y), kSkipped);
          for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(at(quarter["indirect-raw"], x, y, c))) << x << "," << y;
          ASSERT_EQ(at(quarter["indirect-raw"], x, y, 3), at(full["indirect-raw"], x, y, 3))
              << "frame " << frames << " pixel " << x << "," << y << " (a hole?)";
          if (r == kSkipped) {
            filled += at(quarter["indirect-raw"], x, y, 3) == 1.0f;
            continue;
          }
          ++inBlock;
          offsets.insert({x & 1, y & 1});
          traced += r > 0.0f;
          ASSERT_EQ(r, at(full["raw-indirect"], x, y)) << x << "," << y;
          for (int c = 0; c < 4; ++c)
            ASSERT_EQ(at(quarter["indirect-raw"], x, y, c), at(full["indirect-raw"], x, y, c)) << x << "," << y;
        }
        ASSERT_EQ(inBlock, 1) << "frame " << frames << " block " << bx << "," << by;
      }
    ASSERT_EQ(offsets.size(), 1u) << "frame " << frames << ": blocks disagree on the traced pixel";
    positions.insert(*offsets.begin());
  }
  EXPECT_EQ(positions.size(), 4u) << "4 frames did not visit every pixel of the block";
  // Both traced and filled geometry pixels occur, so the comparisons say something.
  EXPECT_GT(traced, size_t(kW * kH / 2));
  EXPECT_GT(filled, size_t(kW * kH));
}

TEST(IndirectRate, OddSizesFillEveryPixel) {
  // Partial blocks on the last column and row: the raw image's alpha is still the full rate's.
  auto dir = testDir();
  constexpr int kW = 63, kH = 47;
  auto quarter = render(dir, "builtin:cornell", kW, kH, "--frames 2 --indirect-rate quarter", {"indirect-raw"});
  auto full = render(dir, "builtin:cornell", kW, kH, "--frames 2 --indirect-rate full", {"indirect-raw"});
  ASSERT_EQ(quarter.size(), 1u);
  ASSERT_EQ(full.size(), 1u);
  size_t geometry = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(at(quarter["indirect-raw"], x, y, c)));
      ASSERT_EQ(at(quarter["indirect-raw"], x, y, 3), at(full["indirect-raw"], x, y, 3)) << x << "," << y;
      geometry += at(full["indirect-raw"], x, y, 3) == 1.0f;
    }
  EXPECT_GT(geometry, size_t(kW * kH / 2));
}

// Per-channel image means and the RMS difference of two images' rgb over pixels where both have alpha 1.
struct Diff {
  double mean[3] = {0, 0, 0}, otherMean[3] = {0, 0, 0}, rms = 0;
};
Diff compare(const ImageF& a, const ImageF& b) {
  Diff d;
  double n = 0, sq = 0;
  for (size_t i = 0; i < a.rgba.size(); i += 4) {
    for (int c = 0; c < 3; ++c) {
      d.mean[c] += a.rgba[i + c];
      d.otherMean[c] += b.rgba[i + c];
      sq += (a.rgba[i + c] - b.rgba[i + c]) * (a.rgba[i + c] - b.rgba[i + c]);
    }
    n += 1;
  }
  for (int c = 0; c < 3; ++c) {
    d.mean[c] /= n;
    d.otherMean[c] /= n;
  }
  d.rms = std::sqrt(sq / (3 * n));
  return d;
}

TEST(IndirectRate, StaticCameraQuarterRateConvergesToFullRate) {
  // A static camera: SVGF's temporal accumulation sees every pixel traced once per 4 frames, so after
  // 64 frames the quarter rate's denoised indirect light (16 samples per pixel) agrees with the full
  // rate's (64) within the full rate's own noise, measured as the difference between two seeds.
  // Equal frame counts, not equal samples: SVGF's output mean still rises with the history length
  // (its edge-stopping suppresses rare bright samples: the full rate's mean here is ~0.18 after 4
  // frames, ~0.21 after 16, ~0.23 after 64), which would hide the comparison. The quarter run has
  // its own seed, so it shares no rays with the full-rate run it is compared with.
  auto dir = testDir();
  constexpr int kW = 64, kH = 48;
  const std::string frames = " --frames 64";
  auto full = render(dir, "builtin:cornell", kW, kH, "--indirect-rate full --seed 1" + frames, {"indirect-denoised"});
  auto fullOther =
      render(dir, "builtin:cornell", kW, kH, "--indirect-rate full --seed 2" + frames, {"indirect-denoised"});
  auto quarter =
      render(dir, "builtin:cornell", kW, kH, "--indirect-rate quarter --seed 2" + frames, {"indirect-denoised"});
  ASSERT_TRUE(full.count("indirect-denoised") && fullOther.count("indirect-denoised") &&
              quarter.count("indirect-denoised"));
  const Diff noise = compare(fullOther["indirect-denoised"], full["indirect-denoised"]);
  const Diff d = compare(quarter["indirect-denoised"], full["indirect-denoised"]);
  std::printf(
      "[indirect-rate] mean E full %.4f %.4f %.4f, quarter %.4f %.4f %.4f; RMS quarter-full %.4f, "
      "full seed 2 - seed 1 %.4f\n",
      d.otherMean[0], d.otherMean[1], d.otherMean[2], d.mean[0], d.mean[1], d.mean[2], d.rms, noise.rms);
  ASSERT_GT(noise.rms, 0.0) << "two seeds gave the same image: nothing was traced";
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(d.otherMean[c], 0.05) << "no indirect light in channel " << c;
    EXPECT_NEAR(d.mean[c], d.otherMean[c], 0.03 * d.otherMean[c]) << "channel " << c;
  }
  EXPECT_LT(d.rms, 1.5 * noise.rms);
}

}  // namespace
}  // namespace rayster::test
