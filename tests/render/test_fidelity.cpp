// Fidelity: the hybrid frame (default settings: denoised, TAA on, probes, automatic exposure, after
// kHybridFrames static frames) against a converged path-traced reference of the same scene, per
// effect: mean luminance within kEnergyTolerance, and HDR-FLIP and relMSE within frozen budgets. The masks come from
// the hybrid's own G-buffer AOVs (tests/fidelity/masks.h: shadowed, reflective, refractive, rest, plus the whole
// image), the errors from the real `rayster compare --mask --json`, and the budgets are frozen in
// tests/fidelity/budgets.json. The noise floor is the same comparison between two references rendered with different
// seeds: a budget below it could not tell a renderer bug from Monte Carlo noise.
//
// The references are committed EXRs (tests/fidelity/refs/, README.md there has the command): at
// thousands of samples they take minutes each on lavapipe, far more than a test may.
// Re-freezing the budgets (after a deliberate change, never to hide a regression):
//   RAYSTER_FIDELITY_BLESS=1 ./build/tests/rayster_tests --gtest_filter='Fidelity*'
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/fidelity/masks.h"
#include "tests/render/analytic_scenes.h"

namespace rayster::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kWidth = 96, kHeight = 72;
// Energy: the hybrid's mean luminance over each mask against the reference's. The target (issue 14)
// is ±kEnergyTolerance everywhere. A mask that met it when the budgets were frozen must keep
// meeting it; one that did not (a known gap: docs/fidelity.md lists them and why) is held to its
// frozen error plus kEnergyGapSlack, so it can only get better, and is printed as a gap.
constexpr double kEnergyTolerance = 0.05;
constexpr double kEnergyGapSlack = 0.02;
// Masks smaller than this carry no energy check: the mean of a few dozen pixels of a path-traced
// reference is still noisy where caustics and fireflies land.
constexpr size_t kMinEnergyPixels = 150;
constexpr int kHybridFrames = 32;  // static camera: TAA and the denoisers' histories have settled by then
constexpr int kHybridSeed = 1;     // with --primary raster: "auto" picks by timing, so its image could vary
// A budget is the measured error times this: room for driver and denoiser jitter, not for a bug.
constexpr double kMargin = 1.25;
// Masks smaller than this carry no budget: a handful of pixels is all edge and all noise.
constexpr size_t kMinMaskPixels = 24;
const std::vector<std::string> kMetrics = {"hdr-flip", "relmse"};
using fidelity::buildMasks;
using fidelity::kMaskNames;

fs::path fidelityDir() { return fs::path(RAYSTER_SOURCE_DIR) / "tests" / "fidelity"; }
// The scenes: built-in ones, and the Blender-exported corpus (assets/corpus, docs/corpus.md).
std::string sceneSource(const std::string& scene) {
  if (scene == "whitted" || scene == "cornell" || scene == "spheres") return "builtin:" + scene;
  const fs::path corpus = fs::path(RAYSTER_SOURCE_DIR) / "assets" / "corpus";
  return (corpus / (scene + (scene == "product" || scene == "foliage" ? ".json" : ".glb"))).string();
}

// Mean Rec. 709 luminance of `img` over the pixels `mask` covers.
double maskedLuminance(const ImageF& img, const Image8& mask) {
  double sum = 0.0;
  size_t n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      if (mask.pixel(x, y)[0] == 0) continue;
      const float* p = img.pixel(x, y);
      sum += 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
      ++n;
    }
  return n ? sum / double(n) : 0.0;
}
fs::path budgetsPath() { return fidelityDir() / "budgets.json"; }
fs::path referencePath(const std::string& scene, int seed) {
  return fidelityDir() / "refs" / fmt::format("{}-seed{}.exr", scene, seed);
}

size_t coverage(const Image8& mask) { return maskFromImage(mask).count(); }

// `rayster compare REF TEST --mask M --json`: the metrics' means (and the pixels compared).
json compareCli(const fs::path& ref, const fs::path& test, const fs::path& mask, const fs::path& out,
                const fs::path& heatmap = {}) {
  std::string args = fmt::format("compare {} {} --metric hdr-flip,relmse,flip --mask {} --json {}", ref.string(),
                                 test.string(), mask.string(), out.string());
  if (!heatmap.empty()) args += " --heatmap " + heatmap.string();
  RunResult r = runRayster(args);
  EXPECT_EQ(r.exitCode, 0) << r.output;
  std::ifstream in(out);
  if (!in) return {};
  json report = json::parse(in, nullptr, false);
  EXPECT_FALSE(report.is_discarded()) << out;
  json values;
  values["pixels"] = report.value("pixels", 0);
  values["hdr-flip"] = report["metrics"]["hdr-flip"]["mean"];
  values["relmse"] = report["metrics"]["relmse"];
  values["flip"] = report["metrics"]["flip"]["mean"];
  return values;
}

json readBudgets() {
  std::ifstream in(budgetsPath());
  if (!in) return json::object();
  json j = json::parse(in, nullptr, false);
  return j.is_discarded() ? json::object() : j;
}

void writeBudgets(const std::string& scene, const json& entry) {
  json all = readBudgets();
  all["_comment"] =
      "Frozen fidelity budgets (tests/render/test_fidelity.cpp): hybrid vs path-traced reference per "
      "scene x mask x metric; budget = measured x margin; noiseFloor = reference seed 1 vs seed 2. "
      "Re-freeze: RAYSTER_FIDELITY_BLESS=1 ./build/tests/rayster_tests --gtest_filter='Fidelity*'";
  all["size"] = {kWidth, kHeight};
  all["hybridFrames"] = kHybridFrames;
  all["margin"] = kMargin;
  all["scenes"][scene] = entry;
  std::ofstream(budgetsPath()) << all.dump(2) << "\n";
}

void checkScene(const std::string& scene) {
  const fs::path dir = testDir();
  const bool bless = std::getenv("RAYSTER_FIDELITY_BLESS") != nullptr;

  // The references: committed, the right size, real images.
  ImageF refs[2];
  for (int seed : {1, 2}) {
    auto ref = readExr(referencePath(scene, seed));
    ASSERT_TRUE(ref.ok()) << (ref.ok() ? "" : ref.error().message) << " (see tests/fidelity/refs/README.md)";
    auto empty = rejectEmpty(*ref, kWidth, kHeight);
    ASSERT_FALSE(empty.has_value()) << referencePath(scene, seed) << ": " << *empty;
    refs[seed - 1] = std::move(ref).value();
  }

  // The hybrid frame with its default settings (automatic exposure, probes), denoised and
  // TAA-resolved, with the AOVs the masks are built from.
  analytic::Rendered hybrid = analytic::renderHdr(dir, "hybrid", sceneSource(scene), kWidth, kHeight, kHybridFrames,
                                                  "depth,material,shadow-denoised",
                                                  fmt::format("--seed {} --taa on --primary raster", kHybridSeed));
  ASSERT_FALSE(hybrid.hdr.empty());
  ASSERT_EQ(hybrid.aovs.size(), 3u);
  EXPECT_NE(hybrid.hdr.rgba, refs[0].rgba) << "the hybrid frame is not the reference";

  const auto masks = buildMasks(hybrid.aovs["depth"], hybrid.aovs["material"], hybrid.aovs["shadow-denoised"]);
  const json budgets = readBudgets();
  const json* frozen =
      budgets.contains("scenes") && budgets["scenes"].contains(scene) ? &budgets["scenes"][scene] : nullptr;
  if (!bless) {
    ASSERT_NE(frozen, nullptr) << "no budgets for " << scene << " in " << budgetsPath();
  }

  json entry = json::object();
  for (const auto& name : kMaskNames) {
    const Image8& mask = masks.at(name);
    const size_t pixels = coverage(mask);
    const bool budgeted = frozen && frozen->contains(name);
    if (pixels < kMinMaskPixels) {
      EXPECT_FALSE(budgeted) << scene << "/" << name << " has a budget but its mask now covers " << pixels << " pixels";
      std::printf("[fidelity] %-8s %-10s %5zu pixels: too few, no budget\n", scene.c_str(), name.c_str(), pixels);
      continue;
    }
    const fs::path maskPng = dir / fmt::format("mask-{}.png", name);
    ASSERT_TRUE(writePng(maskPng, mask).ok());
    const fs::path hybridExr = dir / "hybrid.exr";
    const json error =
        compareCli(referencePath(scene, 1), hybridExr, maskPng, dir / fmt::format("hybrid-{}.json", name));
    const json floor =
        compareCli(referencePath(scene, 1), referencePath(scene, 2), maskPng, dir / fmt::format("floor-{}.json", name));
    ASSERT_FALSE(error.is_null() || floor.is_null());
    EXPECT_EQ(error["pixels"].get<size_t>(), pixels);

    json& e = entry[name];
    e["pixels"] = pixels;
    // Energy: the mean luminance against the reference, beside the references' own difference.
    const double refMean = maskedLuminance(refs[0], mask);
    ASSERT_GT(refMean, 0.0) << scene << "/" << name;
    const double energy = maskedLuminance(hybrid.hdr, mask) / refMean - 1.0,
                 energyFloor = maskedLuminance(refs[1], mask) / refMean - 1.0;
    const bool checked = pixels >= kMinEnergyPixels;
    const bool meets = std::abs(energy) <= kEnergyTolerance;
    e["energy"] = {{"measured", energy},
                   {"noiseFloor", energyFloor},
                   {"checked", checked},
                   {"meetsTarget", meets},
                   {"budget", meets ? kEnergyTolerance : std::abs(energy) + kEnergyGapSlack}};
    std::printf("[fidelity] %-8s %-10s %5zu pixels  energy   hybrid %+.4f  references %+.4f%s\n", scene.c_str(),
                name.c_str(), pixels, energy, energyFloor,
                !checked ? "  (too few pixels)"
                : meets  ? ""
                         : "  KNOWN GAP: outside the ±5 % target");
    if (checked && !bless) {
      EXPECT_LE(std::abs(energyFloor), kEnergyTolerance / 2)
          << scene << "/" << name << ": the references differ by " << energyFloor << "; render them with more samples";
      ASSERT_TRUE(budgeted && (*frozen)[name].contains("energy"))
          << scene << "/" << name << ": no frozen energy budget";
      const json& b = (*frozen)[name]["energy"];
      const double budget = b["meetsTarget"].get<bool>() ? kEnergyTolerance : b["budget"].get<double>();
      EXPECT_LE(std::abs(energy), budget) << scene << "/" << name << ": mean luminance " << energy
                                          << " from the path tracer's, over its budget " << budget;
    }
    for (const auto& metric : kMetrics) {
      const double value = error[metric].get<double>(), noise = floor[metric].get<double>();
      std::printf("[fidelity] %-8s %-10s %5zu pixels  %-8s hybrid %.5f  noise floor %.5f", scene.c_str(), name.c_str(),
                  pixels, metric.c_str(), value, noise);
      EXPECT_GT(value, 0.0) << scene << "/" << name << "/" << metric << ": the hybrid is not the reference";
      // relMSE of an unconverged reference is dominated by its fireflies (caustics through glass), so
      // its floor can exceed the hybrid's error; bless records whether the floor is under the budget and
      // the test holds every floor that was to staying there (docs/fidelity.md discusses the others).
      e[metric] = {{"measured", value},
                   {"budget", value * kMargin},
                   {"noiseFloor", noise},
                   {"floorBelowBudget", noise < value * kMargin}};
      if (budgeted && !bless) {
        const json& b = (*frozen)[name][metric];
        const double budget = b["budget"].get<double>();
        std::printf("  budget %.5f\n", budget);
        EXPECT_LE(value, budget) << scene << "/" << name << "/" << metric << " over its frozen budget";
        if (b.value("floorBelowBudget", true))
          EXPECT_LT(noise, budget) << scene << "/" << name << "/" << metric
                                   << ": the references' own noise reaches the budget; render them with more samples";
        else
          std::printf("[fidelity] %s/%s/%s: noise floor %.5f over the budget (unconverged reference), not asserted\n",
                      scene.c_str(), name.c_str(), metric.c_str(), noise);
      } else {
        std::printf("\n");
        if (!bless) ADD_FAILURE() << scene << "/" << name << " (" << pixels << " pixels) has no frozen budget";
      }
    }
  }
  if (bless) writeBudgets(scene, entry);
}

TEST(Fidelity, Whitted) { checkScene("whitted"); }
TEST(Fidelity, Cornell) { checkScene("cornell"); }
TEST(Fidelity, Spheres) { checkScene("spheres"); }
// The Blender corpus (docs/corpus.md): a room lit by one point light, an atrium lit through its
// roof by the sun, a product shot under an HDR environment, alpha-masked foliage under sun and sky.
TEST(Fidelity, BlenderRoom) { checkScene("room"); }
TEST(Fidelity, BlenderAtrium) { checkScene("atrium"); }
TEST(Fidelity, BlenderProduct) { checkScene("product"); }
TEST(Fidelity, BlenderFoliage) { checkScene("foliage"); }

}  // namespace
}  // namespace rayster::test
