// Off means gone, and AOVs are any named image (docs/architecture.md): an effect that is switched
// off, or has nothing to do, records no pass and allocates no image, which `--timings` and
// `--memory-report` show; `--aov NAME` reads any image of the frame's graph by its name.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

// What one run recorded: its passes (the --timings table) and its frame's images (--memory-report).
struct Listing {
  std::set<std::string> passes, images;
  std::map<std::string, std::string> sizes;  // image → "WxH" or "WxHxLAYERS"
  bool hasPass(const std::string& p) const { return passes.count(p) > 0; }
  bool anyPass(const std::string& part) const {
    return std::any_of(passes.begin(), passes.end(),
                       [&](const std::string& p) { return p.find(part) != std::string::npos; });
  }
  bool anyImage(const std::string& part) const {
    return std::any_of(images.begin(), images.end(),
                       [&](const std::string& i) { return i.find(part) != std::string::npos; });
  }
};

Listing parse(const std::string& output) {
  Listing l;
  std::istringstream in(output);
  std::string line;
  enum { None, Passes, Images } section = None;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string first;
    words >> first;
    if (first.rfind("rayster:", 0) == 0) continue;  // progress lines may interleave
    if (first == "pass" && section == None) {
      section = Passes;
    } else if (section == Passes && first == "frame") {
      section = None;
    } else if (section == Passes && !first.empty()) {
      l.passes.insert(first);
    } else if (first == "image" && line.find("format") != std::string::npos) {
      section = Images;
    } else if (section == Images && !first.empty()) {
      std::string format, size;
      words >> format >> size;
      l.images.insert(first);
      l.sizes[first] = size;
    }
  }
  return l;
}

class EffectPasses : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testDir(); }

  // A diffuse scene (white quads, roughness 1: nothing for the specular pass) lit by the default sun.
  std::string diffuseScene() {
    std::ofstream(dir_ / "quads.mtl") << "newmtl white\nKd 0.8 0.8 0.8\nNs 0\nillum 2\n";
    std::ofstream(dir_ / "quads.obj") << "mtllib quads.mtl\nusemtl white\n"
                                         "v -4 0 4\nv 4 0 4\nv 4 0 -4\nv -4 0 -4\n"
                                         "v -1 0 0\nv 1 0 0\nv 1 2 0\nv -1 2 0\n"
                                         "f 1 2 3 4\nf 5 6 7 8\n";
    return (dir_ / "quads.obj").string();
  }

  Listing list(const std::string& scene, const std::string& args) {
    const auto out = dir_ / "out.png";
    RunResult r = runRayster("render " + scene + " --size 48x32 --frames 2 --timings --memory-report " + args + " -o " +
                             out.string());
    EXPECT_EQ(r.exitCode, 0) << args << "\n" << r.output;
    auto img = readPng(out);
    EXPECT_TRUE(img.ok()) << args;
    if (img.ok()) {
      EXPECT_FALSE(rejectEmpty(*img, 48, 32).has_value()) << args << ": " << rejectEmpty(*img, 48, 32).value_or("");
    }
    Listing l = parse(r.output);
    EXPECT_TRUE(l.hasPass("lighting") && l.hasPass("tonemap")) << args << "\n" << r.output;
    EXPECT_TRUE(l.images.count("hdr")) << args << "\n" << r.output;
    return l;
  }

  std::filesystem::path dir_;
};

TEST_F(EffectPasses, EveryEffectOnRecordsItsPassesAndHistories) {
  const Listing probes = list("builtin:whitted", "");
  for (const char* p : {"gi-probe-trace", "gi-probe-classify", "gi-probe-update-irradiance",
                        "gi-probe-update-visibility", "gi-probe-sample"})
    EXPECT_TRUE(probes.hasPass(p)) << p << ": the probes are the default diffuse indirect light";
  for (const char* i : {"gi-probe-irradiance", "gi-probe-bounce", "gi-probe-visibility", "gi-probe-data"})
    EXPECT_TRUE(probes.images.count(i)) << i;
  EXPECT_FALSE(probes.anyPass("rt-indirect")) << "the probes take the one-bounce path's place";

  const Listing l = list("builtin:whitted", "--gi path");
  for (const char* p :
       {"rt-shadows", "rt-ao", "shadow-temporal", "rt-specular", "rt-specular-fill", "reflection-temporal",
        "rt-indirect", "rt-indirect-fill", "indirect-temporal", "denoise-surface"})
    EXPECT_TRUE(l.hasPass(p)) << p;
  for (const char* i : {"shadow-raw", "specular-raw", "indirect-raw", "surface", "shadow-history", "specular-history",
                        "indirect-history", "taa-history"})
    EXPECT_TRUE(l.images.count(i)) << i;
  EXPECT_EQ(l.sizes.at("shadow-raw"), "48x32x2") << "the sun's layer and AO's";
}

TEST_F(EffectPasses, AnEffectSwitchedOffRecordsNoPassAndNoImage) {
  const Listing ao = list("builtin:whitted", "--ao off");
  EXPECT_FALSE(ao.anyPass("-ao")) << "rt-ao";
  EXPECT_FALSE(ao.anyImage("ao-"));
  EXPECT_EQ(ao.sizes.at("shadow-raw"), "48x32") << "one layer: the sun's, none for AO";
  EXPECT_TRUE(ao.hasPass("rt-shadows"));

  const Listing indirect = list("builtin:whitted", "--indirect off");
  EXPECT_FALSE(indirect.anyPass("indirect"));
  EXPECT_FALSE(indirect.anyImage("indirect"));
  EXPECT_FALSE(indirect.anyPass("gi-probe"));
  EXPECT_FALSE(indirect.anyImage("gi-"));
  EXPECT_TRUE(indirect.hasPass("rt-specular"));

  // Many-light mode (no shadow layer) with AO off: nothing shadows, nothing occludes.
  const Listing noShadows = list("builtin:whitted", "--shadow-lights 0 --ao off");
  EXPECT_FALSE(noShadows.anyPass("shadow"));
  EXPECT_FALSE(noShadows.anyImage("shadow"));
  EXPECT_TRUE(noShadows.hasPass("rt-direct"));

  // The raw-rate twins follow their effects.
  const Listing raw = list("builtin:whitted", "--raw-rays --ao off --indirect off");
  EXPECT_TRUE(raw.hasPass("raw-rt-specular"));
  EXPECT_FALSE(raw.hasPass("raw-rt-ao"));
  EXPECT_FALSE(raw.hasPass("raw-rt-indirect"));
}

// The G-buffer's clear-coat/sheen target (RGBA32UI, 32 MiB at 1080p) exists only in a scene with a
// coat or a sheen; elsewhere both producers leave it out and lighting reads a one-texel zero image.
TEST_F(EffectPasses, OnlyACoatOrSheenAllocatesTheLayersTarget) {
  const std::string layered =
      (std::filesystem::path(RAYSTER_SOURCE_DIR) / "assets/corpus/features/materials.glb").string();
  for (const char* primary : {"raster", "rt"}) {
    const std::string args = std::string("--primary ") + primary;
    const Listing flat = list("builtin:whitted", args);
    EXPECT_FALSE(flat.images.count("gbuffer-layers")) << primary << ": whitted has no clear coat or sheen";
    EXPECT_TRUE(flat.images.count("neutral-layers")) << primary;
    const Listing coat = list(layered, args);
    EXPECT_TRUE(coat.images.count("gbuffer-layers")) << primary << ": materials.glb has Clearcoat and Sheen";
    EXPECT_EQ(coat.sizes.at("gbuffer-layers"), "48x32") << primary;
  }
}

TEST_F(EffectPasses, DenoiseOffKeepsNoDenoiserPassOrHistory) {
  const Listing l = list("builtin:whitted", "--denoise off --gi path");
  EXPECT_FALSE(l.anyPass("temporal"));
  EXPECT_FALSE(l.anyPass("atrous"));
  for (const std::string& i : l.images)
    EXPECT_TRUE(i.find("history") == std::string::npos || i.rfind("taa-history", 0) == 0) << i;
  EXPECT_FALSE(l.images.count("surface-prev"));
  EXPECT_TRUE(l.hasPass("rt-indirect-fill")) << "quarter-rate indirect still fills its blocks";
  // At full rate nothing needs the surface image either.
  const Listing full = list("builtin:whitted", "--denoise off --gi path --indirect-rate full");
  EXPECT_FALSE(full.hasPass("denoise-surface"));
  EXPECT_FALSE(full.anyImage("surface"));
}

TEST_F(EffectPasses, NothingSmoothToTraceRecordsNoSpecularPass) {
  const std::string scene = diffuseScene();
  const Listing l = list(scene, "");
  EXPECT_FALSE(l.anyPass("specular"));
  EXPECT_FALSE(l.anyPass("reflection"));
  EXPECT_FALSE(l.anyImage("specular-"));
  EXPECT_TRUE(l.hasPass("rt-shadows"));
  // "Shadows only": the G-buffer, the shadow pass and its denoiser, lighting, TAA, tonemap.
  const Listing shadowsOnly = list(scene, "--ao off --indirect off");
  for (const std::string& p : shadowsOnly.passes) {
    const bool expected = p.rfind("gbuffer-", 0) == 0 || p.rfind("cull", 0) == 0 || p == "visible" ||
                          p.rfind("hiz", 0) == 0 || p == "denoise-surface" || p.rfind("shadow-", 0) == 0 ||
                          p == "rt-shadows" || p == "lighting" || p == "taa" || p == "tonemap";
    EXPECT_TRUE(expected) << "shadows only recorded " << p;
  }
}

// The same frame with the denoisers off shows the raw signals; on, it shows the denoised ones.
TEST_F(EffectPasses, DenoiseOffLightsWithTheRawSignals) {
  auto off = renderAovs(dir_, "builtin:whitted --size 48x32 --frames 2 --denoise off",
                        {"reflection-raw", "reflection-denoised", "shadow-raw", "shadow-denoised"});
  for (const auto& [raw, denoised] :
       {std::pair{"reflection-raw", "reflection-denoised"}, {"shadow-raw", "shadow-denoised"}})
    EXPECT_EQ(off[raw].rgba, off[denoised].rgba) << raw;
  auto on = renderAovs(dir_, "builtin:whitted --size 48x32 --frames 2", {"reflection-raw", "reflection-denoised"});
  EXPECT_NE(on["reflection-raw"].rgba, on["reflection-denoised"].rgba);
}

TEST_F(EffectPasses, AnyGraphImageIsAnAov) {
  // "hdr" (lighting's output) is the frame's HDR image when TAA is off; a layer by NAME:LAYER is the
  // same as its alias; an id target and a history read back too.
  auto aovs = renderAovs(dir_, "builtin:whitted --size 48x32 --frames 2 --taa off",
                         {"hdr", "shadow-raw:1", "ao-raw", "gbuffer-id", "shadow-history", "surface"});
  auto frame = readExr(dir_ / "out.exr");
  ASSERT_TRUE(frame.ok());
  ASSERT_EQ(aovs["hdr"].rgba.size(), frame->rgba.size());
  for (size_t i = 0; i < frame->rgba.size(); i += 4)
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(aovs["hdr"].rgba[i + c], frame->rgba[i + c], 1e-3f * std::max(1.0f, frame->rgba[i + c])) << i / 4;
  EXPECT_EQ(aovs["shadow-raw:1"].rgba, aovs["ao-raw"].rgba) << "AO is the shadow image's layer 1";
  std::set<float> ids;
  for (size_t i = 0; i < aovs["gbuffer-id"].rgba.size(); i += 4) ids.insert(aovs["gbuffer-id"].rgba[i]);
  EXPECT_GT(ids.size(), 2u) << "several instances and the background";

  RunResult unknown = runRayster("render builtin:whitted --size 48x32 --frames 3 --aov no-such-image -o " +
                                 (dir_ / "bad.png").string());
  EXPECT_EQ(unknown.exitCode, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("unknown AOV 'no-such-image'"), std::string::npos) << unknown.output;
  EXPECT_NE(unknown.output.find("gbuffer-normals"), std::string::npos) << "the message lists the images";
  EXPECT_FALSE(std::filesystem::exists(dir_ / "bad.png")) << "no half-written output";
  RunResult layer =
      runRayster("render builtin:whitted --size 48x32 --frames 1 --aov shadow-raw:7 -o " + (dir_ / "bad.png").string());
  EXPECT_EQ(layer.exitCode, 2) << layer.output;
  EXPECT_NE(layer.output.find("has 2 layer(s)"), std::string::npos) << layer.output;
}

}  // namespace
}  // namespace rayster::test
