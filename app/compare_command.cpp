// `rayster compare REF TEST`: how far one image is from another. FLIP and relMSE come with the
// fidelity work; this reports what the golden tests use.
#include <cstdio>
#include <filesystem>

#include "app/render_command.h"
#include "core/image_io.h"
#include "core/metrics.h"

namespace rayster::app {

int compareCommand(const CompareOptions& o) {
  auto load = [](const std::string& path) -> Result<Image8> {
    std::string ext = std::filesystem::path(path).extension().string();
    if (ext == ".png" || ext == ".PNG") return readPng(path);
    auto linear = readImageLinear(path);
    if (!linear) return linear.error();
    return encodeSrgb8(*linear);
  };
  auto ref = load(o.reference);
  if (!ref) return std::fprintf(stderr, "rayster: error: %s\n", ref.error().message.c_str()), int(ref.error().code);
  auto test = load(o.test);
  if (!test) return std::fprintf(stderr, "rayster: error: %s\n", test.error().message.c_str()), int(test.error().code);
  if (ref->width != test->width || ref->height != test->height) {
    std::fprintf(stderr, "rayster: error: sizes differ: %dx%d vs %dx%d\n", ref->width, ref->height, test->width,
                 test->height);
    return int(ExitCode::BadInput);
  }
  ImageDiff d = compare(*ref, *test, o.tolerance);
  std::printf("within %d/255: %.4f%% of pixels; max channel diff %d; RMSE %.5f; PSNR %.2f dB\n", o.tolerance,
              100.0 * d.fractionWithinTolerance, d.maxChannelDiff, d.rmse, d.psnr);
  if (!o.heatmap.empty())
    if (auto s = writePng(o.heatmap, d.heatmap); !s) return std::fprintf(stderr, "rayster: error: %s\n", s.error().message.c_str()), int(s.error().code);
  if (o.minFraction >= 0 && d.fractionWithinTolerance < o.minFraction) {
    std::printf("over budget: %.4f%% < %.4f%%\n", 100.0 * d.fractionWithinTolerance, 100.0 * o.minFraction);
    return int(ExitCode::TestFailed);
  }
  return 0;
}

} // namespace rayster::app
