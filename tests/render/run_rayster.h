#pragma once
// Runs the real `rayster` binary as a user would, with validation on, and reads what it wrote.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/image.h"
#include "core/image_io.h"
#include "core/metrics.h"
#include "tests/support/test_dirs.h"

namespace rayster::test {

struct RunResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr
};

// `prefix` runs the command (e.g. under xvfb-run); stdout and stderr are one pipe. The binary
// inherits the test process's RAYSTER_CACHE_DIR (tests/support/test_dirs.h).
// Mean Rec. 709 luminance of an HDR image (linear values).
inline double meanLuminance(const ImageF& img) {
  double sum = 0;
  for (size_t i = 0; i + 3 < img.rgba.size(); i += 4)
    sum += 0.2126 * img.rgba[i] + 0.7152 * img.rgba[i + 1] + 0.0722 * img.rgba[i + 2];
  return img.rgba.empty() ? 0.0 : sum / double(img.rgba.size() / 4);
}

inline RunResult runRaysterWith(const std::string& prefix, const std::string& args, const std::string& env) {
  std::string cmd = prefix + "env XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp} RAYSTER_VALIDATION=1 " + env + " " +
                    std::string(RAYSTER_BINARY) + " " + args + " 2>&1";
  RunResult r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  while (size_t n = fread(buf.data(), 1, buf.size(), pipe)) r.output.append(buf.data(), n);
  int status = pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline RunResult runRayster(const std::string& args, const std::string& env = "") {
  return runRaysterWith("", args, env);
}

// The viewer needs a display: Xvfb, with a 24-bit screen (its default 8-bit visual has no Vulkan
// surface format).
inline bool haveXvfb() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }
// xvfb-run exits with codes of its own when it fails to clean up after the command (5: "problem
// while cleaning up temporary directory", seen once under load), replacing rayster's: the command
// runs inside `sh -c` that prints rayster's own exit code last, and that code is the result.
inline RunResult runUnderXvfb(const std::string& args, const std::string& env = "") {
  const std::string marker = "[rayster-exit ";
  RunResult r = runRaysterWith("xvfb-run -a -s '-screen 0 1024x768x24' sh -c '\"$@\"; echo \"" + marker + "$?]\"' sh ",
                               args, env);
  const size_t at = r.output.rfind(marker);
  if (at == std::string::npos) return r;  // xvfb-run failed before running the command: its code stands
  r.exitCode = std::atoi(r.output.c_str() + at + marker.size());
  const size_t end = r.output.find(']', at);
  r.output.erase(at, end == std::string::npos ? std::string::npos : end - at + 2);
  return r;
}

// Renders with `args` into dir/name.png, asserts success and a non-empty image of the given size.
inline Image8 renderOk(const std::filesystem::path& dir, const std::string& name, const std::string& args, int w,
                       int h) {
  auto out = dir / (name + ".png");
  RunResult r =
      runRayster("render " + args + " --size " + std::to_string(w) + "x" + std::to_string(h) + " -o " + out.string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  auto img = readPng(out);
  EXPECT_TRUE(img.ok()) << (img.ok() ? "" : img.error().message);
  if (!img.ok()) return {};
  auto empty = rejectEmpty(*img, w, h);
  EXPECT_FALSE(empty.has_value()) << name << ": " << empty.value_or("");
  return std::move(img).value();
}

// `rayster render ARGS -o dir/out.exr --aov LIST`; each AOV's EXR by name (a missing one fails).
inline std::map<std::string, ImageF> renderAovs(const std::filesystem::path& dir, const std::string& args,
                                                const std::vector<std::string>& aovs) {
  std::string list;
  for (const std::string& a : aovs) list += (list.empty() ? "" : ",") + a;
  auto out = dir / "out.exr";
  RunResult r = runRayster("render " + args + " --aov " + list + " -o " + out.string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  std::map<std::string, ImageF> images;
  for (const std::string& a : aovs) {
    auto img = readExr(dir / ("out." + a + ".exr"));
    EXPECT_TRUE(img.ok()) << a << "\n" << r.output;
    if (img.ok()) images[a] = std::move(*img);
  }
  return images;
}

}  // namespace rayster::test
