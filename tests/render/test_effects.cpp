// Ray-traced AO, one-bounce indirect diffuse and glossy reflections (docs/techniques.md §13, §15, §16) on
// small scenes written here (OBJ + scene file + EXR environment), through the real binary.
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <gtest/gtest.h>

#include "tests/render/golden.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

constexpr int kS = 64;

// Axis-aligned quads as OBJ with an MTL: "white" (Kd 1, roughness 1), "mirror" (illum 3: metal,
// roughness 0) and "grey".
struct Quad {
  glm::vec3 a, b, c, d;
  std::string material;
};

std::filesystem::path writeObj(const std::filesystem::path& dir, const std::vector<Quad>& quads) {
  std::ofstream(dir / "quads.mtl") << "newmtl white\nKd 1 1 1\nNs 0\nillum 2\n"
                                      "newmtl grey\nKd 0.5 0.5 0.5\nNs 0\nillum 2\n"
                                      "newmtl mirror\nKd 0.9 0.9 0.9\nKs 0.9 0.9 0.9\nillum 3\n";
  std::ofstream obj(dir / "quads.obj");
  obj << "mtllib quads.mtl\n";
  int base = 1;
  for (const Quad& q : quads) {
    for (glm::vec3 p : {q.a, q.b, q.c, q.d}) obj << "v " << p.x << " " << p.y << " " << p.z << "\n";
    obj << "usemtl " << q.material << "\nf " << base << " " << base + 1 << " " << base + 2 << " " << base + 3 << "\n";
    base += 4;
  }
  return dir / "quads.obj";
}

// An equirect EXR: uniform radiance 1, or a gradient with a bright band (something to reflect).
void writeEnvironment(const std::filesystem::path& dir, bool uniform) {
  ImageF env = ImageF::make(64, 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      float* p = env.pixel(x, y);
      float band = (x / 8) % 2 ? 4.0f : 0.5f;
      for (int c = 0; c < 3; ++c) p[c] = uniform ? 1.0f : band * (0.3f + 0.2f * c) * (1.0f - y / 40.0f);
      p[3] = 1.0f;
    }
  ASSERT_TRUE(writeExr(dir / "env.exr", env).ok());
}

std::filesystem::path writeSceneFile(const std::filesystem::path& dir, const std::vector<Quad>& quads, bool uniformEnv,
                                     glm::vec3 eye, glm::vec3 target) {
  writeObj(dir, quads);
  writeEnvironment(dir, uniformEnv);
  auto path = dir / "scene.json";
  // A dark light keeps the loader from adding its default sun: the environment is the only light.
  std::ofstream(path) << R"({"models": [{"path": "quads.obj"}], "environment": {"map": "env.exr"},
  "lights": [{"type": "point", "position": [0, 100, 0], "intensity": 0}],
  "cameras": [{"name": "c", "position": [)"
                      << eye.x << "," << eye.y << "," << eye.z << R"(], "target": [)" << target.x << "," << target.y
                      << "," << target.z << R"(], "yfov": 40}]})";
  return path;
}

// A floor quad y = 0 over [x0, x1] × [z0, z1], facing up.
Quad floorQuad(float x0, float x1, float z0, float z1, std::string m) {
  return {{x0, 0, z1}, {x1, 0, z1}, {x1, 0, z0}, {x0, 0, z0}, std::move(m)};
}

// Renders `scene` at kS × kS with `args` and the comma-separated AOVs; the AOVs' EXR images by name,
// and the image itself as "hdr".
std::map<std::string, ImageF> renderAovs(const std::filesystem::path& dir, const std::string& scene,
                                         const std::string& args, const std::string& aovs) {
  std::vector<std::string> names;
  for (size_t start = 0; start < aovs.size();) {
    const size_t comma = aovs.find(',', start);
    names.push_back(aovs.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    start = comma == std::string::npos ? aovs.size() : comma + 1;
  }
  std::map<std::string, ImageF> images = test::renderAovs(
      dir, scene + " --primary raster --size " + std::to_string(kS) + "x" + std::to_string(kS) + " " + args, names);
  if (auto hdr = readExr(dir / "out.exr"); hdr.ok()) images["hdr"] = std::move(*hdr);  // the image itself
  return images;
}

double meanChannel(const ImageF& img, int c) {
  double sum = 0;
  for (size_t i = 0; i < img.rgba.size(); i += 4) sum += img.rgba[i + c];
  return sum / double(img.rgba.size() / 4);
}

TEST(Ao, OpenPlaneIsUnoccluded) {
  auto dir = testDir();
  auto scene = writeSceneFile(dir, {floorQuad(-50, 50, -50, 50, "white")}, true, {0, 3, 4}, {0, 0, 0});
  auto img = renderAovs(dir, scene.string(), "--frames 2 --ao-radius 100", "ao-raw,ao-denoised");
  for (const char* name : {"ao-raw", "ao-denoised"})
    for (size_t i = 0; i < img[name].rgba.size(); i += 4)
      ASSERT_EQ(img[name].rgba[i], 1.0f) << name << " texel " << i / 4;
}

// The hybrid denoises AO as the shadow denoiser's last layer: beside the scene's shadow layer, or
// alone in many-light mode (--shadow-lights 0 traces no shadow layer). The layers never mix, so
// both give the same AO bit for bit; with AO off it stays 1 everywhere.
TEST(Ao, SameWithOrWithoutShadowLayersAndOneWhenOff) {
  auto dir = testDir();
  const std::string aovs = "ao-raw,ao-denoised";
  auto withShadows = renderAovs(dir, "builtin:whitted", "--frames 3 --seed 4", aovs);
  auto alone = renderAovs(dir, "builtin:whitted", "--frames 3 --seed 4 --shadow-lights 0", aovs);
  for (const std::string name : {"ao-raw", "ao-denoised"}) {
    ASSERT_EQ(withShadows[name].rgba.size(), alone[name].rgba.size()) << name;
    ASSERT_FALSE(withShadows[name].rgba.empty()) << name;
    for (size_t i = 0; i < alone[name].rgba.size(); i += 4)
      ASSERT_EQ(withShadows[name].rgba[i], alone[name].rgba[i]) << name << " texel " << i / 4;
  }
  const double mean = meanChannel(withShadows["ao-denoised"], 0);
  EXPECT_GT(mean, 0.2);
  EXPECT_LT(mean, 0.99) << "the whitted scene has contact occlusion";
  auto off = renderAovs(dir, "builtin:whitted", "--frames 2 --ao off", aovs);
  for (const char* name : {"ao-raw", "ao-denoised"})
    for (size_t i = 0; i < off[name].rgba.size(); i += 4)
      ASSERT_EQ(off[name].rgba[i], 1.0f) << name << " texel " << i / 4;
}

TEST(Ao, OffLeavesAnUnoccludedPlaneAsLitAsOn) {
  // A white plane under a uniform environment has nothing to occlude it: AO on or off, it returns its
  // albedo (1: the diffuse layer plus the Fresnel share). AO off binds a one-texel neutral image; a
  // lighting pass reading it at the pixel read outside it and lost the environment's specular share.
  auto dir = testDir();
  auto scene = writeSceneFile(dir, {floorQuad(-50, 50, -50, 50, "white")}, true, {0, 3, 4}, {0, 0, 0});
  auto on = renderAovs(dir, scene.string(), "--frames 4 --ao on", "ao-denoised");
  auto off = renderAovs(dir, scene.string(), "--frames 4 --ao off", "ao-denoised");
  EXPECT_GT(meanChannel(on["ao-denoised"], 0), 0.99) << "nothing occludes the plane";
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(meanChannel(on["hdr"], c), 1.0, 0.02) << "AO on, channel " << c;
    EXPECT_NEAR(meanChannel(off["hdr"], c), 1.0, 0.02) << "AO off, channel " << c;
    EXPECT_NEAR(meanChannel(off["hdr"], c), meanChannel(on["hdr"], c), 0.01) << "channel " << c;
  }
}

TEST(Ao, FloorBesideAWallIsHalfOccluded) {
  // An (almost) infinite wall at x = 0 over a floor at x > 0: with an unlimited radius, half of the
  // cosine lobe of every floor point faces the wall (and of every wall point, the floor): AO → 0.5.
  auto dir = testDir();
  auto scene = writeSceneFile(
      dir, {floorQuad(0, 400, -400, 400, "white"), {{0, 0, -400}, {0, 0, 400}, {0, 400, 400}, {0, 400, -400}, "white"}},
      true, {3, 1.5f, 0}, {0.5f, 0.3f, 0});
  auto img = renderAovs(dir, scene.string(), "--frames 16 --ao-radius 10000", "ao-denoised");
  EXPECT_NEAR(meanChannel(img["ao-denoised"], 0), 0.5, 0.03);
  // A short radius sees almost nothing but the corner itself.
  auto shortRadius = renderAovs(dir, scene.string(), "--frames 4 --ao-radius 0.01", "ao-denoised");
  EXPECT_GT(meanChannel(shortRadius["ao-denoised"], 0), 0.95);
}

TEST(Indirect, WhitePlaneUnderAUniformEnvironmentReturnsItsAlbedo) {
  // Every indirect ray misses and sees radiance 1: E = π, and lighting's albedo/π·E gives the albedo
  // (1: the diffuse layer 0.96 plus the Fresnel share 0.04 reflecting the same environment).
  auto dir = testDir();
  auto scene = writeSceneFile(dir, {floorQuad(-50, 50, -50, 50, "white")}, true, {0, 3, 4}, {0, 0, 0});
  auto on = renderAovs(dir, scene.string(), "--frames 4 --indirect on --gi path", "indirect-raw,indirect-denoised");
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(meanChannel(on["indirect-raw"], c), 3.14159265, 0.01) << "E = π·1 in channel " << c;
    EXPECT_NEAR(meanChannel(on["hdr"], c), 1.0, 0.02) << "channel " << c;
  }
  // Without traced indirect light the SH irradiance gives the same answer.
  auto off = renderAovs(dir, scene.string(), "--frames 1 --indirect off", "indirect-raw");
  EXPECT_NEAR(meanChannel(off["hdr"], 1), 1.0, 0.02);
  EXPECT_EQ(meanChannel(off["indirect-raw"], 1), 0.0);
}

TEST(Glossy, RoughnessZeroThroughVndfEqualsTheMirrorPath) {
  // A roughness-0 mirror floor reflecting a grey wall and a banded sky: once as a mirror, once through
  // the VNDF sampler (--mirror-roughness -1). At α = 0 the sampler returns the mirror normal and the
  // weight G2/G1 / (A + B) is 1, and the glossy sample draws from its own random stream.
  auto dir = testDir();
  auto scene = writeSceneFile(
      dir, {floorQuad(-5, 5, -5, 5, "mirror"), {{-2, 0, -2}, {2, 0, -2}, {2, 2, -2}, {-2, 2, -2}, "grey"}}, false,
      {0, 1.5f, 4}, {0, 0.5f, 0});
  const std::string args = scene.string() + " --primary raster --frames 2 --seed 5";
  Image8 mirror = renderOk(dir, "mirror", args, kS, kS);
  Image8 vndf = renderOk(dir, "vndf", args + " --mirror-roughness -1", kS, kS);
  ImageDiff diff = compare(mirror, vndf, 1);
  if (diff.fractionWithinTolerance < 0.999) (void)writePng(dir / "diff.png", diff.heatmap);
  EXPECT_GE(diff.fractionWithinTolerance, 0.999) << "max diff " << diff.maxChannelDiff;
}

TEST(Effects, OptionsAreChecked) {
  auto dir = testDir();
  auto out = dir / "a.png";
  for (const char* bad : {"--ao maybe", "--indirect yes", "--ao-radius -1", "--glossy-threshold 2"}) {
    RunResult r = runRayster(std::string("render --size 32x24 ") + bad + " -o " + out.string());
    EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
}

}  // namespace
}  // namespace rayster::test
