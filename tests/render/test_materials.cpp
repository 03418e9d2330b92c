// Vertex colours, KHR_materials_unlit and KHR_materials_specular end to end, in every mode: the
// hybrid frame with the raster and the traced G-buffer, the raster mode and the path tracer. Each
// scene is a scene file of analytic glTF parts (tests/render/analytic_scenes.h); the checks read the
// linear HDR image (before exposure and tonemapping) at pixels whose world point is known.
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "tests/render/analytic_scenes.h"

namespace rayster::test::analytic {
namespace {

constexpr int kSize = 64;

struct ModeSpec {
  const char* name;
  const char* args;
  int frames;
};
// The path tracer gets more frames: its image is a mean of one sample per pixel per frame.
const ModeSpec kModes[] = {{"hybrid-raster", "--primary raster", 2},
                           {"hybrid-rt", "--primary rt", 2},
                           {"raster", "--mode raster", 2},
                           {"pathtrace", "--mode pathtrace", 16}};

// Mean linear RGB over the pixels for which `keep(ray)` holds, and how many there were.
struct Mean {
  glm::dvec3 rgb{0.0};
  int pixels = 0;
};
Mean meanWhere(const ImageF& img, const CameraSpec& cam, const std::function<bool(const Ray&)>& keep) {
  Mean m;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      if (!keep(pixelRay(cam, img.width, img.height, x, y))) continue;
      const float* p = img.pixel(x, y);
      m.rgb += glm::dvec3(p[0], p[1], p[2]);
      ++m.pixels;
    }
  if (m.pixels > 0) m.rgb /= double(m.pixels);
  return m;
}

// Where the ray meets the plane z = 0.
glm::vec2 onPlaneZ0(const Ray& r) {
  const glm::vec3 p = r.origin + r.dir * (-r.origin.z / r.dir.z);
  return {p.x, p.y};
}

// Pixels of the plane z = 0 inside [x0, x1] × [y0, y1].
std::function<bool(const Ray&)> inRect(float x0, float y0, float x1, float y1) {
  return [=](const Ray& r) {
    const glm::vec2 p = onPlaneZ0(r);
    return p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1;
  };
}

std::string fmtRgb(glm::dvec3 c) { return fmt::format("({:.4f}, {:.4f}, {:.4f})", c.r, c.g, c.b); }

// A quad with one RGBA8 colour per corner, in unitQuad()'s vertex order: (-,-), (+,-), (+,+), (-,+).
Mesh coloredQuad(std::vector<uint8_t> rgbaPerCorner) {
  Mesh m = unitQuad();
  m.colors = std::move(rgbaPerCorner);
  return m;
}

// ---- Vertex colours ----

// Left: a white diffuse quad with red, green, blue and white corners (normalized u8 COLOR_0) under a
// uniform environment of radiance 1, so each corner shows its colour (× (1 − F), + F of the
// environment). Right: an emitter of radiance 4 whose vertex alpha falls from 1 (left edge) to 0
// (right edge) under alpha MASK at 0.5, so its right half is cut away and shows the environment (1).
TEST(VertexColors, MultiplyBaseColourAndAlphaInEveryMode) {
  auto dir = testDir();
  SceneSpec s;
  MaterialSpec white{glm::vec3(1.0f), 0.0f, 1.0f};
  s.models.push_back({"colors", coloredQuad({255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255}),
                      white, glm::vec3(2, 2, 1), glm::vec3(0), glm::vec3(-1.05f, 0, 0)});
  MaterialSpec cutout = emitter(4.0f);
  cutout.alphaMode = "MASK";
  cutout.alphaCutoff = 0.5f;
  s.models.push_back({"cutout", coloredQuad({0, 0, 0, 255, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 255}), cutout,
                      glm::vec3(2, 2, 1), glm::vec3(0), glm::vec3(1.05f, 0, 0)});
  s.lights = {darkLight()};
  s.environment = uniformEnvironment(1.0f);
  s.camera = {{0, 0, 6}, {0, 0, 0}, 40};
  const auto scene = writeScene(dir, "colors", s);
  for (const ModeSpec& mode : kModes) {
    SCOPED_TRACE(mode.name);
    Rendered r = renderHdr(dir, mode.name, scene, kSize, kSize, mode.frames, "", mode.args);
    ASSERT_FALSE(r.hdr.empty());
    // Corner regions of the left quad (x in [-2.05, -0.05], y in [-1, 1]), 0.15 in from its edges.
    const Mean red = meanWhere(r.hdr, s.camera, inRect(-1.9f, -0.85f, -1.45f, -0.4f));
    const Mean green = meanWhere(r.hdr, s.camera, inRect(-0.65f, -0.85f, -0.2f, -0.4f));
    const Mean blue = meanWhere(r.hdr, s.camera, inRect(-0.65f, 0.4f, -0.2f, 0.85f));
    const Mean whiteCorner = meanWhere(r.hdr, s.camera, inRect(-1.9f, 0.4f, -1.45f, 0.85f));
    for (const Mean* m : {&red, &green, &blue, &whiteCorner}) ASSERT_GT(m->pixels, 20);
    std::printf("[colors] %-13s red %s green %s blue %s white %s\n", mode.name, fmtRgb(red.rgb).c_str(),
                fmtRgb(green.rgb).c_str(), fmtRgb(blue.rgb).c_str(), fmtRgb(whiteCorner.rgb).c_str());
    // Each corner is mostly its own colour: 0.8 of it in the hybrid, a few percent less in the path
    // tracer (single-scattering GGX at roughness 1 loses what the hybrid's split keeps). The two
    // triangles blend in the other corners' colours over their barycentric weights (about 0.2).
    EXPECT_GT(red.rgb.r, 0.5);
    EXPECT_LT(red.rgb.g, 0.3);
    EXPECT_LT(red.rgb.b, 0.3);
    EXPECT_GT(green.rgb.g, 0.5);
    EXPECT_LT(green.rgb.r, 0.3);
    EXPECT_LT(green.rgb.b, 0.3);
    EXPECT_GT(blue.rgb.b, 0.5);
    EXPECT_LT(blue.rgb.r, 0.3);
    EXPECT_LT(blue.rgb.g, 0.3);
    EXPECT_GT(whiteCorner.rgb.r, 0.5);
    EXPECT_GT(whiteCorner.rgb.g, 0.5);
    EXPECT_GT(whiteCorner.rgb.b, 0.5);
    // The cut-out: vertex alpha × base alpha against the cutoff, in raster (discard) and traced
    // (any-hit) visibility alike.
    const Mean kept = meanWhere(r.hdr, s.camera, inRect(0.3f, -0.7f, 0.8f, 0.7f));
    const Mean cut = meanWhere(r.hdr, s.camera, inRect(1.3f, -0.7f, 1.8f, 0.7f));
    ASSERT_GT(kept.pixels, 20);
    ASSERT_GT(cut.pixels, 20);
    EXPECT_NEAR(kept.rgb.r, 4.0, 0.1) << "where vertex alpha > 0.5 the emitter stays";
    EXPECT_NEAR(cut.rgb.r, 1.0, 0.1) << "where vertex alpha < 0.5 the environment shows through";
  }
}

// ---- KHR_materials_unlit ----

// An unlit floor (metallic 1, roughness 0: parameters unlit ignores) under a sun from straight above
// and a dim sky, a box floating over it casting a hard shadow, and a white mirror wall behind.
// The floor's radiance is its base colour everywhere: in the box's shadow as in the sun, and seen in
// the mirror (reflectance 1) as seen directly.
TEST(Unlit, ShowsItsBaseColourUnlitUnshadowedInEveryMode) {
  auto dir = testDir();
  const glm::vec3 base(0.2f, 0.5f, 0.8f);
  SceneSpec s;
  MaterialSpec flat{base, 1.0f, 0.0f};
  flat.unlit = true;
  s.models.push_back({"floor", unitQuad(), flat, glm::vec3(6, 6, 1), glm::vec3(-90, 0, 0), glm::vec3(0)});
  const float boxX = 1.2f;  // off the axis, so that the mirror's middle reflects open floor
  s.models.push_back(
      {"box", unitBox(), MaterialSpec{glm::vec3(0.5f)}, glm::vec3(1), glm::vec3(0), glm::vec3(boxX, 1.5f, 0)});
  s.models.push_back({"mirror", unitQuad(), MaterialSpec{glm::vec3(1.0f), 1.0f, 0.0f}, glm::vec3(6, 3, 1), glm::vec3(0),
                      glm::vec3(0, 1.5f, -3)});
  s.lights = {R"({"type": "directional", "direction": [0, -1, 0], "intensity": 5, "angularRadius": 0})"};
  s.environment = uniformEnvironment(0.3f);
  s.camera = {{0, 4, 6}, {0, 0.8f, 0}, 50};
  const auto scene = writeScene(dir, "unlit", s);

  // The box [boxX ± 0.5] × [1, 2] × [±0.5], grown by `margin`: slab test for a ray segment.
  auto hitsBox = [boxX](glm::vec3 o, glm::vec3 d, float tMax, float margin) {
    float t0 = 0.0f, t1 = tMax;
    const glm::vec3 lo(boxX - 0.5f - margin, 1.0f - margin, -0.5f - margin);
    const glm::vec3 hi(boxX + 0.5f + margin, 2.0f + margin, 0.5f + margin);
    for (int a = 0; a < 3; ++a) {
      if (std::abs(d[a]) < 1e-9f) {
        if (o[a] < lo[a] || o[a] > hi[a]) return false;
        continue;
      }
      float ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
      t0 = std::max(t0, std::min(ta, tb));
      t1 = std::min(t1, std::max(ta, tb));
    }
    return t0 <= t1;
  };
  // Where a ray from `o` along `d` meets the floor, if before the box and `edge` from the floor's
  // open edges (its back edge meets the mirror, where its reflection continues it seamlessly).
  auto floorPoint = [&](glm::vec3 o, glm::vec3 d, float edge, float margin, glm::vec3& p) {
    if (d.y >= 0.0f) return false;
    const float t = -o.y / d.y;
    p = o + t * d;
    return std::abs(p.x) < edge && p.z > -3.0f && p.z < edge && !hitsBox(o, d, t, margin);
  };
  auto direct = [&](bool shadowed) {
    return [&, shadowed](const Ray& r) {
      glm::vec3 p;
      if (!floorPoint(r.origin, r.dir, 2.7f, 0.05f, p)) return false;
      const bool under = std::abs(p.x - boxX) < 0.4f && std::abs(p.z) < 0.4f;
      const bool open = std::abs(p.x - boxX) > 0.7f || std::abs(p.z) > 0.7f;
      return shadowed ? under : open;
    };
  };
  // Mirror pixels whose reflected ray meets the floor (the mirror is the plane z = −3), well away
  // from the reflected edges of the floor and the box, which the reflection denoiser blurs.
  auto mirrored = [&](const Ray& r) {
    if (r.dir.z >= 0.0f) return false;
    const float t = (-3.0f - r.origin.z) / r.dir.z;
    const glm::vec3 q = r.origin + t * r.dir;
    if (std::abs(q.x) > 2.6f || q.y < 0.2f || q.y > 2.7f || hitsBox(r.origin, r.dir, t, 0.3f)) return false;
    glm::vec3 p;
    return floorPoint(q, glm::vec3(r.dir.x, r.dir.y, -r.dir.z), 2.2f, 0.3f, p);
  };
  for (const ModeSpec& mode : kModes) {
    SCOPED_TRACE(mode.name);
    Rendered r = renderHdr(dir, mode.name, scene, kSize, kSize, mode.frames, "", mode.args);
    ASSERT_FALSE(r.hdr.empty());
    const Mean lit = meanWhere(r.hdr, s.camera, direct(false));
    const Mean shade = meanWhere(r.hdr, s.camera, direct(true));
    const Mean mirror = meanWhere(r.hdr, s.camera, mirrored);
    std::printf("[unlit] %-13s sunlit %s (%d px), in shadow %s (%d px), in the mirror %s (%d px)\n", mode.name,
                fmtRgb(lit.rgb).c_str(), lit.pixels, fmtRgb(shade.rgb).c_str(), shade.pixels,
                fmtRgb(mirror.rgb).c_str(), mirror.pixels);
    ASSERT_GT(lit.pixels, 200);
    ASSERT_GT(shade.pixels, 10);
    ASSERT_GT(mirror.pixels, 50);
    // Seen directly: exactly its base colour (fp16 HDR rounding only).
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(lit.rgb[c], base[c], 0.005) << "channel " << c << " in the sun";
      EXPECT_NEAR(shade.rgb[c], base[c], 0.005) << "channel " << c << " in the box's shadow";
    }
    // In a mirror of reflectance 1: the hybrid's split-sum lobe albedo and the denoiser's blur
    // at reflected edges cost a few percent; the raster mode's screen-space reflections more.
    const double tol = std::string(mode.name) == "raster" ? 0.1 : 0.04;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(mirror.rgb[c], base[c], tol * base[c] + 0.005) << "channel " << c << " in the mirror";
  }
}

// ---- KHR_materials_specular ----

// Four black dielectric quads in a 2 × 2 grid, symmetric about the view axis, so that every quad
// sees the same angles: specular 1; specular 1 × a specularTexture whose A is 128/255 (its RGB 0, to
// catch reading the wrong channel); specular 0; specularColor (1, 0.5, 0.5) × a red
// specularColorTexture. Black base colour leaves only the specular lobe, which the extension scales
// by `specular` at every angle (F0 and F90 alike) and tints by the colour at F0 only.
struct SpecularGrid {
  SceneSpec scene;
  std::filesystem::path file;
};
SpecularGrid specularGrid(const std::filesystem::path& dir, const std::string& name, float roughness) {
  Image8 half = Image8::make(1, 1), red = Image8::make(1, 1);
  half.rgba = {0, 0, 0, 128};
  red.rgba = {255, 0, 0, 255};
  EXPECT_TRUE(writePng(dir / "spec-half.png", half).ok());
  EXPECT_TRUE(writePng(dir / "spec-red.png", red).ok());
  MaterialSpec full{glm::vec3(0.0f), 0.0f, roughness}, textured = full, none = full, tinted = full;
  textured.specularTexture = "spec-half.png";
  none.specular = 0.0f;
  tinted.specularColor = glm::vec3(1.0f, 0.5f, 0.5f);
  tinted.specularColorTexture = "spec-red.png";
  SpecularGrid g;
  const float c = 0.9f;
  g.scene.models = {{"full", unitQuad(), full, glm::vec3(1.6f, 1.6f, 1), glm::vec3(0), glm::vec3(-c, c, 0)},
                    {"half", unitQuad(), textured, glm::vec3(1.6f, 1.6f, 1), glm::vec3(0), glm::vec3(c, c, 0)},
                    {"none", unitQuad(), none, glm::vec3(1.6f, 1.6f, 1), glm::vec3(0), glm::vec3(-c, -c, 0)},
                    {"red", unitQuad(), tinted, glm::vec3(1.6f, 1.6f, 1), glm::vec3(0), glm::vec3(c, -c, 0)}};
  g.scene.camera = {{0, 0, 6}, {0, 0, 0}, 40};
  g.file = dir / (name + ".json");
  return g;
}

struct GridMeans {
  Mean full, half, none, red;
};
// The same region of each quad, mirrored into its quadrant: 0.3 to 1.5 from the axes.
GridMeans gridMeans(const ImageF& img, const CameraSpec& cam) {
  auto quadrant = [](float sx, float sy) {
    return [=](const Ray& r) {
      const glm::vec2 p = onPlaneZ0(r);
      const float x = p.x * sx, y = p.y * sy;
      return x >= 0.3f && x <= 1.5f && y >= 0.3f && y <= 1.5f;
    };
  };
  return {meanWhere(img, cam, quadrant(-1, 1)), meanWhere(img, cam, quadrant(1, 1)),
          meanWhere(img, cam, quadrant(-1, -1)), meanWhere(img, cam, quadrant(1, -1))};
}

// What every mode must show: the lobe scales with specular (texture A 128/255 ≈ 0.502), is gone at
// 0, and the red tint keeps the red channel of the untinted lobe while green and blue keep only
// the F90 part (≈ 0 at these angles).
void expectSpecularScaling(const GridMeans& m, double minFull) {
  ASSERT_GT(m.full.pixels, 100);
  ASSERT_EQ(m.full.pixels, m.half.pixels) << "the grid should be symmetric";
  const double full = m.full.rgb.g;
  EXPECT_GT(full, minFull);
  EXPECT_NEAR(m.half.rgb.g / full, 128.0 / 255.0, 0.02) << "specularTexture.a × specularFactor";
  EXPECT_LT(m.none.rgb.g, 0.01 * full) << "specular 0: a pure diffuse (here: black) material";
  EXPECT_NEAR(m.red.rgb.r / full, 1.0, 0.03) << "red channel: F0 · 1";
  EXPECT_LT(m.red.rgb.g, 0.1 * full) << "green: only the grazing part, F90 · (1 − v·h)⁵";
  EXPECT_LT(m.red.rgb.b, 0.1 * full);
}

// The highlight of a sun behind the camera on rough (0.7) quads, black environment: direct light
// through the BRDF (hybrid: the lighting pass, with traced or shadow-map visibility; path tracer:
// next-event estimation). Rough enough that no traced glossy reflection stands in for the lobe.
TEST(Specular, HighlightScalesAndTintsAsTheExtensionSays) {
  auto dir = testDir();
  SpecularGrid g = specularGrid(dir, "highlight", 0.7f);
  g.scene.lights = {R"({"type": "directional", "direction": [0, 0, -1], "intensity": 10, "angularRadius": 0})"};
  writeScene(dir, "highlight", g.scene);
  std::vector<GridMeans> means;
  for (const ModeSpec& mode : kModes) {
    SCOPED_TRACE(mode.name);
    Rendered r = renderHdr(dir, mode.name, g.file, kSize, kSize, mode.frames, "", mode.args);
    ASSERT_FALSE(r.hdr.empty());
    GridMeans m = gridMeans(r.hdr, g.scene.camera);
    std::printf("[specular highlight] %-13s full %s half %s none %s red %s\n", mode.name, fmtRgb(m.full.rgb).c_str(),
                fmtRgb(m.half.rgb).c_str(), fmtRgb(m.none.rgb).c_str(), fmtRgb(m.red.rgb).c_str());
    // GGX at α = 0.49 on the half vector: D·V·F·E ≈ 1.3 · 0.25 · 0.04 · 10 ≈ 0.13 at the peak.
    expectSpecularScaling(m, 0.03);
    means.push_back(m);
  }
  // The hybrid evaluates the same BRDF as the path tracer for a delta sun (no noise but the path
  // tracer's sub-pixel jitter): they agree to the G-buffer's 8-bit quantisation of roughness and of
  // specular (each ≤ 0.4 %, moving this lobe's mean by about 1 %) and fp16, i.e. within 3 %.
  const GridMeans& pt = means.back();
  for (size_t i = 0; i + 1 < means.size(); ++i) {
    SCOPED_TRACE(kModes[i].name);
    EXPECT_NEAR(means[i].full.rgb.g / pt.full.rgb.g, 1.0, 0.03) << "hybrid / raster vs path tracer, specular 1";
    EXPECT_NEAR(means[i].half.rgb.g / pt.half.rgb.g, 1.0, 0.03) << "specular 0.5";
    EXPECT_NEAR(means[i].red.rgb.r / pt.red.rgb.r, 1.0, 0.03) << "red";
  }
}

// Mirror-smooth quads in a uniform environment of radiance 5: each reflects F · 5 with F ≈ F0 at
// these angles: 0.04 · 5 = 0.2 at specular 1 (traced mirror reflection × the lobe's F0·A + F90·B in
// the hybrid, the environment approximation in raster mode, the BSDF in the path tracer).
TEST(Specular, ReflectionScalesAndTintsAsTheExtensionSays) {
  auto dir = testDir();
  SpecularGrid g = specularGrid(dir, "mirror", 0.0f);
  g.scene.lights = {darkLight()};
  g.scene.environment = uniformEnvironment(5.0f);
  writeScene(dir, "mirror", g.scene);
  std::vector<GridMeans> means;
  for (const ModeSpec& mode : kModes) {
    SCOPED_TRACE(mode.name);
    Rendered r = renderHdr(dir, mode.name, g.file, kSize, kSize, mode.frames, "", mode.args);
    ASSERT_FALSE(r.hdr.empty());
    GridMeans m = gridMeans(r.hdr, g.scene.camera);
    std::printf("[specular mirror] %-13s full %s half %s none %s red %s\n", mode.name, fmtRgb(m.full.rgb).c_str(),
                fmtRgb(m.half.rgb).c_str(), fmtRgb(m.none.rgb).c_str(), fmtRgb(m.red.rgb).c_str());
    expectSpecularScaling(m, 0.1);
    // Schlick at ≤ 25° off normal adds (1 − cos)⁵ < 1e-5: F0 · L to the DFG table's accuracy.
    EXPECT_NEAR(m.full.rgb.g, 0.2, 0.01) << "0.04 · 5";
    means.push_back(m);
  }
  // Hybrid vs path tracer: the split-sum table at roughness 0 (its A + B is 1 to about 1 %) and
  // 16 path-traced samples per pixel of an almost noiseless integrand: within 3 %.
  const GridMeans& pt = means.back();
  for (size_t i = 0; i + 1 < means.size(); ++i) {
    SCOPED_TRACE(kModes[i].name);
    EXPECT_NEAR(means[i].full.rgb.g / pt.full.rgb.g, 1.0, 0.03);
    EXPECT_NEAR(means[i].red.rgb.r / pt.red.rgb.r, 1.0, 0.03);
  }
}

// The energy split: white diffuse quads under a uniform environment of radiance 1, rough (1), one
// with the default specular, one with specularColor red. The extension takes from the diffuse
// layer what the dielectric lobe's largest channel reflects (1 − max F), so the tinted quad's green
// and blue carry its diffuse layer alone, (1 − F)·1 with F ≈ F0 = 0.04 (the red lobe's): 0.96,
// where the per-channel rule 1 − F_green would give 1.
TEST(Specular, DiffuseKeepsWhatTheLargestChannelLeaves) {
  auto dir = testDir();
  SceneSpec s;
  MaterialSpec white{glm::vec3(1.0f), 0.0f, 1.0f}, tinted = white;
  tinted.specularColor = glm::vec3(1.0f, 0.0f, 0.0f);
  s.models = {{"white", unitQuad(), white, glm::vec3(1.8f, 1.8f, 1), glm::vec3(0), glm::vec3(-1, 0, 0)},
              {"tinted", unitQuad(), tinted, glm::vec3(1.8f, 1.8f, 1), glm::vec3(0), glm::vec3(1, 0, 0)}};
  s.lights = {darkLight()};
  s.environment = uniformEnvironment(1.0f);
  s.camera = {{0, 0, 6}, {0, 0, 0}, 40};
  const auto scene = writeScene(dir, "split", s);
  std::vector<double> greens;
  for (const ModeSpec& mode : kModes) {
    SCOPED_TRACE(mode.name);
    Rendered r = renderHdr(dir, mode.name, scene, kSize, kSize, mode.frames, "", mode.args);
    ASSERT_FALSE(r.hdr.empty());
    const Mean w = meanWhere(r.hdr, s.camera, inRect(-1.7f, -0.7f, -0.3f, 0.7f));
    const Mean t = meanWhere(r.hdr, s.camera, inRect(0.3f, -0.7f, 1.7f, 0.7f));
    ASSERT_EQ(w.pixels, t.pixels);
    ASSERT_GT(w.pixels, 200);
    std::printf("[specular split] %-13s white %s tinted %s\n", mode.name, fmtRgb(w.rgb).c_str(), fmtRgb(t.rgb).c_str());
    EXPECT_NEAR(t.rgb.r / w.rgb.r, 1.0, 0.01) << "red: the same lobe and the same diffuse layer";
    EXPECT_NEAR(t.rgb.g, t.rgb.b, 1e-3);
    // (The path tracer integrates 1 − Schlick(v·h) over the incident directions, a little below 0.96.)
    EXPECT_NEAR(t.rgb.g, 0.96, 0.01) << "green: the diffuse layer alone, 1 − F of the red channel";
    greens.push_back(t.rgb.g);
  }
  // The diffuse layer alone is the same integral in both (no split-sum approximation of a lobe):
  // hybrid and path tracer within 1 %.
  for (size_t i = 0; i + 1 < greens.size(); ++i) EXPECT_NEAR(greens[i] / greens.back(), 1.0, 0.01) << kModes[i].name;
}

// Glass: two thin-walled panes (ior 1.5, transmission 1) seen from above under a sky of radiance 1
// above the horizon and 0 below it, so each pixel carries only the reflected sky: F at near-normal
// incidence. The extension remaps the exact Fresnel F0(η) … 1 onto its F0 … F90: specular 0.5 halves
// it (0.02), specularColor red keeps 0.04 in red and nothing in green and blue. Reflection is
// chosen stochastically (probability max F), so the hybrid and the path tracer average 32 frames.
TEST(Specular, ScalesAndTintsGlassReflections) {
  auto dir = testDir();
  SceneSpec s;
  MaterialSpec half = glass(1.5f, 0.0f), red = half;
  half.specular = 0.5f;
  red.specularColor = glm::vec3(1.0f, 0.0f, 0.0f);
  s.models = {{"half", unitQuad(), half, glm::vec3(2, 4, 1), glm::vec3(-90, 0, 0), glm::vec3(-1.05f, 0, 0)},
              {"red", unitQuad(), red, glm::vec3(2, 4, 1), glm::vec3(-90, 0, 0), glm::vec3(1.05f, 0, 0)}};
  s.lights = {darkLight()};
  s.environment = R"({"sky": {"zenith": [1, 1, 1], "horizon": [1, 1, 1], "ground": [0, 0, 0]}, "intensity": 1})";
  s.camera = {{0, 6, 0.5f}, {0, 0, 0}, 30};
  const auto scene = writeScene(dir, "glass", s);
  // Pixels whose ray meets the plane y = 0 inside x0 ≤ x ≤ x1, |z| ≤ 1.2.
  auto onFloor = [](float x0, float x1) {
    return [=](const Ray& r) {
      glm::vec3 p;
      return hitHorizontal(r, 0.0f, p) && p.x >= x0 && p.x <= x1 && std::abs(p.z) <= 1.2f;
    };
  };
  for (const ModeSpec& mode : kModes) {
    SCOPED_TRACE(mode.name);
    const int frames = std::string(mode.name) == "raster" ? 2 : 32;
    Rendered r = renderHdr(dir, mode.name, scene, kSize, kSize, frames, "", mode.args);
    ASSERT_FALSE(r.hdr.empty());
    const Mean h = meanWhere(r.hdr, s.camera, onFloor(-1.8f, -0.3f));
    const Mean t = meanWhere(r.hdr, s.camera, onFloor(0.3f, 1.8f));
    ASSERT_GT(h.pixels, 300);
    ASSERT_GT(t.pixels, 300);
    std::printf("[specular glass] %-13s half %s red %s (%d px each)\n", mode.name, fmtRgb(h.rgb).c_str(),
                fmtRgb(t.rgb).c_str(), h.pixels);
    // Binomial noise of pixels × frames reflection choices at F ≈ 0.02–0.04: σ < 0.001; 4 σ plus
    // the rise of F over the panes' ≤ 10° off-normal angles (< 0.001). The raster mode's Schlick
    // approximation is deterministic.
    const double tol = 0.005;
    EXPECT_NEAR(h.rgb.g, 0.02, tol) << "specular 0.5 halves the glass reflection";
    EXPECT_NEAR(h.rgb.r, h.rgb.g, tol);
    EXPECT_NEAR(t.rgb.r, 0.04, tol + 0.002) << "the red tint keeps the red reflection";
    EXPECT_LT(t.rgb.g, 0.002) << "and removes the others (F90 · w ≈ 0 near normal incidence)";
    EXPECT_LT(t.rgb.b, 0.002);
  }
}

}  // namespace
}  // namespace rayster::test::analytic
