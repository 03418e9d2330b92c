// On a CPU device (lavapipe) `rayster render` without --size/--frames picks a smaller default and
// says so in one line; explicit flags win. In a pipe (as here: popen) it prints progress lines.
#include <regex>

#include <gtest/gtest.h>

#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

struct Progress {
  std::vector<uint32_t> done;
  uint32_t total = 0;
};

// Every "rayster: frame K/N (P%), T s" line.
Progress progressLines(const std::string& output) {
  Progress p;
  static const std::regex line(R"(rayster: frame (\d+)/(\d+) \((\d+)%\), [0-9.]+ s)");
  for (auto it = std::sregex_iterator(output.begin(), output.end(), line); it != std::sregex_iterator(); ++it) {
    p.done.push_back(uint32_t(std::stoul((*it)[1])));
    p.total = uint32_t(std::stoul((*it)[2]));
    EXPECT_EQ(std::stoul((*it)[3]), p.done.back() * 100 / p.total) << it->str();
  }
  return p;
}

size_t count(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST(CpuDefaults, ReadmeCommandPicksTheCpuSizeAndShowsProgress) {
  auto dir = testDir();
  RunResult r = runRayster("render -o " + (dir / "whitted.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::smatch m;
  static const std::regex said(
      R"(rayster: CPU device [^:\n]+: rendering (\d+)x(\d+), (\d+) frames by default \(--size/--frames to override\))");
  ASSERT_TRUE(std::regex_search(r.output, m, said)) << r.output;
  EXPECT_EQ(count(r.output, "by default"), 1u) << r.output;
  const int w = std::stoi(m[1]), h = std::stoi(m[2]);
  const uint32_t frames = uint32_t(std::stoul(m[3]));
  EXPECT_LT(w * h, 1280 * 720) << "smaller than the GPU default";
  auto img = readPng(dir / "whitted.png");
  ASSERT_TRUE(img.ok());
  EXPECT_EQ(img->width, w);
  EXPECT_EQ(img->height, h);
  const Progress p = progressLines(r.output);
  EXPECT_EQ(p.total, frames) << r.output;
  EXPECT_GE(p.done.size(), 2u) << r.output;
  ASSERT_FALSE(p.done.empty());
  EXPECT_EQ(p.done.back(), frames) << "the last line is the end";
  EXPECT_EQ(r.output.find('\r'), std::string::npos) << "no terminal redraws in a pipe";
}

TEST(CpuDefaults, ExplicitSizeAndFramesWin) {
  auto dir = testDir();
  RunResult r = runRayster("render builtin:cornell --size 80x60 --frames 3 -o " + (dir / "c.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("by default"), std::string::npos) << r.output;
  auto img = readPng(dir / "c.png");
  ASSERT_TRUE(img.ok());
  EXPECT_EQ(img->width, 80);
  EXPECT_EQ(img->height, 60);
  const Progress p = progressLines(r.output);
  EXPECT_EQ(p.total, 3u) << r.output;
  ASSERT_FALSE(p.done.empty()) << r.output;
  EXPECT_EQ(p.done.back(), 3u);
}

TEST(CpuDefaults, PathTracerTakesTheCpuFramesUnlessSppIsGiven) {
  auto dir = testDir();
  RunResult r = runRayster("render builtin:cornell --mode pathtrace --size 48x32 -o " + (dir / "p.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::smatch m;
  static const std::regex said(
      R"(rayster: CPU device [^:\n]+: rendering (\d+) frames by default \(--frames to override\))");
  ASSERT_TRUE(std::regex_search(r.output, m, said)) << r.output;
  const Progress p = progressLines(r.output);
  EXPECT_EQ(p.total, uint32_t(std::stoul(m[1]))) << r.output;
  auto img = readPng(dir / "p.png");
  ASSERT_TRUE(img.ok());
  EXPECT_EQ(img->width, 48);

  RunResult spp =
      runRayster("render builtin:cornell --mode pathtrace --size 48x32 --spp 2 -o " + (dir / "s.png").string());
  ASSERT_EQ(spp.exitCode, 0) << spp.output;
  EXPECT_EQ(spp.output.find("by default"), std::string::npos) << spp.output;
  EXPECT_EQ(progressLines(spp.output).total, 2u) << spp.output;
}

}  // namespace
}  // namespace rayster::test
