// fidelity_masks STEM OUTDIR: reads STEM.depth.exr, STEM.material.exr and STEM.shadow-denoised.exr
// (written by `rayster render --aov depth,material,shadow-denoised -o STEM.png`) and writes
// OUTDIR/mask-NAME.png for every fidelity mask, printing each one's pixel count.
// Used by scripts/fidelity-report.sh; the test builds the same masks in-process.
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/image_io.h"
#include "core/metrics.h"
#include "tests/fidelity/masks.h"

int main(int argc, char** argv) {
  using namespace rayster;
  if (argc != 3) {
    std::fprintf(stderr, "usage: fidelity_masks STEM OUTDIR\n");
    return 2;
  }
  const std::string stem = argv[1];
  const std::filesystem::path outDir = argv[2];
  ImageF aov[3];
  const char* names[3] = {"depth", "material", "shadow-denoised"};
  for (int i = 0; i < 3; ++i) {
    auto img = readExr(stem + "." + names[i] + ".exr");
    if (!img.ok()) {
      std::fprintf(stderr, "fidelity_masks: %s\n", img.error().message.c_str());
      return 3;
    }
    aov[i] = std::move(img).value();
  }
  for (const auto& [name, mask] : fidelity::buildMasks(aov[0], aov[1], aov[2])) {
    if (!writePng(outDir / ("mask-" + name + ".png"), mask).ok()) return 8;
    std::printf("%s %zu\n", name.c_str(), maskFromImage(mask).count());
  }
  return 0;
}
