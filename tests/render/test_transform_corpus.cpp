// The glTF-Transform corpus (assets/corpus/transform, made by scripts/corpus/make_transform_corpus.sh
// with @gltf-transform/cli; docs/gltf-compression.md): the Khronos validator finds no error in any
// file, Rayster loads every one, and each compressed or restructured variant renders the picture
// of its uncompressed source through the same camera.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include "scene/loader.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

namespace fs = std::filesystem;
const fs::path kDir = fs::path(RAYSTER_SOURCE_DIR) / "assets" / "corpus" / "transform";

// Each variant and the source it was made from.
const std::map<std::string, std::string> kVariants = {
    {"quantize.glb", "source.glb"}, {"meshopt.glb", "source.glb"},          {"meshopt-gltf/meshopt.gltf", "source.glb"},
    {"draco.glb", "source.glb"},    {"draco-sequential.glb", "source.glb"}, {"merge.glb", "source.glb"},
    {"instance.glb", "source.glb"}, {"instance-meshopt.glb", "source.glb"}, {"dedup.glb", "source.glb"},
    {"weld.glb", "source.glb"},     {"room-meshopt.glb", "room.glb"},       {"room-draco.glb", "room.glb"},
};

// Raster mode: deterministic, and every pixel is a function of geometry, normals, UVs and the
// texture, which is what compression changes. The tolerance, from what the compressed files
// quantize (gltf-transform's defaults) at this size (a pixel spans 4 to 6 cm of the scene):
//  - positions, 14 bits over each mesh's box: at most 0.4 mm, under 1 % of a pixel, so only
//    pixels an edge passes within 1 % of their centre change coverage. Those can change by the
//    full contrast of the two surfaces (the floor's far edge against the black sky: 113/255 in
//    draco.glb), so no bound on the largest difference, only on how many pixels and the RMSE;
//  - normals, 8 to 10 bits octahedral: under half a degree, so N·L and the highlights move by
//    about 1 %: a few 1/255 steps on lit surfaces, up to 18/255 on the spheres' highlights;
//  - UVs, 12 bits: 1/60 of a texel of the 64-texel checker, a blend of 3/255 at its edges.
// Measured (lavapipe, 160x120): at most 8 pixels beyond 6/255 (meshopt), RMSE at most 0.0044
// (draco, its two edge pixels). Required: 99.5 % of the pixels (all but 96) within 6/255 and an
// RMSE under 3/255 (a handful of full-contrast edge flips), far below what a wrong attribute,
// a missing instance or a lost texture costs (merge.glb with one half missing: RMSE 0.43).
constexpr int kSize[2] = {160, 120};
constexpr int kChannelTolerance = 6;
constexpr double kFractionWithin = 0.995;
constexpr double kMaxRmse = 3.0 / 255.0;

std::string quoted(const std::string& s) { return "'" + s + "'"; }

TEST(TransformCorpus, ValidatorFindsNoErrorAndRaysterLoadsEveryFile) {
  const fs::path module = fs::path(RAYSTER_SOURCE_DIR) / "tools" / "npm" / "node_modules" / "gltf-validator";
  std::vector<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(kDir))
    if (e.path().extension() == ".gltf" || e.path().extension() == ".glb") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  ASSERT_EQ(files.size(), kVariants.size() + 2) << "every file in the corpus is a variant or a source";
  for (const std::string& f : files) {
    auto scene = scene::loadScene(f);
    EXPECT_TRUE(scene.ok()) << f << ": " << scene.error().message;
  }
  if (std::system("command -v node >/dev/null 2>&1") != 0 || !fs::exists(module))
    GTEST_SKIP() << "node or tools/npm/node_modules/gltf-validator is missing (scripts/setup.sh installs both)";
  std::string cmd = "GLTF_VALIDATOR_MODULE=" + quoted(module.string()) + " node " +
                    quoted((fs::path(RAYSTER_SOURCE_DIR) / "tools" / "gltf-validate.js").string());
  for (const std::string& f : files) cmd += " " + quoted(f);
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  size_t reports = 0;
  char line[8192];
  while (std::fgets(line, sizeof line, pipe)) {
    const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
    if (j.is_discarded()) continue;
    ++reports;
    EXPECT_EQ(j["errors"].get<int>(), 0) << j["file"] << ": " << j["first"];
  }
  EXPECT_EQ(pclose(pipe), 0);
  EXPECT_EQ(reports, files.size());
}

TEST(TransformCorpus, EveryVariantRendersLikeItsSource) {
  auto dir = testDir();
  const std::string common = " --mode raster --frames 1 --seed 1";
  std::map<std::string, Image8> sources;
  for (const auto& [variant, source] : kVariants) {
    if (!sources.count(source))
      sources[source] =
          renderOk(dir, fs::path(source).stem().string(), (kDir / source).string() + common, kSize[0], kSize[1]);
    const std::string stem = fs::path(variant).stem().string() + "-variant";
    const Image8 image = renderOk(dir, stem, (kDir / variant).string() + common, kSize[0], kSize[1]);
    const Image8& reference = sources[source];
    ASSERT_FALSE(reference.empty());
    if (image.empty()) continue;  // renderOk said why
    const ImageDiff diff = compare(reference, image, kChannelTolerance);
    EXPECT_GE(diff.fractionWithinTolerance, kFractionWithin) << variant;
    EXPECT_LE(diff.rmse, kMaxRmse) << variant;
    std::printf("%-28s vs %-10s: max %3d/255, %.4f within %d/255, rmse %.5f\n", variant.c_str(), source.c_str(),
                diff.maxChannelDiff, diff.fractionWithinTolerance, kChannelTolerance, diff.rmse);
    if (diff.fractionWithinTolerance < kFractionWithin || diff.rmse > kMaxRmse)
      (void)writePng(dir / (stem + "-diff.png"), diff.heatmap);
  }
}

// A corrupt compressed stream in a real file: exit code 3 (bad input), one error line naming the
// JSON path, and no image.
TEST(TransformCorpus, CorruptStreamsExitWithOneLineAndNoImage) {
  auto dir = testDir();
  const std::pair<const char*, std::string> cases[] = {
      {"draco.glb", "extensions.KHR_draco_mesh_compression: Draco cannot decode"},
      {"meshopt.glb", "extensions.EXT_meshopt_compression: "}};
  for (const auto& [name, expected] : cases) {
    std::ifstream in(kDir / name, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    // Draco streams start with "DRACO"; meshopt vertex streams with 0xA0: break the first of each.
    size_t at = bytes.find("DRACO");
    if (std::string(name) == "meshopt.glb") {
      uint32_t jsonLength = 0;
      std::memcpy(&jsonLength, bytes.data() + 12, 4);
      const nlohmann::json json = nlohmann::json::parse(bytes.substr(20, jsonLength));
      at = std::string::npos;
      for (const auto& view : json["bufferViews"])
        if (view.contains("extensions") && view["extensions"]["EXT_meshopt_compression"]["mode"] == "ATTRIBUTES") {
          at = 20 + jsonLength + 8 + view["extensions"]["EXT_meshopt_compression"].value("byteOffset", size_t(0));
          break;
        }
    }
    ASSERT_NE(at, std::string::npos) << name;
    for (size_t i = at + 5; i < at + 40 && i < bytes.size(); ++i) bytes[i] = char(0xFF);
    if (std::string(name) == "meshopt.glb") bytes[at] = char(0xA7);
    const fs::path broken = dir / (std::string("broken-") + name);
    std::ofstream(broken, std::ios::binary) << bytes;
    const fs::path out = dir / "broken.png";
    RunResult r = runRayster("render " + broken.string() + " --mode raster --size 32x24 --frames 1 -o " + out.string());
    EXPECT_EQ(r.exitCode, 3) << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << r.output;
    size_t errors = 0;
    for (size_t at = r.output.find("rayster: error: "); at != std::string::npos;
         at = r.output.find("rayster: error: ", at + 1))
      ++errors;
    EXPECT_EQ(errors, 1u) << r.output;
    EXPECT_FALSE(fs::exists(out));
  }
}

}  // namespace
}  // namespace rayster::test
