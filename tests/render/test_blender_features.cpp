// The Blender feature corpus (assets/corpus/features, made by scripts/corpus/make_features.py with
// Debian's blender 3.4.1; docs/corpus.md): a skin, shape keys, a colour attribute and the material
// extensions as Blender's own exporter writes them. The validator finds no error; each file renders
// its golden in the hybrid; the animated ones move where the mesh moves and nowhere else and pose
// like the scene layer's CPU bake; the vertex colours show; and the loader reads every extension
// with the value the script set, which the path tracer then renders visibly.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include "scene/animation.h"
#include "scene/loader.h"
#include "scene/skinning.h"
#include "tests/render/analytic_scenes.h"
#include "tests/render/bake_gltf.h"
#include "tests/render/golden.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

namespace fs = std::filesystem;
const fs::path kDir = fs::path(RAYSTER_SOURCE_DIR) / "assets" / "corpus" / "features";
constexpr int kW = 160, kH = 120;

// The pose each golden shows (the limb and the ball are mid-way through their actions).
struct Feature {
  const char* file;
  float time;
};
const Feature kFeatures[] = {{"skinned", 1.5f}, {"shapekeys", 1.0f}, {"vertex_colors", 0.0f}, {"materials", 0.0f}};

void PrintTo(const Feature& f, std::ostream* os) { *os << f.file << " at t = " << f.time; }

fs::path featurePath(const std::string& stem) { return kDir / (stem + ".glb"); }

std::string hybridArgs(const std::string& stem, float time) {
  return featurePath(stem).string() + " --exposure 0 --frames 4 --seed 1 --primary raster --pause --time " +
         std::to_string(time);
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

// Where a world-space point lands in the image of the scene's first camera (pixel coordinates,
// top row 0).
glm::vec2 project(const scene::Camera& c, glm::vec3 world, int w, int h) {
  const glm::mat4 clipFromWorld =
      glm::perspective(c.yFov, float(w) / float(h), c.zNear, c.zFar) * glm::lookAt(c.position, c.target, c.up);
  const glm::vec4 clip = clipFromWorld * glm::vec4(world, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return {(ndc.x * 0.5f + 0.5f) * float(w), (0.5f - ndc.y * 0.5f) * float(h)};
}

const scene::Material* materialNamed(const scene::Scene& s, const std::string& name) {
  for (const scene::Material& m : s.materials)
    if (m.name == name) return &m;
  return nullptr;
}

// The world position of the instance drawn with the material `name` (one sphere per material).
glm::vec3 instanceWithMaterial(const scene::Scene& s, const std::string& name) {
  for (const scene::Instance& i : s.instances)
    for (const scene::Primitive& p : s.meshes[i.mesh].primitives)
      if (s.materials[p.material].name == name) return glm::vec3(i.worldFromObject[3]);
  ADD_FAILURE() << "no instance with material " << name;
  return glm::vec3(0.0f);
}

double luminance(glm::dvec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }
double luminance(const float* p) { return luminance(glm::dvec3(p[0], p[1], p[2])); }

// Statistics of the pixels of a linear image within r pixels of `centre`.
struct Window {
  glm::dvec3 mean{0.0};
  double maxLuminance = 0.0, minLuminance = 1e30;
};
Window window(const ImageF& image, glm::vec2 centre, int r) {
  Window out;
  int n = 0;
  for (int y = int(centre.y) - r; y <= int(centre.y) + r; ++y)
    for (int x = int(centre.x) - r; x <= int(centre.x) + r; ++x) {
      if ((x - int(centre.x)) * (x - int(centre.x)) + (y - int(centre.y)) * (y - int(centre.y)) > r * r) continue;
      const float* p = image.pixel(std::clamp(x, 0, image.width - 1), std::clamp(y, 0, image.height - 1));
      out.mean += glm::dvec3(p[0], p[1], p[2]);
      out.maxLuminance = std::max(out.maxLuminance, luminance(p));
      out.minLuminance = std::min(out.minLuminance, luminance(p));
      ++n;
    }
  out.mean /= double(n);
  return out;
}

// Pixels where any channel of a and b differs by more than `tolerance`.
size_t differingPixels(const ImageF& a, const ImageF& b, float tolerance) {
  size_t n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      bool differs = false;
      for (int c = 0; c < 3; ++c) differs |= !(std::abs(a.pixel(x, y)[c] - b.pixel(x, y)[c]) <= tolerance);
      n += differs;
    }
  return n;
}

TEST(BlenderFeatures, ValidatorFindsNoErrorAndEveryFileLoadsWithWhatItTests) {
  for (const Feature& f : kFeatures) {
    auto s = scene::loadScene(featurePath(f.file).string());
    ASSERT_TRUE(s.ok()) << f.file << ": " << s.error().message;
    EXPECT_FALSE(s->lights.empty()) << f.file;
    EXPECT_FALSE(s->cameras.empty()) << f.file;
  }
  auto skinned = scene::loadScene(featurePath("skinned").string());
  ASSERT_TRUE(skinned.ok());
  ASSERT_EQ(skinned->skins.size(), 1u);
  EXPECT_EQ(skinned->skins[0].joints.size(), 3u) << "three bones";
  EXPECT_FALSE(skinned->animations.empty());
  auto morphed = scene::loadScene(featurePath("shapekeys").string());
  ASSERT_TRUE(morphed.ok());
  size_t targets = 0;
  for (const scene::Mesh& m : morphed->meshes)
    for (const scene::Primitive& p : m.primitives) targets = std::max(targets, p.targets.size());
  EXPECT_EQ(targets, 2u) << "Squash and Bulge";
  EXPECT_FALSE(morphed->animations.empty());
  auto coloured = scene::loadScene(featurePath("vertex_colors").string());
  ASSERT_TRUE(coloured.ok());
  size_t colouredPrimitives = 0;
  for (const scene::Mesh& m : coloured->meshes)
    for (const scene::Primitive& p : m.primitives) colouredPrimitives += !p.colors.empty();
  EXPECT_EQ(colouredPrimitives, 1u) << "the panel has COLOR_0";

  const fs::path module = fs::path(RAYSTER_SOURCE_DIR) / "tools" / "npm" / "node_modules" / "gltf-validator";
  if (std::system("command -v node >/dev/null 2>&1") != 0 || !fs::exists(module))
    GTEST_SKIP() << "node or tools/npm/node_modules/gltf-validator is missing (scripts/setup.sh installs both)";
  std::string cmd = "GLTF_VALIDATOR_MODULE=" + quoted(module.string()) + " node " +
                    quoted((fs::path(RAYSTER_SOURCE_DIR) / "tools" / "gltf-validate.js").string());
  for (const Feature& f : kFeatures) cmd += " " + quoted(featurePath(f.file).string());
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
  EXPECT_EQ(reports, std::size(kFeatures));
}

// What make_features.py sets on each sphere's Principled BSDF, as Blender 3.4.1's exporter writes it
// (assets/corpus/README.md lists the JSON).
TEST(BlenderFeatures, LoaderReadsEveryMaterialExtensionWithTheValueTheScriptSet) {
  auto s = scene::loadScene(featurePath("materials").string());
  ASSERT_TRUE(s.ok()) << s.error().message;
  auto get = [&](const char* name) {
    const scene::Material* m = materialNamed(*s, name);
    EXPECT_NE(m, nullptr) << name;
    return m ? *m : scene::Material{};
  };
  const scene::Material plain = get("Plain");
  EXPECT_NEAR(plain.baseColor.r, 0.6f, 1e-6f);
  EXPECT_NEAR(plain.roughness, 0.4f, 1e-6f);
  EXPECT_FALSE(plain.layered());
  const scene::Material coat = get("Clearcoat");
  EXPECT_FLOAT_EQ(coat.clearcoat, 1.0f);
  EXPECT_NEAR(coat.clearcoatRoughness, 0.05f, 1e-6f);
  EXPECT_FALSE(coat.clearcoatTexture.valid());
  const scene::Material coatTexture = get("ClearcoatTexture");
  EXPECT_FLOAT_EQ(coatTexture.clearcoat, 1.0f);
  EXPECT_TRUE(coatTexture.clearcoatTexture.valid()) << "the stripes image drives the Clearcoat input";
  const scene::Material specular = get("Specular");
  // Blender's Specular 1 is F0 0.08, twice glTF's 0.04: the exporter writes specularColorFactor 2.
  EXPECT_NEAR(specular.specularColor.r, 2.0f, 1e-5f);
  EXPECT_FLOAT_EQ(specular.specular, 1.0f);
  const scene::Material glass = get("Glass");
  EXPECT_FLOAT_EQ(glass.transmission, 1.0f);
  EXPECT_FLOAT_EQ(glass.ior, 1.5f);
  EXPECT_FLOAT_EQ(glass.thickness, 0.0f) << "thin-walled: no KHR_materials_volume";
  EXPECT_FLOAT_EQ(glass.roughness, 0.0f);
  const scene::Material volume = get("GlassVolume");
  EXPECT_FLOAT_EQ(volume.transmission, 1.0f);
  EXPECT_NEAR(volume.ior, 1.33f, 1e-6f);
  EXPECT_NEAR(volume.thickness, 0.8f, 1e-6f);
  EXPECT_NEAR(volume.attenuationColor.g, 0.9f, 1e-6f);
  EXPECT_NEAR(volume.attenuationColor.r, 0.2f, 1e-6f);
  EXPECT_FLOAT_EQ(volume.attenuationDistance, 1.0f);
  const scene::Material glassTexture = get("GlassTexture");
  EXPECT_FLOAT_EQ(glassTexture.transmission, 1.0f);
  EXPECT_TRUE(glassTexture.transmissionTexture.valid()) << "the stripes image drives the Transmission input";
  const scene::Material emission = get("Emission");
  // emissiveFactor (1, 0.5, 0.1) × emissiveStrength 4, folded in by the loader.
  EXPECT_NEAR(emission.emissive.r, 4.0f, 1e-5f);
  EXPECT_NEAR(emission.emissive.g, 2.0f, 1e-5f);
  EXPECT_NEAR(emission.emissive.b, 0.4f, 1e-5f);
  const scene::Material sheen = get("Sheen");
  EXPECT_NEAR(sheen.sheenColor.r, 1.0f, 1e-6f);
  EXPECT_NEAR(sheen.sheenColor.g, 0.9f, 1e-6f);
  EXPECT_NEAR(sheen.sheenColor.b, 0.2f, 1e-6f);
  EXPECT_NEAR(sheen.sheenRoughness, 0.5f, 1e-6f);
}

class BlenderFeatureGolden : public ::testing::TestWithParam<Feature> {};

TEST_P(BlenderFeatureGolden, HybridMatchesGolden) {
  const Feature f = GetParam();
  const fs::path dir = testDir();
  const Image8 image = renderOk(dir, f.file, hybridArgs(f.file, f.time), kW, kH);
  ASSERT_FALSE(image.empty());
  expectMatchesGolden(image, std::string("blender-") + f.file + "-160x120", dir);
}

INSTANTIATE_TEST_SUITE_P(BlenderFeatures, BlenderFeatureGolden, ::testing::ValuesIn(kFeatures),
                         [](const auto& info) { return std::string(info.param.file); });

// Two times of the same action, paused: the image changes where the limb (ball) moves and its
// shadow falls, and stays the same elsewhere; and the deformed G-buffer is the scene layer's CPU
// pose (scene::bakePose) written as a static glTF.
TEST(BlenderFeatures, AnimationMovesOnlyTheDeformingMeshAndPosesLikeTheSceneLayer) {
  const fs::path dir = testDir();
  for (const char* stem : {"skinned", "shapekeys"}) {
    SCOPED_TRACE(stem);
    const fs::path file = featurePath(stem);
    auto loaded = scene::loadScene(file.string());
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    const std::string common =
        " --mode raster --taa off --frames 1 --pause --size " + std::to_string(kW) + "x" + std::to_string(kH);
    const std::vector<std::string> aovs = {"depth", "normal", "albedo"};
    const fs::path a = dir / stem / "t0", b = dir / stem / "t1", c = dir / stem / "baked";
    for (const fs::path& d : {a, b, c}) fs::create_directories(d);
    const float t1 = 1.9f;
    auto rest = renderAovs(a, file.string() + common + " --time 0 --hdr " + (a / "hdr.exr").string(), aovs);
    auto posed = renderAovs(b, file.string() + common + " --time 1.9 --hdr " + (b / "hdr.exr").string(), aovs);
    ASSERT_EQ(rest.size(), aovs.size());
    ASSERT_EQ(posed.size(), aovs.size());
    auto restHdr = readExr(a / "hdr.exr"), posedHdr = readExr(b / "hdr.exr");
    ASSERT_TRUE(restHdr.ok() && posedHdr.ok());
    for (const ImageF* i : {&*restHdr, &*posedHdr}) {
      auto empty = rejectEmpty(*i, kW, kH);
      EXPECT_FALSE(empty.has_value()) << empty.value_or("");
    }
    // Where the mesh moves: the depth changes on a good part of the frame.
    const size_t movedGeometry = differingPixels(rest["depth"], posed["depth"], 1e-3f);
    EXPECT_GT(movedGeometry, size_t(kW * kH / 50)) << "the pose at t = 1.9 should differ from t = 0";
    // Where nothing moves: every pixel whose depth is unchanged and that is not in the moving
    // mesh's shadow keeps its colour. Raster mode's shadow map moves with the mesh, so the test
    // counts only pixels outside both poses' shadowed regions: unchanged depth, same albedo, and a
    // change of light under 1 %.
    size_t still = 0, stillChanged = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        if (std::abs(rest["depth"].pixel(x, y)[0] - posed["depth"].pixel(x, y)[0]) > 1e-5f) continue;
        ++still;
        const float *p = restHdr->pixel(x, y), *q = posedHdr->pixel(x, y);
        const double lp = luminance(p), lq = luminance(q);
        if (std::abs(lp - lq) > 0.5 * std::max(lp, lq)) continue;  // the shadow moved over it
        stillChanged += std::abs(lp - lq) > 0.01 * std::max(lp, lq) + 1e-6;
      }
    EXPECT_GT(still, size_t(kW * kH / 2)) << "most of the frame (floor, sky) does not move";
    EXPECT_LE(stillChanged, still / 100) << "pixels whose geometry did not move changed colour";

    scene::Scene pose = *loaded;
    scene::evaluateAnimations(pose, t1);
    const fs::path baked = writeBakedGltf(scene::bakePose(pose), loaded->cameras.front(), c / "baked.gltf");
    auto reference = renderAovs(c, baked.string() + common, aovs);
    ASSERT_EQ(reference.size(), aovs.size());
    for (const std::string& aov : aovs) {
      const size_t differ = differingPixels(posed[aov], reference[aov], 2e-3f);
      EXPECT_LE(differ, size_t(kW * kH / 200)) << aov << ": " << differ << " pixels differ from the static copy";
    }
    std::printf("%s: %zu pixels moved, %zu still, %zu of them changed colour\n", stem, movedGeometry, still,
                stillChanged);
  }
}

// The panel's 4 x 4 cells show the colour attribute's palette (red, green, blue, yellow, and a
// white corner cell), not the material's white.
TEST(BlenderFeatures, VertexColoursShowOnThePanel) {
  const fs::path dir = testDir();
  auto s = scene::loadScene(featurePath("vertex_colors").string());
  ASSERT_TRUE(s.ok()) << s.error().message;
  analytic::Rendered r = analytic::renderHdr(dir, "vertex_colors", featurePath("vertex_colors"), kW, kH, 4, "",
                                             "--exposure 0 --seed 1 --mode hybrid");
  ASSERT_FALSE(r.hdr.empty());
  // Cell (row, col) spans x in [-1 + col/2, -0.5 + col/2], height [0.2 + row/2, 0.7 + row/2] (glTF
  // y up) at z = 0; colours as in make_features.py: palette[(row + col) % 4], (0, 0) white.
  const glm::vec3 palette[4] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}};
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) {
      SCOPED_TRACE("cell row " + std::to_string(row) + " col " + std::to_string(col));
      const glm::vec2 px =
          project(s->cameras.front(), glm::vec3(-0.75f + 0.5f * col, 0.45f + 0.5f * row, 0.0f), kW, kH);
      const glm::dvec3 c = window(r.hdr, px, 2).mean;
      const double peak = std::max({c.r, c.g, c.b});
      ASSERT_GT(peak, 0.02) << "the cell should be lit";
      const glm::vec3 want = (row == 0 && col == 0) ? glm::vec3(1.0f) : palette[(row + col) % 4];
      for (int k = 0; k < 3; ++k) {
        if (want[k] > 0.5f)
          EXPECT_GT(c[k], 0.6 * peak) << "channel " << k << " should be lit";
        else
          EXPECT_LT(c[k], 0.15 * peak) << "channel " << k << " should be dark";
      }
    }
}

// The path tracer on the nine spheres: each is lit and differs from the others; the coat adds a
// reflection the plain sphere lacks (half of it where the coat texture is black); the glass shows the checker floor
// through it; the volume tints it green; the emitter shows its radiance, factor × strength.
TEST(BlenderFeatures, PathTracerRendersEverySphereWithItsMaterial) {
  const fs::path dir = testDir();
  auto s = scene::loadScene(featurePath("materials").string());
  ASSERT_TRUE(s.ok()) << s.error().message;
  analytic::Rendered r = analytic::renderHdr(dir, "materials-pt", featurePath("materials"), kW, kH, 1, "",
                                             "--mode pathtrace --spp 16 --exposure 0 --seed 1");
  ASSERT_FALSE(r.hdr.empty());
  const char* const names[] = {"Plain",       "Clearcoat",    "ClearcoatTexture", "Specular", "Glass",
                               "GlassVolume", "GlassTexture", "Emission",         "Sheen"};
  std::map<std::string, Window> w, whole;
  for (const char* name : names) {
    const glm::vec2 px = project(s->cameras.front(), instanceWithMaterial(*s, name), kW, kH);
    w[name] = window(r.hdr, px, 5);       // the middle of the sphere: they are about 22 pixels across
    whole[name] = window(r.hdr, px, 10);  // all of it, with its highlight
    std::printf("%-17s at (%5.1f, %5.1f): mean (%.3f %.3f %.3f), luminance %.3f .. %.3f\n", name, px.x, px.y,
                w[name].mean.r, w[name].mean.g, w[name].mean.b, w[name].minLuminance, w[name].maxLuminance);
    EXPECT_GT(w[name].maxLuminance, 0.01) << name << " is black";
  }
  for (const char* a : names)
    for (const char* b : names) {
      if (std::string(a) >= b) continue;
      const glm::dvec3 d = w[a].mean - w[b].mean;
      const double scale = std::max(luminance(w[a].mean), luminance(w[b].mean));
      EXPECT_GT(glm::length(d), 0.03 * scale) << a << " and " << b << " look the same";
    }
  // The key light's reflection is a fraction of a pixel here (a 0.1 m sphere light 5 m away in a
  // 0.4 m ball), so what the coat adds that one sees is its reflection of the lit floor over the
  // whole ball: brighter than the same red without a coat, and the striped coat in between.
  const double plain = luminance(whole["Plain"].mean), coated = luminance(whole["Clearcoat"].mean),
               striped = luminance(whole["ClearcoatTexture"].mean);
  EXPECT_GT(coated, 1.15 * plain) << "the coat reflects the floor on top of the red base";
  EXPECT_GT(striped, plain * 1.04) << "half of the striped coat";
  EXPECT_LT(striped, coated / 1.04) << "half of the striped coat";
  EXPECT_GT(w["Glass"].maxLuminance, 3.0 * w["Glass"].minLuminance) << "the checker floor seen through the glass";
  EXPECT_GT(w["GlassVolume"].mean.g, 1.3 * w["GlassVolume"].mean.r) << "green attenuation";
  EXPECT_NEAR(w["Emission"].mean.r, 4.0, 0.6) << "emissiveFactor 1 × strength 4";
  EXPECT_NEAR(w["Emission"].mean.g / w["Emission"].mean.r, 0.5, 0.08);
}

}  // namespace
}  // namespace rayster::test
