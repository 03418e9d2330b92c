// Golden images per effect (issue 4): each denoised stage of the hybrid frame of builtin:cornell
// and builtin:whitted, written by --aov, against its golden — so a change to one effect shows up
// as that effect's image, not only as a changed final frame.
#include <filesystem>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "tests/render/golden.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

constexpr int kW = 160, kH = 120;
const char* const kStages[] = {"shadow-denoised", "reflection-denoised", "ao-denoised", "indirect-denoised"};

void expectStagesMatchGoldens(const std::string& scene) {
  auto dir = testDir();
  std::string aovs;
  for (const char* s : kStages) aovs += std::string(aovs.empty() ? "" : ",") + s;
  renderOk(dir, scene, "builtin:" + scene + " --primary raster --frames 8 --seed 1 --aov " + aovs, kW, kH);
  for (const char* stage : kStages) {
    auto img = readPng(dir / (scene + "." + stage + ".png"));
    ASSERT_TRUE(img.ok()) << stage;
    auto empty = rejectEmpty(*img, kW, kH);
    EXPECT_FALSE(empty.has_value()) << stage << ": " << empty.value_or("");
    expectMatchesGolden(*img, scene + "-" + stage + "-160x120", dir);
  }
}

TEST(EffectGoldens, Cornell) { expectStagesMatchGoldens("cornell"); }
TEST(EffectGoldens, Whitted) { expectStagesMatchGoldens("whitted"); }

} // namespace
} // namespace rayster::test
