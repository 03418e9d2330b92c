// glTF content the loader skips with a warning instead of refusing the file: images no material
// uses (missing or undecodable), primitives without POSITION (valid glTF: "skipped"), and meshes
// left with nothing to draw. What a material does use is still required.
#include <gtest/gtest.h>

#include "core/image_io.h"
#include "gltf_test_util.h"
#include "scene/loader.h"

using namespace rayster;
using namespace rayster::test;

namespace {

struct Loaded {
  Result<scene::Scene> scene;
  std::string stderrText;
};

// Loads with stderr captured, so the warnings can be checked.
Loaded loadCapturing(const TempDir& dir, const std::string& bytes) {
  ::testing::internal::CaptureStderr();
  Result<scene::Scene> scene = loadBytes(dir, bytes);
  return {std::move(scene), ::testing::internal::GetCapturedStderr()};
}

bool hasLine(const std::string& text, const std::string& start, const std::string& part) {
  size_t at = 0;
  while (at < text.size()) {
    size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(at, end - at);
    if (line.rfind(start, 0) == 0 && line.find(part) != std::string::npos) return true;
    at = end + 1;
  }
  return false;
}

// A PNG that stb_image cannot decode: a header claiming 16x16 and no pixel data.
std::string undecodablePngUri() {
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A, 0,   0,   0,   13,   'I',  'H',  'D',
                              'R',  0,   0,   0,   16,   0,    0,    0,    16,  8,   6,   0,    0,    0,    0,
                              0,    0,   0,   0,   0,    0,    0,    'I',  'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
  return "data:image/png;base64," + base64(png);
}

// Material 0 uses texture 0 as its base colour; texture 0 shows image `image`.
void texturedMaterial(Doc& d, int image) {
  d.j["textures"] = Json::array({{{"source", image}}});
  d.j["materials"] =
      Json::array({{{"name", "painted"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  primitive(d)["material"] = 0;
}

TEST(GltfSkip, MissingImageNoMaterialUsesWarnsAndLoads) {
  TempDir dir;
  Doc d = quadDoc();
  d.j["images"] = Json::array({{{"uri", "nowhere.png"}}});
  Loaded l = loadCapturing(dir, d.gltf());
  ASSERT_TRUE(l.scene.ok()) << l.scene.error().message;
  EXPECT_EQ(l.scene->instances.size(), 1u);
  EXPECT_TRUE(hasLine(l.stderrText, "rayster: warning: ", "nowhere.png")) << l.stderrText;
}

TEST(GltfSkip, UndecodableImageNoMaterialUsesLoads) {
  TempDir dir;
  Doc d = quadDoc();
  d.j["images"] = Json::array({{{"uri", undecodablePngUri()}}});
  d.j["textures"] = Json::array({{{"source", 0}}});  // a texture, but no material shows it
  Loaded l = loadCapturing(dir, d.gltf());
  ASSERT_TRUE(l.scene.ok()) << l.scene.error().message;
  EXPECT_EQ(l.scene->instances.size(), 1u);
}

TEST(GltfSkip, MissingImageAMaterialUsesIsRefused) {
  TempDir dir;
  Doc d = quadDoc();
  d.j["images"] = Json::array({{{"uri", "nowhere.png"}}});
  texturedMaterial(d, 0);
  Result<scene::Scene> s = loadBytes(dir, d.gltf());
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ExitCode::BadInput);
  EXPECT_NE(s.error().message.find("nowhere.png"), std::string::npos) << s.error().message;
  EXPECT_NE(s.error().message.find("painted"), std::string::npos) << s.error().message;
  EXPECT_EQ(s.error().message.find('\n'), std::string::npos) << s.error().message;
}

TEST(GltfSkip, UsedImageBesideASkippedOneIsTheOneTextured) {
  TempDir dir;
  Image8 red = Image8::make(3, 2);
  for (size_t i = 0; i < red.rgba.size(); i += 4) red.rgba[i] = 255, red.rgba[i + 3] = 255;
  ASSERT_TRUE(writePng(dir.path() / "red.png", red).ok());
  Doc d = quadDoc();
  d.j["images"] = Json::array({{{"uri", "nowhere.png"}}, {{"uri", "red.png"}}});
  texturedMaterial(d, 1);
  Loaded l = loadCapturing(dir, d.gltf());
  ASSERT_TRUE(l.scene.ok()) << l.scene.error().message;
  const scene::Scene& s = *l.scene;
  ASSERT_EQ(s.materials.size(), 1u);
  const scene::TextureRef& ref = s.materials[0].baseColorTexture;
  ASSERT_TRUE(ref.valid());
  const scene::ImageData& img = s.images.at(s.textures.at(size_t(ref.texture)).image);
  EXPECT_EQ(img.width, 3);
  EXPECT_EQ(img.height, 2);
  EXPECT_EQ(img.rgba[0], 255);
  EXPECT_TRUE(hasLine(l.stderrText, "rayster: warning: ", "nowhere.png")) << l.stderrText;
}

TEST(GltfSkip, PrimitiveWithoutPositionIsSkipped) {
  TempDir dir;
  Doc d = quadDoc();
  Json second = primitive(d);
  second["attributes"].erase("POSITION");
  d.j["meshes"][0]["primitives"].push_back(second);
  Loaded l = loadCapturing(dir, d.gltf());
  ASSERT_TRUE(l.scene.ok()) << l.scene.error().message;
  ASSERT_EQ(l.scene->meshes.size(), 1u);
  EXPECT_EQ(l.scene->meshes[0].primitives.size(), 1u);
  EXPECT_EQ(l.scene->instances.size(), 1u);
  EXPECT_TRUE(hasLine(l.stderrText, "rayster: warning: ", "primitive 1 has no POSITION")) << l.stderrText;
}

TEST(GltfSkip, MeshWithEveryPrimitiveSkippedDrawsNothing) {
  TempDir dir;
  Doc d = quadDoc();
  Json headless = primitive(d);
  headless["attributes"].erase("POSITION");
  d.j["meshes"].push_back({{"name", "ghost"}, {"primitives", Json::array({headless})}});
  d.j["nodes"].push_back({{"name", "ghost-node"}, {"mesh", 1}});
  d.j["nodes"][0]["children"] = {1};  // under the quad: the hierarchy still holds it
  Loaded l = loadCapturing(dir, d.gltf());
  ASSERT_TRUE(l.scene.ok()) << l.scene.error().message;
  const scene::Scene& s = *l.scene;
  ASSERT_EQ(s.instances.size(), 1u);
  EXPECT_EQ(s.instances[0].name, "quad");
  for (const scene::Mesh& m : s.meshes) EXPECT_FALSE(m.primitives.empty()) << m.name << " is kept empty";
  EXPECT_EQ(s.nodes.size(), 2u);
  EXPECT_TRUE(hasLine(l.stderrText, "rayster: warning: ", "ghost")) << l.stderrText;
}

TEST(GltfSkip, NothingLeftToRenderIsRefused) {
  TempDir dir;
  Doc d = quadDoc();
  primitive(d)["attributes"].erase("POSITION");
  const auto path = dir.write("empty.gltf", d.gltf());
  ::testing::internal::CaptureStderr();
  Result<scene::Scene> s = scene::loadScene(path.string());
  const std::string warnings = ::testing::internal::GetCapturedStderr();
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ExitCode::BadInput);
  EXPECT_NE(s.error().message.find("nothing to render"), std::string::npos) << s.error().message;
  EXPECT_EQ(s.error().message.find('\n'), std::string::npos) << s.error().message;
  EXPECT_TRUE(hasLine(warnings, "rayster: warning: ", "POSITION")) << warnings;
}

}  // namespace
