// The raster mode (render/raster_frame.h) through the real binary, validation on: built-in scenes,
// shadow maps against ray-traced shadows and closed forms, screen-space reflections, goldens, and
// the fallback on a device without ray tracing (RAYSTER_DISABLE_RT=1 hides it on lavapipe).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>

#include "tests/render/analytic_scenes.h"
#include "tests/render/golden.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

using namespace analytic;

Placed floorAt0(float size, MaterialSpec m = {}) {
  return {"floor", unitQuad(), m, glm::vec3(size, size, 1), glm::vec3(-90, 0, 0), glm::vec3(0)};
}

// Mean linear-ish RGB (8-bit) of a rectangle of an LDR image, as fractions of the image size.
glm::vec3 meanRgb(const Image8& img, float x0, float y0, float x1, float y1) {
  glm::dvec3 sum(0.0);
  int n = 0;
  for (int y = int(y0 * img.height); y < int(y1 * img.height); ++y)
    for (int x = int(x0 * img.width); x < int(x1 * img.width); ++x) {
      const uint8_t* p = &img.rgba[(size_t(y) * img.width + x) * 4];
      sum += glm::dvec3(p[0], p[1], p[2]);
      ++n;
    }
  return glm::vec3(sum / double(std::max(n, 1)));
}

TEST(RasterMode, CornellWallsAndShadow) {
  auto dir = testDir();
  Image8 img = renderOk(dir, "cornell", "builtin:cornell --mode raster --frames 2", 128, 96);
  ASSERT_FALSE(img.rgba.empty());
  const glm::vec3 left = meanRgb(img, 0.10f, 0.35f, 0.18f, 0.6f), right = meanRgb(img, 0.82f, 0.35f, 0.90f, 0.6f);
  EXPECT_GT(left.r, 1.5f * left.g) << "left wall should be red";
  EXPECT_GT(right.g, 1.5f * right.r) << "right wall should be green";
  // The tall box stands back left, the light in the middle of the ceiling: the floor at the box's
  // left foot lies in its shadow, darker than the open floor in front of the boxes.
  const glm::vec3 openFloor = meanRgb(img, 0.30f, 0.88f, 0.45f, 0.95f);
  const glm::vec3 underBox = meanRgb(img, 0.25f, 0.72f, 0.33f, 0.80f);
  EXPECT_LT(underBox.r + underBox.g + underBox.b, 0.6f * (openFloor.r + openFloor.g + openFloor.b))
      << "shadow " << underBox.r << " vs open floor " << openFloor.r;
  EXPECT_GT(openFloor.r, 30.0f) << "the open floor should be lit";
}

TEST(RasterMode, WhittedAndSpheresRender) {
  auto dir = testDir();
  Image8 whitted = renderOk(dir, "whitted", "builtin:whitted --mode raster --frames 2", 96, 72);
  Image8 spheres = renderOk(dir, "spheres", "builtin:spheres --mode raster --frames 2", 96, 72);
  EXPECT_FALSE(whitted.rgba.empty());
  EXPECT_FALSE(spheres.rgba.empty());
  // The analytic spheres cast shadow-map shadows (their impostors write exact depth).
  Rendered r = renderHdr(dir, "spheres-shadow", "builtin:spheres", 96, 72, 1, "shadow-raw", "--mode raster");
  ASSERT_TRUE(r.aovs.count("shadow-raw"));
  int shadowed = 0;
  for (int y = 0; y < 72; ++y)
    for (int x = 0; x < 96; ++x) shadowed += r.aovs.at("shadow-raw").pixel(x, y)[0] < 0.5f;
  EXPECT_GT(shadowed, 96 * 72 / 50) << "the spheres should shadow the ground";
}

// A pixel of `a` disagrees with `b` unless `b` has the same value within `radius` pixels; only
// pixels where `counted` is true are compared.
template <class Counted>
int mismatches(const ImageF& a, const ImageF& b, int radius, Counted counted) {
  auto shadowed = [](const ImageF& img, int x, int y) { return img.pixel(x, y)[0] < 0.5f; };
  int bad = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (!counted(x, y)) continue;
      bool found = false;
      for (int dy = -radius; dy <= radius && !found; ++dy)
        for (int dx = -radius; dx <= radius && !found; ++dx) {
          int u = std::clamp(x + dx, 0, a.width - 1), v = std::clamp(y + dy, 0, a.height - 1);
          found = shadowed(a, x, y) == shadowed(b, u, v);
        }
      bad += !found;
    }
  return bad;
}

// The sun's cascade shadow lands where the ray-traced hard shadow does (within 2 pixels).
TEST(RasterMode, SunCascadeMatchesTracedShadow) {
  auto dir = testDir();
  SceneSpec s;
  s.models.push_back(floorAt0(6.0f));
  s.models.push_back(
      {"blocker", unitQuad(), {glm::vec3(0.5f)}, glm::vec3(1), glm::vec3(-90, 0, 0), glm::vec3(0, 1, 0)});
  s.lights = {R"({"type": "directional", "direction": [1, -1, 0], "intensity": 3, "angularRadius": 0})"};
  s.camera = {{2.5f, 5, 2}, {0.8f, 0, 0}, 50};
  const auto scene = writeScene(dir, "sun", s);
  const int size = 64;
  Rendered raster = renderHdr(dir, "raster", scene, size, size, 1, "shadow-raw", "--mode raster");
  Rendered traced = renderHdr(dir, "traced", scene, size, size, 1, "shadow-raw", "--mode hybrid");
  ASSERT_TRUE(raster.aovs.count("shadow-raw") && traced.aovs.count("shadow-raw"));
  const ImageF& a = raster.aovs.at("shadow-raw");
  const ImageF& b = traced.aovs.at("shadow-raw");
  // Floor pixels only (the traced image leaves the background 0).
  auto onFloor = [&](int x, int y) {
    glm::vec3 p;
    return hitHorizontal(pixelRay(s.camera, size, size, x, y), 0.0f, p) && std::abs(p.x) < 2.8f && std::abs(p.z) < 2.8f;
  };
  int shadowedA = 0, shadowedB = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      if (!onFloor(x, y)) continue;
      shadowedA += a.pixel(x, y)[0] < 0.5f;
      shadowedB += b.pixel(x, y)[0] < 0.5f;
    }
  EXPECT_GT(shadowedB, 40) << "the traced shadow should be in view";
  EXPECT_NEAR(shadowedA, shadowedB, 0.15 * shadowedB);
  EXPECT_LE(mismatches(a, b, 2, onFloor), 3);
  EXPECT_LE(mismatches(b, a, 2, onFloor), 3);
}

// Soft edges: a sphere light's shadow has a penumbra that grows with the light's radius
// (percentage-closer soft shadows); a hard point light's edge is only the PCF kernel wide.
TEST(RasterMode, PenumbraGrowsWithLightRadius) {
  auto dir = testDir();
  SceneSpec s;
  s.models.push_back(floorAt0(6.0f));
  s.models.push_back(
      {"blocker", unitQuad(), {glm::vec3(0.5f)}, glm::vec3(1.2f), glm::vec3(-90, 0, 0), glm::vec3(0, 1, 0)});
  s.camera = {{0, 6, 0.01f}, {0, 0, 0}, 50};
  const int size = 64;
  int penumbra[2] = {};
  for (int i = 0; i < 2; ++i) {
    const float radius = i == 0 ? 0.0f : 0.4f;
    s.lights = {
        fmt::format(R"({{"type": "point", "position": [0.3, 2.5, 0.2], "intensity": 10, "radius": {}}})", radius)};
    const std::string name = "penumbra" + std::to_string(i);
    Rendered r = renderHdr(dir, name, writeScene(dir, name, s), size, size, 1, "shadow-raw", "--mode raster");
    ASSERT_TRUE(r.aovs.count("shadow-raw"));
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const float v = r.aovs.at("shadow-raw").pixel(x, y)[0];
        penumbra[i] += v > 0.1f && v < 0.9f;
      }
  }
  EXPECT_GT(penumbra[1], 2 * penumbra[0] + 20) << "hard " << penumbra[0] << " px, soft " << penumbra[1] << " px";
  std::printf("[raster] penumbra pixels: hard light %d, sphere light %d\n", penumbra[0], penumbra[1]);
}

// A point light in the middle of a closed room with a small cube on each axis: each of the six
// cube-map faces must shadow its wall where the cube projects, and leave the rest lit.
TEST(RasterMode, PointLightCubeShadowsAllSides) {
  auto dir = testDir();
  SceneSpec s;
  Mesh room = unitBox();
  s.models.push_back({"room", room, {glm::vec3(0.8f)}, glm::vec3(6.0f), glm::vec3(0), glm::vec3(0)});
  const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int i = 0; i < 6; ++i)
    s.models.push_back(
        {"cube" + std::to_string(i), unitBox(), {glm::vec3(0.8f)}, glm::vec3(0.4f), glm::vec3(0), axes[i]});
  s.lights = {R"({"type": "point", "position": [0, 0, 0], "intensity": 20, "radius": 0})"};
  const int size = 96;
  int shadowedPerWall[6] = {}, litPerWall[6] = {}, bad = 0;
  for (int view = 0; view < 2; ++view) {
    // Two cameras in opposite corners see all six walls between them.
    const float c = view == 0 ? 2.0f : -2.0f;
    s.camera = {{c, c, c}, {-c, -c, -c}, 80};
    const std::string name = "room" + std::to_string(view);
    Rendered r = renderHdr(dir, name, writeScene(dir, name, s), size, size, 1, "shadow-raw", "--mode raster");
    ASSERT_TRUE(r.aovs.count("shadow-raw"));
    const ImageF& vis = r.aovs.at("shadow-raw");
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        Ray ray = pixelRay(s.camera, size, size, x, y);
        bool nearCube = false;
        for (const glm::vec3& a : axes) {
          const glm::vec3 toCube = a - ray.origin;
          const float t = std::max(glm::dot(toCube, ray.dir), 0.0f);
          nearCube |= glm::length(ray.origin + ray.dir * t - a) < 0.45f;
        }
        if (nearCube) continue;
        float tHit = 1e30f;
        int axis = 0;
        for (int k = 0; k < 3; ++k) {
          if (std::abs(ray.dir[k]) < 1e-6f) continue;
          const float t = ((ray.dir[k] > 0 ? 3.0f : -3.0f) - ray.origin[k]) / ray.dir[k];
          if (t > 0 && t < tHit) tHit = t, axis = k;
        }
        const glm::vec3 p = ray.origin + ray.dir * tHit;
        const int wall = axis * 2 + (p[axis] > 0 ? 0 : 1);
        const float u = std::abs(p[(axis + 1) % 3]), v = std::abs(p[(axis + 2) % 3]);
        const float inside = std::max(u, v);  // the cube's shadow: |u|, |v| < 0.75 on the wall
        if (std::abs(inside - 0.75f) < 0.2f || std::max(u, v) > 2.7f) continue;  // edges and corners
        const bool shadowed = inside < 0.75f;
        const float value = vis.pixel(x, y)[0];
        if (shadowed ? value > 0.2f : value < 0.8f) {
          if (++bad <= 5)
            ADD_FAILURE() << "wall " << wall << " at (" << p.x << ", " << p.y << ", " << p.z << ") should be "
                          << (shadowed ? "shadowed" : "lit") << ", visibility " << value;
        }
        ++(shadowed ? shadowedPerWall : litPerWall)[wall];
      }
  }
  EXPECT_LE(bad, 5);
  for (int w = 0; w < 6; ++w) {
    EXPECT_GT(shadowedPerWall[w], 10) << "wall " << w << ": its cube's shadow should be in view";
    EXPECT_GT(litPerWall[w], 50) << "wall " << w;
  }
}

// A mirror floor reflects an emissive red box: screen-space reflections find it in the depth
// buffer; where the reflected ray misses the box the black environment shows.
TEST(RasterMode, SsrReflectsOnMirrorFloor) {
  auto dir = testDir();
  SceneSpec s;
  MaterialSpec mirror{glm::vec3(1.0f), 1.0f, 0.0f};
  s.models.push_back(floorAt0(8.0f, mirror));
  MaterialSpec redEmitter = emitter(2.0f);
  redEmitter.emissive = glm::vec3(2.0f, 0.0f, 0.0f);
  s.models.push_back({"box", unitBox(), redEmitter, glm::vec3(1.0f), glm::vec3(0), glm::vec3(0, 0.5f, 0)});
  s.lights = {darkLight()};
  s.camera = {{0, 1.2f, 4}, {0, 0.3f, 0}, 45};
  const int size = 96;
  Rendered r = renderHdr(dir, "mirror", writeScene(dir, "mirror", s), size, size, 1, "", "--mode raster");
  ASSERT_EQ(r.hdr.width, size);
  int reflecting = 0, red = 0, missing = 0, dark = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      Ray ray = pixelRay(s.camera, size, size, x, y);
      glm::vec3 p;
      if (!hitHorizontal(ray, 0.0f, p) || std::abs(p.x) > 3.5f || std::abs(p.z) > 3.5f) continue;
      // Not the box itself in front of the floor point.
      if (std::abs(p.x) < 0.6f && std::abs(p.z) < 0.6f) continue;
      glm::vec3 d = ray.dir;
      d.y = -d.y;
      // Reflected ray against the box [-0.5, 0.5] × [0, 1] × [-0.5, 0.5] (slabs), shrunk and grown
      // to stay off the reflection's silhouette.
      auto hitsBox = [&](float grow) {
        float t0 = 0, t1 = 1e30f;
        const glm::vec3 lo(-0.5f - grow, -grow, -0.5f - grow), hi(0.5f + grow, 1 + grow, 0.5f + grow);
        for (int k = 0; k < 3; ++k) {
          if (std::abs(d[k]) < 1e-7f) {
            if (p[k] < lo[k] || p[k] > hi[k]) return false;
            continue;
          }
          const float a = (lo[k] - p[k]) / d[k], b = (hi[k] - p[k]) / d[k];
          t0 = std::max(t0, std::min(a, b));
          t1 = std::min(t1, std::max(a, b));
        }
        return t1 >= t0 && t1 > 0;
      };
      const bool hits = hitsBox(-0.08f);
      if (!hits && hitsBox(0.08f)) continue;
      const float* px = r.hdr.pixel(x, y);
      if (hits) {
        ++reflecting;
        red += px[0] > 0.5f && px[1] < 0.2f * px[0];
      } else {
        ++missing;
        dark += px[0] < 0.2f;
      }
    }
  ASSERT_GT(reflecting, 100) << "the reflection should be in view";
  EXPECT_GT(red, 0.8 * reflecting) << red << " of " << reflecting << " reflecting floor pixels are red";
  EXPECT_GT(dark, 0.8 * missing) << dark << " of " << missing;
}

TEST(RasterMode, GoldenCornell) {
  auto dir = testDir();
  Image8 img =
      renderOk(dir, "raster_cornell", "builtin:cornell --mode raster --frames 4 --seed 3 --exposure 0", 160, 120);
  ASSERT_FALSE(img.rgba.empty());
  expectMatchesGolden(img, "raster_cornell", dir);
}

TEST(RasterMode, GoldenWhitted) {
  auto dir = testDir();
  Image8 img =
      renderOk(dir, "raster_whitted", "builtin:whitted --mode raster --frames 4 --seed 3 --exposure 0", 160, 120);
  ASSERT_FALSE(img.rgba.empty());
  expectMatchesGolden(img, "raster_whitted", dir);
}

// Without ray tracing the default (hybrid) mode falls back to raster with a one-line notice.
TEST(RasterMode, FallbackWithoutRayTracing) {
  auto dir = testDir();
  const auto out = dir / "fallback.png";
  RunResult r = runRayster("render builtin:cornell --size 64x48 --frames 1 -o " + out.string(), "RAYSTER_DISABLE_RT=1");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("has no ray-tracing pipelines: rendering with --mode raster"), std::string::npos) << r.output;
  auto img = readPng(out);
  ASSERT_TRUE(img.ok());
  EXPECT_FALSE(rejectEmpty(*img, 64, 48).has_value());
}

// Animation on a device without ray tracing (no TLAS to refit): a played frame's G-buffer and
// shadow maps match the paused pose at the same time.
TEST(RasterMode, AnimationWithoutRayTracingMatchesThePausedPose) {
  auto dir = testDir();
  const std::string scene = writeAnimatedGltf(dir).string();
  auto render = [&](const std::string& name, const std::string& args) {
    RunResult r = runRayster("render " + scene + " --mode raster --taa off --size 96x72 --aov albedo,shadow-raw " +
                                 args + " -o " + (dir / (name + ".png")).string(),
                             "RAYSTER_DISABLE_RT=1");
    EXPECT_EQ(r.exitCode, 0) << r.output;
  };
  render("played", "--frames 2 --path-fps 1");
  // Two frames too, so the last one has the same frame index (the PCF disk turns per frame).
  render("paused", "--frames 2 --time 1 --pause");
  for (const char* aov : {"albedo", "shadow-raw"}) {
    auto a = readExr(dir / (std::string("played.") + aov + ".exr"));
    auto b = readExr(dir / (std::string("paused.") + aov + ".exr"));
    ASSERT_TRUE(a.ok() && b.ok()) << aov;
    EXPECT_FALSE(rejectEmpty(*a, 96, 72).has_value()) << aov;
    ASSERT_EQ(a->rgba.size(), b->rgba.size());
    size_t differ = 0;
    for (size_t i = 0; i < a->rgba.size(); ++i) differ += std::abs(a->rgba[i] - b->rgba[i]) > 1e-3f;
    EXPECT_EQ(differ, 0u) << aov << ": " << differ << " channel values differ";
  }
}

TEST(RasterMode, RequireRtExitsWithMissingCapability) {
  auto dir = testDir();
  const auto out = dir / "none.png";
  RunResult r = runRayster("render builtin:cornell --size 64x48 --frames 1 --require-rt -o " + out.string(),
                           "RAYSTER_DISABLE_RT=1");
  EXPECT_EQ(r.exitCode, 5) << r.output;
  EXPECT_NE(r.output.find("no ray-tracing pipelines"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace rayster::test
