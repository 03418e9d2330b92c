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

#include <zstd.h>
#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include "core/bcn.h"
#include "scene/loader.h"
#include "tests/render/run_rayster.h"
#include "tests/unit/ktx2_test_util.h"

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

// The hybrid (ray-traced shadows, reflections, GI probes) sees the decoded geometry through the
// BLASes and the instances through the TLAS: the same comparison for the variants whose geometry or
// instances differ most from the source (two frames, the same seed; same tolerance).
TEST(TransformCorpus, HybridRendersOfCompressedAndInstancedVariantsMatchTheSource) {
  auto dir = testDir();
  const std::string common = " --frames 2 --seed 1";
  const Image8 reference = renderOk(dir, "source-hybrid", (kDir / "source.glb").string() + common, kSize[0], kSize[1]);
  ASSERT_FALSE(reference.empty());
  for (const char* variant : {"instance-meshopt.glb", "draco.glb", "meshopt.glb"}) {
    const std::string stem = fs::path(variant).stem().string() + "-hybrid";
    const Image8 image = renderOk(dir, stem, (kDir / variant).string() + common, kSize[0], kSize[1]);
    if (image.empty()) continue;
    const ImageDiff diff = compare(reference, image, kChannelTolerance);
    EXPECT_GE(diff.fractionWithinTolerance, kFractionWithin) << variant;
    EXPECT_LE(diff.rmse, kMaxRmse) << variant;
    std::printf("hybrid %-22s: max %3d/255, %.4f within %d/255, rmse %.5f\n", variant, diff.maxChannelDiff,
                diff.fractionWithinTolerance, kChannelTolerance, diff.rmse);
  }
}

// source.glb's checker texture as KTX2 through KHR_texture_basisu (no fallback source): RGBA8 with Zstandard
// supercompression, and BC7 (every 4 x 4 block is one checker colour, encoded exactly in mode 5). Both carry the PNG's
// texels exactly, so the render is the same image.
std::vector<uint8_t> bc7Exact(const Image8& image) {
  std::vector<uint8_t> out;
  for (int by = 0; by < image.height / 4; ++by)
    for (int bx = 0; bx < image.width / 4; ++bx) {
      const uint8_t* c = image.pixel(bx * 4, by * 4);
      // Mode 5: 7-bit endpoints c >> 1 and (c ± 1) >> 1 with every colour index 1 give c exactly.
      uint8_t block[16] = {};
      int at = 0;
      auto put = [&](int value, int bits) {
        for (int i = 0; i < bits; ++i, ++at)
          if ((value >> i) & 1) block[at >> 3] |= uint8_t(1 << (at & 7));
      };
      put(1 << 5, 6);  // mode 5
      put(0, 2);       // no rotation
      for (int k = 0; k < 3; ++k) put(c[k] >> 1, 7), put((c[k] < 128 ? c[k] + 1 : c[k] - 1) >> 1, 7);
      put(c[3], 8), put(c[3], 8);
      for (int t = 0; t < 16; ++t) put(1, t == 0 ? 1 : 2);  // colour indices
      out.insert(out.end(), block, block + 16);
    }
  return out;
}

TEST(TransformCorpus, Ktx2TexturesRenderLikeThePng) {
  auto dir = testDir();
  std::ifstream in(kDir / "source.glb", std::ios::binary);
  const std::string glb((std::istreambuf_iterator<char>(in)), {});
  uint32_t jsonLength = 0;
  std::memcpy(&jsonLength, glb.data() + 12, 4);
  nlohmann::json json = nlohmann::json::parse(glb.substr(20, jsonLength));
  const std::string bin = glb.substr(20 + jsonLength + 8);
  std::ofstream(dir / "source.bin", std::ios::binary) << bin;
  json["buffers"][0]["uri"] = "source.bin";
  const nlohmann::json& pngView = json["bufferViews"][json["images"][0]["bufferView"].get<size_t>()];
  std::ofstream(dir / "checker.png", std::ios::binary)
      << bin.substr(pngView.value("byteOffset", size_t(0)), pngView["byteLength"].get<size_t>());
  auto checker = readPng(dir / "checker.png");
  ASSERT_TRUE(checker.ok()) << checker.error().message;
  ASSERT_EQ(checker->width % 4, 0);

  std::vector<uint8_t> packed(ZSTD_compressBound(checker->rgba.size()));
  packed.resize(ZSTD_compress(packed.data(), packed.size(), checker->rgba.data(), checker->rgba.size(), 9));
  test::Ktx2Spec zstd{43, uint32_t(checker->width), uint32_t(checker->height)};
  zstd.scheme = 2;
  zstd.uncompressedLength = checker->rgba.size();
  const std::vector<uint8_t> bc7 = bc7Exact(*checker);
  for (size_t b = 0; b < bc7.size(); b += 16) {  // the encoder is exact, or this test means nothing
    uint8_t texels[16][4];
    decodeBc7(bc7.data() + b, texels);
    const int bx = int(b / 16) % (checker->width / 4), by = int(b / 16) / (checker->width / 4);
    ASSERT_EQ(std::memcmp(texels[0], checker->pixel(bx * 4, by * 4), 4), 0) << "block " << b / 16;
  }
  const std::pair<const char*, std::vector<uint8_t>> variants[] = {
      {"zstd", test::writeKtx2(zstd, packed)},
      {"bc7", test::writeKtx2({146, uint32_t(checker->width), uint32_t(checker->height)}, bc7)}};
  const std::string common = " --mode raster --frames 1 --seed 1";
  const Image8 reference = renderOk(dir, "source", (kDir / "source.glb").string() + common, kSize[0], kSize[1]);
  for (const auto& [name, ktx2] : variants) {
    std::ofstream(dir / (std::string(name) + ".ktx2"), std::ios::binary)
        .write(reinterpret_cast<const char*>(ktx2.data()), std::streamsize(ktx2.size()));
    nlohmann::json doc = json;
    doc["images"].push_back({{"uri", std::string(name) + ".ktx2"}});
    // No fallback `source`: the picture can only come from the KTX2 image.
    for (auto& texture : doc["textures"]) {
      texture["extensions"]["KHR_texture_basisu"]["source"] = doc["images"].size() - 1;
      texture.erase("source");
    }
    doc["extensionsUsed"].push_back("KHR_texture_basisu");
    doc["extensionsRequired"] = {"KHR_texture_basisu"};
    const fs::path file = dir / (std::string(name) + ".gltf");
    std::ofstream(file) << doc.dump();
    const Image8 image = renderOk(dir, name, file.string() + common, kSize[0], kSize[1]);
    ASSERT_FALSE(image.empty());
    EXPECT_EQ(compare(reference, image, 0).maxChannelDiff, 0) << name;
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
