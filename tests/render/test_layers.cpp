// The material layers end to end in the path tracer (lib/layers.glsl), each against what the
// extension's physics says a user must see: a white furnace that no layer brightens, a clear coat
// reflecting F(η 1.5) of its environment scaled by its factor and texture, a sheen whose albedo
// rises towards grazing views as its table says, a thin film whose colour follows its thickness as
// interference predicts, and an anisotropic highlight stretched along the direction its rotation
// picks. Plus KHR_materials_variants through --variant, and the hybrid's one-line warning.
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "shaders/shared/sheen.h"
#include "tests/render/analytic_scenes.h"

namespace rayster::test::analytic {
namespace {

constexpr int kSize = 48;

// Where a pixel ray meets the unit sphere at the origin (radius 0.5): n·v of that point, or -1.
double sphereCosine(const Ray& r) {
  const double b = glm::dot(r.origin, r.dir), c = glm::dot(r.origin, r.origin) - 0.25;
  const double disc = b * b - c;
  if (disc <= 0) return -1;
  const glm::dvec3 p = glm::dvec3(r.origin) + glm::dvec3(r.dir) * (-b - std::sqrt(disc));
  return glm::dot(glm::normalize(p), -glm::dvec3(r.dir));
}

struct Ring {
  glm::dvec3 rgb{0.0};
  int pixels = 0;
};
// Mean linear RGB of the sphere's pixels whose n·v lies in [lo, hi).
Ring sphereRing(const ImageF& img, const CameraSpec& cam, double lo, double hi) {
  Ring m;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const double c = sphereCosine(pixelRay(cam, img.width, img.height, x, y));
      if (c < lo || c >= hi) continue;
      const float* p = img.pixel(x, y);
      m.rgb += glm::dvec3(p[0], p[1], p[2]);
      ++m.pixels;
    }
  if (m.pixels) m.rgb /= double(m.pixels);
  return m;
}

// A base that reflects nothing by itself: black, rough, no dielectric lobe (specular 0).
MaterialSpec blackBase() {
  MaterialSpec m{glm::vec3(0.0f), 0.0f, 1.0f};
  m.specular = 0.0f;
  return m;
}

SceneSpec sphereInFurnace(const MaterialSpec& material, float radiance) {
  SceneSpec s;
  s.models = {{"ball", unitSphere(32), material}};
  s.lights = {darkLight()};
  s.environment = uniformEnvironment(radiance);
  s.camera = {{0, 0, 2.2f}, {0, 0, 0}, 30.0f};
  return s;
}

Rendered pathTrace(const std::filesystem::path& dir, const std::string& name, const SceneSpec& s, int spp,
                   int size = kSize) {
  auto file = writeScene(dir, name, s);
  return renderHdr(dir, name, file, size, size, spp, "", "--mode pathtrace");
}

// A white furnace: a convex object in uniform radiance 1 shows its directional albedo, which no
// layer may push above 1 (a layer that creates energy glows). The white base alone reflects almost
// everything (Lambert + GGX lose little), so every layer on top is tested against the bound.
TEST(Layers, NoLayerCreatesEnergyInAWhiteFurnace) {
  auto dir = testDir();
  const char* const layers[][2] = {
      {"clearcoat", R"("KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatRoughnessFactor": 0.3})"},
      {"sheen", R"("KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1], "sheenRoughnessFactor": 0.3})"},
      {"iridescence", R"("KHR_materials_iridescence": {"iridescenceFactor": 1, "iridescenceIor": 1.8})"},
      {"anisotropy", R"("KHR_materials_anisotropy": {"anisotropyStrength": 1})"},
      {"all", R"("KHR_materials_clearcoat": {"clearcoatFactor": 1},
                 "KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1], "sheenRoughnessFactor": 0.8},
                 "KHR_materials_iridescence": {"iridescenceFactor": 1},
                 "KHR_materials_anisotropy": {"anisotropyStrength": 0.5})"},
  };
  for (const auto& [name, json] : layers) {
    SCOPED_TRACE(name);
    MaterialSpec m{glm::vec3(1.0f), 0.0f, 0.5f};
    m.layers = json;
    SceneSpec s = sphereInFurnace(m, 1.0f);
    Rendered r = pathTrace(dir, name, s, 32, 32);
    ASSERT_FALSE(r.hdr.empty());
    const Ring all = sphereRing(r.hdr, s.camera, 0.0, 1.01);
    const Ring rim = sphereRing(r.hdr, s.camera, 0.0, 0.35);
    std::printf("[furnace] %-12s all %.4f %.4f %.4f  rim %.4f %.4f %.4f\n", name, all.rgb.r, all.rgb.g, all.rgb.b,
                rim.rgb.r, rim.rgb.g, rim.rgb.b);
    ASSERT_GT(all.pixels, 300);
    for (int c = 0; c < 3; ++c) {
      // 32 samples over ~450 pixels: the mean's noise is well under 1 %.
      EXPECT_LE(all.rgb[c], 1.01) << "channel " << c;
      EXPECT_LE(rim.rgb[c], 1.03) << "grazing views, channel " << c;
      EXPECT_GE(all.rgb[c], 0.75) << "the layers must not swallow the light either, channel " << c;
    }
  }
}

// Two quads in a uniform environment of radiance 5, seen head-on: a smooth clear coat on a base
// that reflects nothing shows F(η 1.5) · 5 = 0.04 · 5 = 0.2 at normal incidence, × its factor and
// × its texture's R (128/255 here). `mode`: --mode pathtrace, hybrid or raster.
void expectClearcoatFresnel(const std::string& mode) {
  SCOPED_TRACE(mode);
  auto dir = testDir();
  Image8 half = Image8::make(4, 4);
  for (size_t i = 0; i < half.rgba.size(); ++i) half.rgba[i] = 128;
  ASSERT_TRUE(writePng(dir / "half.png", half).ok());
  MaterialSpec full = blackBase(), textured = blackBase();
  full.layers = R"("KHR_materials_clearcoat": {"clearcoatFactor": 1})";
  textured.layers = R"("KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatTexture": {"index": $TEX}})";
  textured.layerTexture = "half.png";
  SceneSpec s;
  s.models = {{"full", unitQuad(), full, glm::vec3(0.9f), glm::vec3(0), glm::vec3(-0.5f, 0, 0)},
              {"textured", unitQuad(), textured, glm::vec3(0.9f), glm::vec3(0), glm::vec3(0.5f, 0, 0)}};
  s.lights = {darkLight()};
  s.environment = uniformEnvironment(5.0f);
  s.camera = {{0, 0, 4}, {0, 0, 0}, 30.0f};
  auto file = writeScene(dir, "coat", s);
  Rendered r = renderHdr(dir, "coat", file, kSize, kSize, mode == "pathtrace" ? 32 : 2, "", "--mode " + mode);
  ASSERT_FALSE(r.hdr.empty());
  auto mean = [&](float x0, float x1) {
    glm::dvec3 sum(0.0);
    int n = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const Ray ray = pixelRay(s.camera, kSize, kSize, x, y);
        const glm::vec3 p = ray.origin + ray.dir * (-ray.origin.z / ray.dir.z);
        if (p.x < x0 || p.x > x1 || std::abs(p.y) > 0.35f) continue;
        const float* v = r.hdr.pixel(x, y);
        sum += glm::dvec3(v[0], v[1], v[2]);
        ++n;
      }
    EXPECT_GT(n, 50);
    return sum / double(std::max(n, 1));
  };
  const glm::dvec3 a = mean(-0.85f, -0.15f), b = mean(0.15f, 0.85f);
  std::printf("[clearcoat] %s: factor 1: %.4f %.4f %.4f  texture 0.5: %.4f %.4f %.4f\n", mode.c_str(), a.r, a.g, a.b,
              b.r, b.g, b.b);
  for (int c = 0; c < 3; ++c) {
    // Schlick at the quads' viewing angles (up to 12 degrees off normal) adds < 0.1 %.
    EXPECT_NEAR(a[c], 0.2, 0.2 * 0.04) << "factor 1, channel " << c;
    EXPECT_NEAR(b[c], 0.2 * 128.0 / 255.0, 0.1 * 0.05) << "factor 1 × texture 128/255, channel " << c;
  }
}

TEST(Layers, ClearcoatReflectsItsFresnelScaledByFactorAndTexture) { expectClearcoatFresnel("pathtrace"); }
// The hybrid and raster modes shade the coat too (lib/shading.glsl): its reflection of the
// environment is the same 0.2.
TEST(Layers, HybridAndRasterClearcoatReflectItsFresnel) {
  expectClearcoatFresnel("hybrid");
  expectClearcoatFresnel("raster");
}

// A red sheen on a black base in a uniform environment of radiance 1: only red comes back, and as
// much as the sheen lobe's directional albedo (shared/sheen.h), which grows towards grazing views.
void expectSheenAlbedo(const std::string& mode) {
  SCOPED_TRACE(mode);
  auto dir = testDir();
  MaterialSpec m = blackBase();
  m.layers = R"("KHR_materials_sheen": {"sheenColorFactor": [1, 0, 0], "sheenRoughnessFactor": 0.5})";
  SceneSpec s = sphereInFurnace(m, 1.0f);
  auto file = writeScene(dir, "sheen", s);
  Rendered r = renderHdr(dir, "sheen", file, kSize, kSize, mode == "pathtrace" ? 32 : 2, "", "--mode " + mode);
  ASSERT_FALSE(r.hdr.empty());
  // From n·v 0.3: the pixels nearer the silhouette also see the background (sub-pixel jitter).
  const double bands[][2] = {{0.3, 0.45}, {0.45, 0.6}, {0.6, 0.8}, {0.85, 1.01}};
  double previous = 1e9;
  for (const auto& band : bands) {
    const Ring ring = sphereRing(r.hdr, s.camera, band[0], band[1]);
    // The table's mean over the band's n·v (the pixels' n·v spread evenly enough for a midpoint).
    double expected = 0;
    for (int i = 0; i < 16; ++i)
      expected += gpu::sheenAlbedo(float(band[0] + (std::min(band[1], 1.0) - band[0]) * (i + 0.5) / 16), 0.5f) / 16;
    std::printf("[sheen] %s n.v %.2f-%.2f: %.4f %.4f %.4f (table %.4f, %d px)\n", mode.c_str(), band[0], band[1],
                ring.rgb.r, ring.rgb.g, ring.rgb.b, expected, ring.pixels);
    ASSERT_GT(ring.pixels, 20);
    EXPECT_NEAR(ring.rgb.r, expected, 0.1 * expected + 0.003);
    EXPECT_LT(ring.rgb.g, 1e-4) << "a red sheen reflects no green";
    EXPECT_LT(ring.rgb.b, 1e-4) << "nor blue";
    EXPECT_LT(ring.rgb.r, previous) << "the sheen is brightest at grazing views";
    previous = ring.rgb.r;
  }
}

TEST(Layers, SheenReflectsItsColourAsItsAlbedoTableSays) { expectSheenAlbedo("pathtrace"); }
// The hybrid's sheen reflects the environment's irradiance times the same albedo.
TEST(Layers, HybridSheenReflectsItsColourAsItsAlbedoTableSays) { expectSheenAlbedo("hybrid"); }

// Under a light the hybrid's coat and sheen are the path tracer's lobes (lib/layer_lobes.glsl): a
// rough red sphere with a smooth clear coat, and one with a white sheen, lit by a small sphere light
// above the camera in a dim environment. The hybrid's image (4 frames) is within 5 % of the path
// tracer's (256 samples) in mean, and the coat's highlight is where the path tracer draws it and as
// bright; without the coat there is no such highlight.
TEST(Layers, HybridCoatAndSheenUnderALightMatchThePathTracer) {
  auto dir = testDir();
  struct Case {
    const char* name;
    const char* layers;
  };
  const Case cases[] = {
      {"coat", R"("KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatRoughnessFactor": 0.15})"},
      {"sheen", R"("KHR_materials_sheen": {"sheenColorFactor": [0.9, 0.9, 0.9], "sheenRoughnessFactor": 0.4})"},
      {"none", ""},
  };
  auto brightest = [](const ImageF& img, int& bx, int& by) {
    float best = -1;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        if (const float* p = img.pixel(x, y); p[0] + p[1] + p[2] > best) {
          best = p[0] + p[1] + p[2];
          bx = x;
          by = y;
        }
    return best;
  };
  float coatPeak = 0, plainPeak = 0;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    MaterialSpec m{glm::vec3(0.7f, 0.08f, 0.05f), 0.0f, 0.7f};
    m.layers = c.layers;
    SceneSpec s;
    s.models = {{"ball", unitSphere(48), m}};
    s.lights = {R"({"type": "point", "position": [0.6, 1.2, 2.0], "intensity": 6, "radius": 0.05})"};
    s.environment = uniformEnvironment(0.1f);
    s.camera = {{0, 0, 2.2f}, {0, 0, 0}, 30.0f};
    auto file = writeScene(dir, c.name, s);
    Rendered pt = renderHdr(dir, std::string(c.name) + "-pt", file, kSize, kSize, 256, "", "--mode pathtrace");
    Rendered hy = renderHdr(dir, std::string(c.name) + "-hybrid", file, kSize, kSize, 4, "", "--mode hybrid");
    ASSERT_FALSE(pt.hdr.empty());
    ASSERT_FALSE(hy.hdr.empty());
    const Ring a = sphereRing(pt.hdr, s.camera, 0.0, 1.01), b = sphereRing(hy.hdr, s.camera, 0.0, 1.01);
    int px = 0, py = 0, hx = 0, hy2 = 0;
    const float ptPeak = brightest(pt.hdr, px, py), hyPeak = brightest(hy.hdr, hx, hy2);
    std::printf(
        "[layers under a light] %-5s mean pt %.4f %.4f %.4f hybrid %.4f %.4f %.4f; peak pt %.3f at %d,%d "
        "hybrid %.3f at %d,%d\n",
        c.name, a.rgb.r, a.rgb.g, a.rgb.b, b.rgb.r, b.rgb.g, b.rgb.b, ptPeak, px, py, hyPeak, hx, hy2);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(b.rgb[ch], a.rgb[ch], 0.05 * a.rgb[ch] + 1e-3) << "channel " << ch;
    if (std::string(c.name) == "coat") {
      EXPECT_LE(std::abs(px - hx) + std::abs(py - hy2), 2) << "the coat's highlight is where the path tracer has it";
      EXPECT_NEAR(hyPeak, ptPeak, 0.25 * ptPeak) << "and as bright (one pixel: the path tracer's noise)";
      coatPeak = hyPeak;
    }
    if (std::string(c.name) == "none") plainPeak = hyPeak;
  }
  EXPECT_GT(coatPeak, 2.0f * plainPeak) << "the coat's highlight is the coat's";
}

// A thin film of η 1.8 on glass-like η 1.5 seen head-on: light reflected at its top gains a half
// wave (air → denser film), light reflected at its bottom does not (film → less dense base), so
// the two add up where the optical path 2·η·d is a whole number of wavelengths plus a half:
// d = 300 nm (1080 nm) at 720 and 432 nm and cancels at 540 nm, magenta; d = 500 nm (1800 nm) at
// 514 nm, green. Without the film the reflection is grey.
TEST(Layers, IridescenceColoursTheReflectionAsInterferencePredicts) {
  auto dir = testDir();
  auto film = [&](const std::string& name, int thickness) {
    MaterialSpec m{glm::vec3(0.0f), 0.0f, 0.0f};
    if (thickness > 0)
      m.layers = fmt::format(
          R"("KHR_materials_iridescence": {{"iridescenceFactor": 1, "iridescenceIor": 1.8, "iridescenceThicknessMaximum": {}}})",
          thickness);
    SceneSpec s;
    s.models = {{name, unitQuad(), m, glm::vec3(2.0f)}};
    s.lights = {darkLight()};
    s.environment = uniformEnvironment(1.0f);
    s.camera = {{0, 0, 4}, {0, 0, 0}, 12.0f};
    Rendered r = pathTrace(dir, name, s, 32);
    EXPECT_FALSE(r.hdr.empty());
    glm::dvec3 sum(0.0);
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const float* v = r.hdr.pixel(x, y);
        sum += glm::dvec3(v[0], v[1], v[2]);
      }
    sum /= double(kSize * kSize);
    std::printf("[iridescence] %-5s %.4f %.4f %.4f\n", name.c_str(), sum.r, sum.g, sum.b);
    return sum;
  };
  const glm::dvec3 none = film("none", 0), magenta = film("d300", 300), green = film("d500", 500);
  EXPECT_NEAR(none.r / none.b, 1.0, 0.02) << "no film: a grey reflection";
  EXPECT_NEAR(none.g, 0.04, 0.004) << "F0 of η 1.5";
  EXPECT_LT(magenta.g, 0.7 * std::min(magenta.r, magenta.b)) << "d = 300 nm: magenta";
  EXPECT_GT(green.g, 1.3 * std::max(green.r, green.b)) << "d = 500 nm: green";
}

// A rough metal quad under a sun from the camera: the highlight's spread along x and y (second
// moments of its brightness over the quad). Isotropic: round. Anisotropic: stretched along the
// direction, and turned by a quarter turn with anisotropyRotation π/2.
TEST(Layers, AnisotropyStretchesTheHighlightAlongItsDirection) {
  auto dir = testDir();
  auto spread = [&](const std::string& name, const std::string& layers) {
    MaterialSpec m{glm::vec3(1.0f), 1.0f, 0.25f};
    m.layers = layers;
    SceneSpec s;
    s.models = {{name, unitQuad(), m, glm::vec3(3.0f)}};
    s.lights = {R"({"type": "directional", "direction": [0, 0, -1], "intensity": 3, "angularRadius": 0})"};
    s.camera = {{0, 0, 3}, {0, 0, 0}, 50.0f};
    Rendered r = pathTrace(dir, name, s, 16);
    EXPECT_FALSE(r.hdr.empty());
    double w = 0, xx = 0, yy = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const Ray ray = pixelRay(s.camera, kSize, kSize, x, y);
        const glm::vec3 p = ray.origin + ray.dir * (-ray.origin.z / ray.dir.z);
        if (std::abs(p.x) > 1.5f || std::abs(p.y) > 1.5f) continue;
        const double v = r.hdr.pixel(x, y)[1];
        w += v, xx += v * p.x * p.x, yy += v * p.y * p.y;
      }
    const double ratio = xx / std::max(yy, 1e-12);
    std::printf("[anisotropy] %-8s spread x %.4f y %.4f ratio %.3f\n", name.c_str(), xx / w, yy / w, ratio);
    return ratio;
  };
  const double iso = spread("iso", "");
  const double along = spread("along", R"("KHR_materials_anisotropy": {"anisotropyStrength": 0.9})");
  const double turned =
      spread("turned", R"("KHR_materials_anisotropy": {"anisotropyStrength": 0.9, "anisotropyRotation": 1.5707963})");
  EXPECT_NEAR(iso, 1.0, 0.15) << "isotropic: a round highlight";
  EXPECT_TRUE((along > 2.0 && turned < 0.5) || (along < 0.5 && turned > 2.0))
      << "stretched along one axis, and along the other a quarter turn later: " << along << ", " << turned;
}

// A glass ball (η 1.5, a volume) in front of a lit band above its centre: seen through the ball,
// the band's image depends on η. Without dispersion every path is grey, so the ball's mean colour
// is exactly grey; with dispersion 5 (Abbe number 4) red, green and blue refract with different η
// and see different shares of the band, green's between red's and blue's (η rises with frequency).
TEST(Layers, DispersionSplitsTheColoursAGlassBallRefracts) {
  auto dir = testDir();
  auto ball = [&](const std::string& name, float dispersion) {
    MaterialSpec g = glass(1.5f, 1.0f);
    if (dispersion > 0) g.layers = fmt::format(R"("KHR_materials_dispersion": {{"dispersion": {}}})", dispersion);
    SceneSpec s;
    s.models = {
        {"ball", unitSphere(32), g},
        {"band", unitQuad(), emitter(1.0f), glm::vec3(3.0f, 0.6f, 1.0f), glm::vec3(0), glm::vec3(0, 0.45f, -1.5f)}};
    s.lights = {darkLight()};
    s.camera = {{0, 0, 2.5f}, {0, 0, 0}, 28.0f};
    Rendered r = pathTrace(dir, name, s, 32);
    EXPECT_FALSE(r.hdr.empty());
    return sphereRing(r.hdr, s.camera, 0.2, 1.01).rgb;
  };
  const glm::dvec3 grey = ball("plain", 0.0f), split = ball("dispersive", 5.0f);
  std::printf("[dispersion] plain %.4f %.4f %.4f  dispersive %.4f %.4f %.4f\n", grey.r, grey.g, grey.b, split.r,
              split.g, split.b);
  EXPECT_GT(grey.g, 0.05) << "the band shows through the ball";
  EXPECT_NEAR(grey.r, grey.b, 1e-5) << "no dispersion: every path is grey";
  EXPECT_NEAR(grey.g, grey.b, 1e-5);
  EXPECT_GT(std::abs(split.r - split.b), 0.1 * (split.r + split.b) / 2) << "red and blue see different shares";
  EXPECT_TRUE((split.r - split.g) * (split.g - split.b) > 0) << "green's share lies between red's and blue's";
}

// KHR_materials_variants: --variant picks a variant's material, an unknown one is refused (exit 3)
// naming the variants; the hybrid warns once what it approximates of layered materials.
TEST(Layers, VariantIsSelectedOnTheCommandLineAndTheHybridSaysWhatItApproximates) {
  auto dir = testDir();
  MaterialSpec grey{glm::vec3(0.5f)};
  grey.layers = R"("KHR_materials_clearcoat": {"clearcoatFactor": 1})";
  SceneSpec s;
  s.models = {{"quad", unitQuad(), grey, glm::vec3(0.6f)}};
  s.lights = {R"({"type": "directional", "direction": [0, 0, -1], "intensity": 2, "angularRadius": 0})"};
  s.camera = {{0, 0, 3}, {0, 0, 0}, 20.0f};
  auto file = writeScene(dir, "variants", s);
  // Add two variants to the written glTF: "red" and "blue" materials mapped onto the quad.
  {
    std::ifstream in(dir / "quad.gltf");
    nlohmann::json j = nlohmann::json::parse(in);
    j["extensionsUsed"].push_back("KHR_materials_variants");
    j["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "red"}}, {{"name", "blue"}}};
    nlohmann::json red = {{"name", "red"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}}}};
    nlohmann::json blue = {{"name", "blue"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 1, 1}}}}};
    j["materials"].push_back(red);
    j["materials"].push_back(blue);
    j["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"] = {
        {{"material", 1}, {"variants", {0}}}, {{"material", 2}, {"variants", {1}}}};
    std::ofstream(dir / "quad.gltf") << j.dump();
  }
  auto centre = [&](const Rendered& r) {
    const float* p = r.hdr.pixel(kSize / 2, kSize / 2);
    return glm::vec3(p[0], p[1], p[2]);
  };
  Rendered base = renderHdr(dir, "default", file, kSize, kSize, 2, "", "--mode hybrid");
  Rendered blue = renderHdr(dir, "blue", file, kSize, kSize, 2, "", "--mode hybrid --variant blue");
  ASSERT_FALSE(base.hdr.empty());
  ASSERT_FALSE(blue.hdr.empty());
  const glm::vec3 g = centre(base), b = centre(blue);
  EXPECT_NEAR(g.r / g.b, 1.0, 0.05) << "the default material is grey";
  EXPECT_GT(b.b, 10.0f * std::max(b.r, 1e-4f)) << "--variant blue: blue";

  RunResult warned =
      runRayster(fmt::format("render {} --size 16x16 --frames 1 -o {}", file.string(), (dir / "warn.png").string()));
  EXPECT_EQ(warned.exitCode, 0) << warned.output;
  EXPECT_NE(warned.output.find("reflect only the environment (or the GI probes) in its clear coats"), std::string::npos)
      << warned.output;

  RunResult unknown = runRayster(fmt::format("render {} --size 16x16 --frames 1 --variant green -o {}", file.string(),
                                             (dir / "green.png").string()));
  EXPECT_EQ(unknown.exitCode, 3) << unknown.output;
  EXPECT_NE(unknown.output.find("'red', 'blue'"), std::string::npos) << unknown.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "green.png")) << "nothing is written for a refused variant";
}

}  // namespace
}  // namespace rayster::test::analytic
