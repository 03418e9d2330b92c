// Loading big files: images decoded in parallel keep the sequential loader's results and its
// first-error-wins message, and progress lines appear only for phases that run long
// (core/load_progress.h). RAYSTER_PROGRESS_MS=0 stands in for a big scene: every phase is "long".
#include <cstdlib>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "core/load_progress.h"
#include "gltf_test_util.h"
#include "scene/loader.h"

using namespace rayster;
using namespace rayster::test;

namespace {

// Sets RAYSTER_PROGRESS_MS for one scope.
class ProgressThreshold {
 public:
  explicit ProgressThreshold(const char* ms) {
    if (const char* old = std::getenv("RAYSTER_PROGRESS_MS")) old_ = old, had_ = true;
    if (ms)
      setenv("RAYSTER_PROGRESS_MS", ms, 1);
    else
      unsetenv("RAYSTER_PROGRESS_MS");
  }
  ~ProgressThreshold() {
    if (had_)
      setenv("RAYSTER_PROGRESS_MS", old_.c_str(), 1);
    else
      unsetenv("RAYSTER_PROGRESS_MS");
  }

 private:
  std::string old_;
  bool had_ = false;
};

// A quad with `count` materials, each showing its own PNG (image i is i+1 pixels wide, its red
// channel i * 10), and one node per material.
Doc texturedDoc(const TempDir& dir, int count) {
  Doc d = quadDoc();
  for (int i = 0; i < count; ++i) {
    Image8 img = Image8::make(i + 1, 2);
    for (size_t p = 0; p < img.rgba.size(); p += 4) img.rgba[p] = uint8_t(i * 10), img.rgba[p + 3] = 255;
    const std::string name = fmt::format("t{}.png", i);
    EXPECT_TRUE(writePng(dir.path() / name, img).ok());
    d.j["images"].push_back({{"uri", name}});
    d.j["textures"].push_back({{"source", i}});
    d.j["materials"].push_back(
        {{"name", fmt::format("m{}", i)}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", i}}}}}});
  }
  primitive(d)["material"] = 0;
  return d;
}

size_t count(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

}  // namespace

TEST(LoaderProgress, SmallSceneLoadsSilently) {
  ProgressThreshold threshold(nullptr);  // the default, 0.5 s
  TempDir dir;
  Doc d = texturedDoc(dir, 3);
  ::testing::internal::CaptureStderr();
  Result<scene::Scene> s = loadBytes(dir, d.gltf());
  const std::string err = ::testing::internal::GetCapturedStderr();
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(err.find("loading "), std::string::npos) << err;
}

TEST(LoaderProgress, LongPhasesPrintCountsAndTimes) {
  ProgressThreshold threshold("0");
  TempDir dir;
  Doc d = texturedDoc(dir, 6);
  ::testing::internal::CaptureStderr();
  Result<scene::Scene> s = loadBytes(dir, d.gltf());
  const std::string err = ::testing::internal::GetCapturedStderr();
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(count(err, "rayster: loading test.gltf: 6/6 textures decoded in "), 1u) << err;
  EXPECT_GE(count(err, "/6 textures decoded\n"), 1u) << err;  // intermediate counts
  EXPECT_EQ(count(err, "rayster: loading test.gltf: parse took "), 1u) << err;
}

TEST(LoaderProgress, ParallelDecodeKeepsImageOrderAndPixels) {
  TempDir dir;
  Doc d = texturedDoc(dir, 12);
  Result<scene::Scene> s = loadBytes(dir, d.gltf());
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_EQ(s->images.size(), 12u);
  for (int i = 0; i < 12; ++i) {
    const scene::ImageData& img = s->images[size_t(i)];
    EXPECT_EQ(img.width, i + 1);
    EXPECT_EQ(img.rgba.at(0), uint8_t(i * 10));
  }
}

TEST(LoaderProgress, FirstBrokenImageWinsWhateverFinishesFirst) {
  TempDir dir;
  Doc d = texturedDoc(dir, 8);
  // Images 3 and 6 are not PNGs; 3 is the one sequential decoding stopped at.
  dir.write("t3.png", "not a png");
  dir.write("t6.png", "not a png either");
  for (int run = 0; run < 4; ++run) {
    Result<scene::Scene> s = loadBytes(dir, d.gltf());
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().code, ExitCode::BadInput);
    EXPECT_NE(s.error().message.find("image 3 cannot be decoded"), std::string::npos) << s.error().message;
    EXPECT_EQ(s.error().message.find('\n'), std::string::npos) << s.error().message;
  }
}

TEST(LoaderProgress, PhaseWithoutCountsSaysOnlyItsTimeWhenSlow) {
  ProgressThreshold threshold("0");
  ::testing::internal::CaptureStderr();
  { LoadProgress p("loading x.glb", "BLAS build"); }
  std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(count(err, "rayster: loading x.glb: BLAS build took "), 1u) << err;
  ProgressThreshold later("100000");
  ::testing::internal::CaptureStderr();
  {
    LoadProgress p("loading x.glb", "textures decoded", 4);
    for (int i = 0; i < 4; ++i) p.advance();
  }
  err = ::testing::internal::GetCapturedStderr();
  EXPECT_TRUE(err.empty()) << err;
}
