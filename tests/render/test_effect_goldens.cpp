// Golden images per effect (issue 4): each denoised stage of the hybrid frame of builtin:cornell
// and builtin:whitted, written by --aov, against its golden — so a change to one effect shows up
// as that effect's image, not only as a changed final frame. builtin:whitted's final frame is
// checked here too, from the same render.
#include <filesystem>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "tests/render/golden.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

constexpr int kW = 160, kH = 120;
const char* const kStages[] = {"shadow-denoised", "reflection-denoised", "ao-denoised", "indirect-denoised"};

// Renders builtin:SCENE as the goldens were made, with every stage as an AOV, into `dir`.
void renderStages(const std::filesystem::path& dir, const std::string& scene) {
  std::string aovs;
  for (const char* s : kStages) aovs += std::string(aovs.empty() ? "" : ",") + s;
  renderOk(dir, scene, "builtin:" + scene + " --primary raster --frames 8 --seed 1 --exposure 0 --aov " + aovs, kW, kH);
}

// The stages of a render in `rendered` against their goldens; failures write into `dir`.
void expectStagesMatchGoldens(const std::filesystem::path& rendered, const std::string& scene,
                              const std::filesystem::path& dir) {
  for (const char* stage : kStages) {
    auto img = readPng(rendered / (scene + "." + stage + ".png"));
    ASSERT_TRUE(img.ok()) << stage;
    auto empty = rejectEmpty(*img, kW, kH);
    EXPECT_FALSE(empty.has_value()) << stage << ": " << empty.value_or("");
    expectMatchesGolden(*img, scene + "-" + stage + "-160x120", dir);
  }
}

TEST(EffectGoldens, Cornell) {
  auto dir = testDir();
  renderStages(dir, "cornell");
  expectStagesMatchGoldens(dir, "cornell", dir);
}

// One render of builtin:whitted shared by the WhittedRun tests, which ctest runs as one test in
// one process (tests/CMakeLists.txt): the final frame and every stage against their goldens. The
// AOVs only add readbacks; the frame is the image the same command renders without them.
const std::filesystem::path& whittedRun() {
  static const std::filesystem::path dir = [] {
    const auto d = processDir() / "whitted-run";
    std::filesystem::create_directories(d);
    renderStages(d, "whitted");
    return d;
  }();
  return dir;
}

TEST(WhittedRun, FrameMatchesGolden) {
  auto frame = readPng(whittedRun() / "whitted.png");
  ASSERT_TRUE(frame.ok());
  expectMatchesGolden(*frame, "whitted-160x120", testDir());
}

TEST(WhittedRun, StagesMatchGoldens) { expectStagesMatchGoldens(whittedRun(), "whitted", testDir()); }

}  // namespace
}  // namespace rayster::test
