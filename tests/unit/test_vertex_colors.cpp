// Vertex colours: glTF COLOR_0 in every encoding the spec allows (float, normalized unsigned byte
// and short; VEC3 and VEC4) and OBJ's `v x y z r g b`, read into Primitive::colors (linear RGBA).
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "gltf_test_util.h"
#include "scene/obj_loader.h"

using namespace rayster;
using namespace rayster::test;

namespace {

void expectColor(glm::vec4 got, glm::vec4 want, float eps = 1e-6f) {
  EXPECT_NEAR(got.r, want.r, eps);
  EXPECT_NEAR(got.g, want.g, eps);
  EXPECT_NEAR(got.b, want.b, eps);
  EXPECT_NEAR(got.a, want.a, eps);
}

// The test quad with COLOR_0 from `accessor`.
scene::Scene loadWithColors(const TempDir& dir, Doc& d, int accessor) {
  primitive(d)["attributes"]["COLOR_0"] = accessor;
  Result<scene::Scene> s = loadBytes(dir, d.gltf());
  EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.error().message);
  return s.ok() ? std::move(s).value() : scene::Scene{};
}

const std::vector<glm::vec4>& colorsOf(const scene::Scene& s) {
  static const std::vector<glm::vec4> none;
  return s.meshes.empty() || s.meshes[0].primitives.empty() ? none : s.meshes[0].primitives[0].colors;
}

TEST(GltfVertexColors, FloatVec3IsOpaque) {
  TempDir dir;
  Doc d = quadDoc();
  const int c = d.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0.25f, 0.5f, 0.75f}, "VEC3", 3);
  scene::Scene s = loadWithColors(dir, d, c);
  const auto& colors = colorsOf(s);
  ASSERT_EQ(colors.size(), 4u);
  expectColor(colors[0], {1, 0, 0, 1});
  expectColor(colors[2], {0, 0, 1, 1});
  expectColor(colors[3], {0.25f, 0.5f, 0.75f, 1});
}

TEST(GltfVertexColors, FloatVec4KeepsAlpha) {
  TempDir dir;
  Doc d = quadDoc();
  const int c = d.floats({1, 0, 0, 1, 0, 1, 0, 0.5f, 0, 0, 1, 0, 1, 1, 1, 0.25f}, "VEC4", 4);
  scene::Scene s = loadWithColors(dir, d, c);
  const auto& colors = colorsOf(s);
  ASSERT_EQ(colors.size(), 4u);
  expectColor(colors[1], {0, 1, 0, 0.5f});
  expectColor(colors[2], {0, 0, 1, 0});
  expectColor(colors[3], {1, 1, 1, 0.25f});
}

TEST(GltfVertexColors, NormalizedUnsignedByteVec4) {
  TempDir dir;
  Doc d = quadDoc();
  const std::vector<uint8_t> bytes = {255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 0, 51, 102, 204, 255};
  const int c = d.accessor(d.view(bytes), kUByte, 4, "VEC4", /*normalized=*/true);
  scene::Scene s = loadWithColors(dir, d, c);
  const auto& colors = colorsOf(s);
  ASSERT_EQ(colors.size(), 4u);
  expectColor(colors[0], {1, 0, 0, 1});
  expectColor(colors[1], {0, 1, 0, 128 / 255.0f});
  expectColor(colors[3], {0.2f, 0.4f, 0.8f, 1});
}

TEST(GltfVertexColors, NormalizedUnsignedByteVec3WithStride) {
  TempDir dir;
  Doc d = quadDoc();
  // RGB bytes padded to 4-byte elements, as glTF requires for vertex attributes.
  const std::vector<uint8_t> bytes = {255, 0, 0, 9, 0, 255, 0, 9, 0, 0, 255, 9, 255, 255, 255, 9};
  const int c = d.accessor(d.view(bytes, 4), kUByte, 4, "VEC3", /*normalized=*/true);
  scene::Scene s = loadWithColors(dir, d, c);
  const auto& colors = colorsOf(s);
  ASSERT_EQ(colors.size(), 4u);
  expectColor(colors[1], {0, 1, 0, 1});
  expectColor(colors[3], {1, 1, 1, 1});
}

TEST(GltfVertexColors, NormalizedUnsignedShortVec3AndVec4) {
  TempDir dir;
  Doc d = quadDoc();
  const std::vector<uint16_t> rgb = {65535, 0, 0, 0, 65535, 0, 0, 0, 65535, 13107, 26214, 52428};
  const int c = d.accessor(d.view(rgb), kUShort, 4, "VEC3", /*normalized=*/true);
  scene::Scene s = loadWithColors(dir, d, c);
  const auto& colors = colorsOf(s);
  ASSERT_EQ(colors.size(), 4u);
  expectColor(colors[0], {1, 0, 0, 1});
  expectColor(colors[3], {0.2f, 0.4f, 0.8f, 1});

  Doc d4 = quadDoc();
  const std::vector<uint16_t> rgba = {0, 0, 0, 65535, 65535, 65535, 65535, 32768, 0, 0, 0, 0, 1, 2, 3, 4};
  const int c4 = d4.accessor(d4.view(rgba), kUShort, 4, "VEC4", /*normalized=*/true);
  scene::Scene s4 = loadWithColors(dir, d4, c4);
  const auto& colors4 = colorsOf(s4);
  ASSERT_EQ(colors4.size(), 4u);
  expectColor(colors4[1], {1, 1, 1, 32768 / 65535.0f});
  expectColor(colors4[2], {0, 0, 0, 0});
}

TEST(GltfVertexColors, AbsentMeansNoColors) {
  TempDir dir;
  Doc d = quadDoc();
  Result<scene::Scene> s = loadBytes(dir, d.gltf());
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_TRUE(colorsOf(*s).empty()) << "white is the renderer's default, not stored";
}

TEST(GltfVertexColors, FlatNormalsExpandColorsWithPositions) {
  TempDir dir;
  Doc d = quadDoc();
  primitive(d)["attributes"].erase("NORMAL");  // flat normals un-index the primitive
  const int c = d.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1}, "VEC3", 3);
  scene::Scene s = loadWithColors(dir, d, c);
  const scene::Primitive& p = s.meshes.at(0).primitives.at(0);
  ASSERT_EQ(p.positions.size(), 6u);
  ASSERT_EQ(p.colors.size(), 6u);
  // Indices 0 1 2 0 2 3 become vertices v0 v1 v2 v0 v2 v3.
  expectColor(p.colors[2], {0, 0, 1, 1});
  expectColor(p.colors[4], {0, 0, 1, 1});
  expectColor(p.colors[5], {1, 1, 1, 1});
}

// Not what the spec allows for COLOR_0: dropped with a warning, the primitive still renders (white).
TEST(GltfVertexColors, UnnormalizedIntegersAreIgnored) {
  TempDir dir;
  Doc d = quadDoc();
  const std::vector<uint8_t> bytes(16, 1);
  const int c = d.accessor(d.view(bytes), kUByte, 4, "VEC4", /*normalized=*/false);
  scene::Scene s = loadWithColors(dir, d, c);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_TRUE(colorsOf(s).empty());
}

TEST(GltfVertexColors, CountMismatchIsRefused) {
  TempDir dir;
  Doc d = quadDoc();
  primitive(d)["attributes"]["COLOR_0"] = d.floats({1, 0, 0, 0, 1, 0}, "VEC3", 3);
  Result<scene::Scene> s = loadBytes(dir, d.gltf());
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("COLOR_0"), std::string::npos) << s.error().message;
}

TEST(ObjVertexColors, ColorsAfterPositionsAreRead) {
  TempDir dir;
  auto path = dir.write("colored.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\nv 0 1 0 1 1 1\nf 1 2 3 4\n");
  Result<scene::Scene> s = scene::loadObj(path);
  ASSERT_TRUE(s.ok()) << s.error().message;
  const scene::Primitive& p = s->meshes.at(0).primitives.at(0);
  ASSERT_EQ(p.colors.size(), p.positions.size());
  for (size_t i = 0; i < p.positions.size(); ++i) {
    // Vertex k sits at a known corner: pick its colour by position.
    const glm::vec3 q = p.positions[i];
    const glm::vec4 want = q == glm::vec3(0, 0, 0)   ? glm::vec4(1, 0, 0, 1)
                           : q == glm::vec3(1, 0, 0) ? glm::vec4(0, 1, 0, 1)
                           : q == glm::vec3(1, 1, 0) ? glm::vec4(0, 0, 1, 1)
                                                     : glm::vec4(1, 1, 1, 1);
    expectColor(p.colors[i], want);
  }
}

TEST(ObjVertexColors, PlainPositionsHaveNone) {
  TempDir dir;
  auto path = dir.write("plain.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
  Result<scene::Scene> s = scene::loadObj(path);
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_TRUE(s->meshes.at(0).primitives.at(0).colors.empty());
}

}  // namespace
