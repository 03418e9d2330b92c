// `rayster compare` through the real binary: metrics, JSON, heatmap, masks, budgets and bad inputs.
// No GPU involved, so these run quickly on any machine.
#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "run_rayster.h"

using namespace rayster;
using namespace rayster::test;
namespace fs = std::filesystem;

namespace {

Image8 checker(int w, int h, uint8_t shift) {
  Image8 image = Image8::make(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* p = image.pixel(x, y);
      p[0] = static_cast<uint8_t>(((x / 4 + y / 4) % 2) * 180 + 30 + shift);
      p[1] = static_cast<uint8_t>(4 * x + shift);
      p[2] = static_cast<uint8_t>(3 * y);
      p[3] = 255;
    }
  return image;
}

struct Pair {
  fs::path dir, ref, test;
};
Pair writePair(uint8_t shift) {
  Pair p{testDir(), {}, {}};
  p.ref = p.dir / "ref.png";
  p.test = p.dir / "test.png";
  EXPECT_TRUE(writePng(p.ref, checker(48, 32, 0)).ok());
  EXPECT_TRUE(writePng(p.test, checker(48, 32, shift)).ok());
  return p;
}

nlohmann::json readJson(const fs::path& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  return nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
}

int lineCount(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

}  // namespace

TEST(CompareCli, IdenticalImages) {
  Pair p = writePair(0);
  const fs::path json = p.dir / "r.json";
  RunResult r = runRayster("compare " + p.ref.string() + " " + p.ref.string() + " --json " + json.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json j = readJson(json);
  EXPECT_EQ(j["metrics"]["flip"]["mean"], 0.0);
  EXPECT_EQ(j["metrics"]["hdr-flip"]["mean"], 0.0);
  EXPECT_TRUE(j["metrics"]["psnr"].is_null()) << "infinite PSNR is written as null";
  EXPECT_EQ(j["metrics"]["rmse"], 0.0);
  EXPECT_EQ(j["metrics"]["relmse"], 0.0);
  EXPECT_NE(r.output.find("psnr      inf"), std::string::npos) << r.output;
}

TEST(CompareCli, JsonHasEveryFieldAndHeatmapIsWritten) {
  Pair p = writePair(20);
  const fs::path json = p.dir / "out" / "r.json", heat = p.dir / "out" / "heat.png";
  RunResult r = runRayster("compare " + p.ref.string() + " " + p.test.string() + " --json " + json.string() +
                           " --heatmap " + heat.string() + " --ppd 40");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json j = readJson(json);
  for (const char* key : {"reference", "test", "width", "height", "mask", "pixels", "ppd", "metrics", "tolerance",
                          "budgets", "overBudget", "heatmap", "rmsePsnrValues"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["width"], 48);
  EXPECT_EQ(j["pixels"], 48 * 32);
  EXPECT_EQ(j["ppd"], 40.0);
  EXPECT_EQ(j["rmsePsnrValues"], "srgb");
  const auto& m = j["metrics"];
  EXPECT_GT(m["flip"]["mean"].get<double>(), 0.0);
  EXPECT_LE(m["flip"]["mean"].get<double>(), m["flip"]["max"].get<double>());
  EXPECT_GT(m["hdr-flip"]["mean"].get<double>(), 0.0);
  EXPECT_TRUE(m["hdr-flip"]["exposures"].contains("start"));
  EXPECT_GE(m["hdr-flip"]["exposures"]["count"].get<int>(), 2);
  EXPECT_GT(m["psnr"].get<double>(), 10.0);
  EXPECT_GT(m["rmse"].get<double>(), 0.0);
  EXPECT_GT(m["relmse"].get<double>(), 0.0);
  EXPECT_EQ(j["overBudget"], false);
  EXPECT_EQ(j["heatmap"]["shows"], "flip");
  auto image = readPng(heat);
  ASSERT_TRUE(image.ok());
  EXPECT_EQ(image->width, 48);
  EXPECT_EQ(image->height, 32);
  // sRGB steps of 20 in red and green are 20/255 in RMSE terms at most.
  EXPECT_LE(m["rmse"].get<double>(), 20.0 / 255.0 + 1e-6);
}

TEST(CompareCli, SelectedMetricsOnly) {
  Pair p = writePair(10);
  const fs::path json = p.dir / "r.json";
  RunResult r =
      runRayster("compare " + p.ref.string() + " " + p.test.string() + " --metric psnr,rmse --json " + json.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json j = readJson(json);
  EXPECT_TRUE(j["metrics"].contains("psnr"));
  EXPECT_TRUE(j["metrics"].contains("rmse"));
  EXPECT_FALSE(j["metrics"].contains("flip"));
  EXPECT_FALSE(j["metrics"].contains("relmse"));
}

TEST(CompareCli, BudgetsSetTheExitCode) {
  Pair p = writePair(20);
  const std::string args = "compare " + p.ref.string() + " " + p.test.string() + " --metric flip ";
  RunResult within = runRayster(args + "--budget flip=0.9 --budget psnr=5");
  EXPECT_EQ(within.exitCode, 0) << within.output;
  RunResult over = runRayster(args + "--budget flip=0.0001");
  EXPECT_EQ(over.exitCode, 9) << over.output;
  EXPECT_NE(over.output.find("over budget: flip"), std::string::npos) << over.output;
  RunResult psnr = runRayster(args + "--budget rmse=1,psnr=200");  // psnr is a minimum
  EXPECT_EQ(psnr.exitCode, 9) << psnr.output;
  EXPECT_NE(psnr.output.find("over budget: psnr"), std::string::npos) << psnr.output;
  // The legacy tolerance budget still works.
  EXPECT_EQ(runRayster(args + "--min-fraction 1.0").exitCode, 9);
  EXPECT_EQ(runRayster(args + "--tolerance 30 --min-fraction 1.0").exitCode, 0);
  // The JSON records the verdict even when over budget.
  const fs::path json = p.dir / "over.json";
  EXPECT_EQ(runRayster(args + "--budget hdr-flip=0.00001 --json " + json.string()).exitCode, 9);
  const nlohmann::json j = readJson(json);
  EXPECT_EQ(j["overBudget"], true);
  ASSERT_EQ(j["budgets"].size(), 1u);
  EXPECT_EQ(j["budgets"][0]["metric"], "hdr-flip");
  EXPECT_EQ(j["budgets"][0]["pass"], false);
}

TEST(CompareCli, MaskRestrictsTheMean) {
  // Left half identical, right half different: a mask of the left half sees no error.
  Pair p{testDir(), {}, {}};
  p.ref = p.dir / "ref.png";
  p.test = p.dir / "test.png";
  Image8 ref = checker(64, 32, 0), test = ref, mask = Image8::make(64, 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      if (x >= 32) test.pixel(x, y)[1] = 255;
      if (x < 8) mask.pixel(x, y)[0] = 255;  // far from the changed half (FLIP's filters reach ~20 px)
    }
  ASSERT_TRUE(writePng(p.ref, ref).ok());
  ASSERT_TRUE(writePng(p.test, test).ok());
  ASSERT_TRUE(writePng(p.dir / "mask.png", mask).ok());
  const fs::path all = p.dir / "all.json", masked = p.dir / "masked.json";
  const std::string args = "compare " + p.ref.string() + " " + p.test.string();
  ASSERT_EQ(runRayster(args + " --json " + all.string()).exitCode, 0);
  RunResult r = runRayster(args + " --mask " + (p.dir / "mask.png").string() + " --json " + masked.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json a = readJson(all), m = readJson(masked);
  EXPECT_GT(a["metrics"]["flip"]["mean"].get<double>(), 0.1);
  EXPECT_EQ(m["metrics"]["flip"]["mean"], 0.0);
  EXPECT_EQ(m["metrics"]["rmse"], 0.0);
  EXPECT_EQ(m["pixels"], 8 * 32);
  // A mask that covers nothing, or of another size, is refused.
  ASSERT_TRUE(writePng(p.dir / "empty.png", Image8::make(64, 32)).ok());
  RunResult empty = runRayster(args + " --mask " + (p.dir / "empty.png").string());
  EXPECT_EQ(empty.exitCode, 3) << empty.output;
  EXPECT_NE(empty.output.find("covers no pixel"), std::string::npos) << empty.output;
  ASSERT_TRUE(writePng(p.dir / "small.png", checker(8, 8, 0)).ok());
  EXPECT_EQ(runRayster(args + " --mask " + (p.dir / "small.png").string()).exitCode, 3);
}

TEST(CompareCli, HdrInputs) {
  const fs::path dir = testDir();
  ImageF ref = ImageF::make(40, 30);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      float* px = ref.pixel(x, y);
      px[0] = 0.05f * static_cast<float>(x);  // up to ~2: beyond LDR
      px[1] = 0.5f;
      px[2] = (x + y) % 7 == 0 ? 8.0f : 0.2f;
      px[3] = 1.0f;
    }
  ImageF doubled = ref;
  for (size_t i = 0; i < doubled.rgba.size(); ++i)
    if (i % 4 != 3) doubled.rgba[i] *= 2.0f;
  ASSERT_TRUE(writeExr(dir / "ref.exr", ref).ok());
  ASSERT_TRUE(writeExr(dir / "test.exr", doubled).ok());
  const fs::path json = dir / "r.json", heat = dir / "heat.png";
  RunResult r = runRayster("compare " + (dir / "ref.exr").string() + " " + (dir / "test.exr").string() +
                           " --metric hdr-flip,relmse,psnr --json " + json.string() + " --heatmap " + heat.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json j = readJson(json);
  EXPECT_GT(j["metrics"]["hdr-flip"]["mean"].get<double>(), 0.05);
  EXPECT_EQ(j["rmsePsnrValues"], "linear");
  EXPECT_EQ(j["heatmap"]["shows"], "hdr-flip");
  // relMSE of test = 2 ref: (ref)^2 / (ref^2 + 0.01), well below 1 but clearly nonzero.
  EXPECT_GT(j["metrics"]["relmse"].get<double>(), 0.3);
  EXPECT_LT(j["metrics"]["relmse"].get<double>(), 1.0);
  EXPECT_TRUE(fs::exists(heat));
}

TEST(CompareCli, BadInputsGetOneLineErrors) {
  Pair p = writePair(0);
  const std::string ref = p.ref.string();
  RunResult missing = runRayster("compare " + ref + " " + (p.dir / "nope.png").string());
  EXPECT_EQ(missing.exitCode, 3) << missing.output;
  EXPECT_NE(missing.output.find("nope.png"), std::string::npos) << missing.output;
  EXPECT_EQ(lineCount(missing.output), 1) << missing.output;

  ASSERT_TRUE(writePng(p.dir / "small.png", checker(16, 16, 0)).ok());
  RunResult size = runRayster("compare " + ref + " " + (p.dir / "small.png").string());
  EXPECT_EQ(size.exitCode, 3) << size.output;
  EXPECT_NE(size.output.find("sizes differ"), std::string::npos) << size.output;
  EXPECT_EQ(lineCount(size.output), 1) << size.output;

  {
    std::ofstream junk(p.dir / "junk.png");
    junk << "not a png";
  }
  RunResult corrupt = runRayster("compare " + ref + " " + (p.dir / "junk.png").string());
  EXPECT_EQ(corrupt.exitCode, 3) << corrupt.output;
  EXPECT_EQ(lineCount(corrupt.output), 1) << corrupt.output;

  RunResult format = runRayster("compare " + ref + " " + (p.dir / "x.bmp").string());
  EXPECT_EQ(format.exitCode, 2) << format.output;

  const fs::path heat = p.dir / "heat.jpg";
  RunResult badHeat = runRayster("compare " + ref + " " + ref + " --heatmap " + heat.string());
  EXPECT_EQ(badHeat.exitCode, 2) << badHeat.output;
  EXPECT_FALSE(fs::exists(heat));
  EXPECT_EQ(runRayster("compare " + ref + " " + ref + " --metric ssim").exitCode, 2);
  EXPECT_EQ(runRayster("compare " + ref + " " + ref + " --budget flip").exitCode, 2);
  EXPECT_EQ(runRayster("compare " + ref + " " + ref + " --budget mse=3").exitCode, 2);
  EXPECT_EQ(runRayster("compare " + ref + " " + ref + " --ppd 0").exitCode, 2);
  EXPECT_EQ(runRayster("compare " + ref).exitCode, 2);
  // A failed run leaves no output behind.
  const fs::path json = p.dir / "none.json";
  EXPECT_EQ(runRayster("compare " + ref + " " + (p.dir / "small.png").string() + " --json " + json.string()).exitCode,
            3);
  EXPECT_FALSE(fs::exists(json));
}
