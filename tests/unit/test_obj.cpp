// The OBJ/MTL loader: geometry, materials, textures and what it must refuse.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/image_io.h"
#include "scene/loader.h"
#include "scene/obj_loader.h"
#include "tests/support/test_dirs.h"

using namespace rayster;
using namespace rayster::scene;
namespace fs = std::filesystem;

namespace {

// Loaders leave the camera to applyDefaults, and validate() wants one.
bool validWithDefaults(Scene scene) {
  applyDefaults(scene);
  Status status = validate(scene);
  if (!status.ok()) ADD_FAILURE() << status.error().message;
  return status.ok();
}

// A fresh folder per test, removed when it passes, so fixtures never leak between tests or runs.
class ObjTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = rayster::test::testDir();  // removed when the test passes (tests/support/test_dirs.h)
  }

  fs::path write(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  // Loads text as an OBJ and expects BadInput with `needle` in the message.
  void expectRejected(const std::string& text, const std::string& needle) {
    Result<Scene> scene = loadObj(write("bad.obj", text));
    ASSERT_FALSE(scene.ok()) << "accepted:\n" << text;
    EXPECT_EQ(scene.error().code, ExitCode::BadInput);
    EXPECT_NE(scene.error().message.find(needle), std::string::npos) << scene.error().message;
  }

  fs::path dir_;
};

constexpr const char* kQuad = R"(# unit quad facing +Z
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
f 1/1/1 2/2/1 3/3/1 4/4/1
)";

}  // namespace

TEST_F(ObjTest, QuadWithTexcoordsAndNormals) {
  Result<Scene> loaded = loadObj(write("quad.obj", kQuad));
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const Scene& scene = *loaded;
  EXPECT_EQ(scene.name, "quad");
  ASSERT_EQ(scene.meshes.size(), 1u);
  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_EQ(scene.instances[0].worldFromObject, glm::mat4(1.0f));
  ASSERT_EQ(scene.meshes[0].primitives.size(), 1u);
  const Primitive& prim = scene.meshes[0].primitives[0];
  EXPECT_EQ(prim.indices.size(), 6u);  // the quad became two triangles
  EXPECT_EQ(prim.positions.size(), 4u);
  ASSERT_EQ(prim.uvs.size(), 4u);
  for (size_t i = 0; i < prim.positions.size(); ++i) {
    EXPECT_EQ(prim.normals[i], glm::vec3(0, 0, 1));
    // vt (u, v) with v up becomes (u, 1 - v): the corner at y = 0 has uv.y = 1.
    EXPECT_FLOAT_EQ(prim.uvs[i].x, prim.positions[i].x);
    EXPECT_FLOAT_EQ(prim.uvs[i].y, 1.0f - prim.positions[i].y);
  }
  ASSERT_EQ(scene.materials.size(), 1u);  // no mtllib: one default material
  EXPECT_EQ(prim.material, 0u);
  EXPECT_TRUE(validWithDefaults(scene));
}

TEST_F(ObjTest, GeneratesSmoothNormalsAndTriangulatesPolygons) {
  // A pentagon in the xz plane, counter-clockwise seen from +Y, without vn lines.
  Result<Scene> scene = loadObj(write("penta.obj",
                                      "v 0 0 0\nv 1 0 0\nv 1.5 0 -1\nv 0.5 0 -2\nv -0.5 0 -1\n"
                                      "f 1 2 3 4 5\n"));
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  const Primitive& prim = scene->meshes.at(0).primitives.at(0);
  EXPECT_EQ(prim.indices.size(), 9u);
  EXPECT_TRUE(prim.uvs.empty());
  for (const glm::vec3& n : prim.normals) EXPECT_NEAR(glm::distance(n, glm::vec3(0, 1, 0)), 0.0f, 1e-5f);
}

TEST_F(ObjTest, ObjectsAndMaterialsBecomeMeshesAndPrimitives) {
  write("mats.mtl", R"(newmtl red
Kd 0.8 0.1 0.1
Ns 98
Ke 0 0 0
newmtl ghost
Kd 0.2 0.2 0.2
d 0.5
Ke 1 2 3
newmtl mirror
illum 3
Kd 0.5 0.5 0.5
Ks 0.9 0.9 0.8
newmtl glass
illum 7
Kd 0 0 0
Tf 0.9 1 0.95
Ni 1.33
)");
  const std::string obj = std::string("mtllib mats.mtl\n") + "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n" +
                          "o first\nusemtl red\nf 1 2 3\nusemtl ghost\nf 1 3 4\nusemtl red\nf 2 3 4\n" +
                          "o second\nusemtl mirror\nf 1 2 3 4\nusemtl glass\nf 4 3 2\n";
  Result<Scene> loaded = loadObj(write("two.obj", obj));
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const Scene& scene = *loaded;
  ASSERT_EQ(scene.meshes.size(), 2u);
  ASSERT_EQ(scene.instances.size(), 2u);
  EXPECT_EQ(scene.meshes[0].name, "first");
  EXPECT_EQ(scene.instances[1].name, "second");
  ASSERT_EQ(scene.meshes[0].primitives.size(), 2u);  // red (two faces) and ghost
  EXPECT_EQ(scene.meshes[0].primitives[0].indices.size(), 6u);
  ASSERT_EQ(scene.meshes[1].primitives.size(), 2u);
  ASSERT_EQ(scene.materials.size(), 4u);

  const Material& red = scene.materials[scene.meshes[0].primitives[0].material];
  EXPECT_EQ(red.name, "red");
  EXPECT_EQ(red.baseColor, glm::vec4(0.8f, 0.1f, 0.1f, 1.0f));
  EXPECT_NEAR(red.roughness, std::sqrt(2.0f / 100.0f), 1e-6f);
  EXPECT_EQ(red.alphaMode, AlphaMode::Opaque);

  const Material& ghost = scene.materials[scene.meshes[0].primitives[1].material];
  EXPECT_FLOAT_EQ(ghost.baseColor.a, 0.5f);
  EXPECT_EQ(ghost.alphaMode, AlphaMode::Blend);
  EXPECT_EQ(ghost.emissive, glm::vec3(1, 2, 3));

  const Material& mirror = scene.materials[scene.meshes[1].primitives[0].material];
  EXPECT_EQ(mirror.metallic, 1.0f);
  EXPECT_EQ(mirror.roughness, 0.0f);
  EXPECT_EQ(glm::vec3(mirror.baseColor), glm::vec3(0.9f, 0.9f, 0.8f));  // Ks, not Kd

  const Material& glass = scene.materials[scene.meshes[1].primitives[1].material];
  EXPECT_EQ(glass.transmission, 1.0f);
  EXPECT_FLOAT_EQ(glass.ior, 1.33f);
  EXPECT_EQ(glass.roughness, 0.0f);
  EXPECT_EQ(glass.metallic, 0.0f);
  EXPECT_EQ(glm::vec3(glass.baseColor), glm::vec3(0.9f, 1.0f, 0.95f));  // Tf
  EXPECT_TRUE(validWithDefaults(scene));
}

TEST_F(ObjTest, GlassWithoutNiDefaultsToIor15) {
  write("g.mtl", "newmtl g\nillum 4\nKd 1 1 1\n");
  Result<Scene> scene = loadObj(write("g.obj", "mtllib g.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl g\nf 1 2 3\n"));
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_FLOAT_EQ(scene->materials.at(0).ior, 1.5f);
}

TEST_F(ObjTest, DiffuseTextureLoads) {
  Image8 image = Image8::make(2, 3);
  for (size_t i = 0; i < image.rgba.size(); ++i) image.rgba[i] = static_cast<uint8_t>(i * 10);
  ASSERT_TRUE(writePng(dir_ / "textures" / "tex.png", image).ok());
  write("tex.mtl", "newmtl t\nKd 1 1 1\nmap_Kd textures\\tex.png\n");  // Windows separators work
  Result<Scene> loaded = loadObj(write("tex.obj", std::string("mtllib tex.mtl\nusemtl t\n") + kQuad));
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const Scene& scene = *loaded;
  const Material& material = scene.materials.at(0);
  ASSERT_TRUE(material.baseColorTexture.valid());
  const Texture& texture = scene.textures.at(material.baseColorTexture.texture);
  ASSERT_LT(texture.sampler, scene.samplers.size());
  const ImageData& decoded = scene.images.at(texture.image);
  EXPECT_EQ(decoded.width, 2);
  EXPECT_EQ(decoded.height, 3);
  EXPECT_EQ(decoded.rgba, image.rgba);
  EXPECT_TRUE(validWithDefaults(scene));
}

TEST_F(ObjTest, MissingMtlAndTextureAreWarningsOnly) {
  Result<Scene> noMtl = loadObj(write("a.obj", std::string("mtllib nowhere.mtl\nusemtl x\n") + kQuad));
  ASSERT_TRUE(noMtl.ok()) << noMtl.error().message;
  ASSERT_EQ(noMtl->materials.size(), 1u);
  EXPECT_EQ(noMtl->materials[0].name, "default");

  write("b.mtl", "newmtl b\nKd 1 0 0\nmap_Kd missing.png\n");
  Result<Scene> noTexture = loadObj(write("b.obj", std::string("mtllib b.mtl\nusemtl b\n") + kQuad));
  ASSERT_TRUE(noTexture.ok()) << noTexture.error().message;
  EXPECT_FALSE(noTexture->materials.at(0).baseColorTexture.valid());
  EXPECT_TRUE(noTexture->images.empty());
}

TEST_F(ObjTest, RelativeIndicesWork) {
  Result<Scene> scene = loadObj(write("rel.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"));
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_EQ(scene->triangleCount(), 1u);
}

TEST_F(ObjTest, RejectsFaceIndexZeroNamingTheLine) {
  expectRejected("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "bad.obj:4: face vertex index 0");
}

TEST_F(ObjTest, RejectsIndexPastTheVertexCount) {
  expectRejected("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "bad.obj:4: face vertex index 4 is past the 3");
  expectRejected("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3 9\n", ":5:");  // a quad, which tinyobjloader skips
  expectRejected("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", "texcoord index 2");
  expectRejected("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n", "normal index 1");
}

TEST_F(ObjTest, RejectsNonFiniteCoordinatesNamingTheLine) {
  expectRejected("v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n", "bad.obj:3: v coordinate 'nan' is not a finite number");
  expectRejected("v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n", "bad.obj:3: v coordinate 'inf'");
  expectRejected("v 0 0 0\nv 1 0 0\nv 0 1 1e39\nf 1 2 3\n", "bad.obj:3: v coordinate '1e39'");  // a float overflow
  expectRejected("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 nan\nf 1//1 2//1 3//1\n", "bad.obj:4: vn coordinate 'nan'");
  expectRejected("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt -inf 0\nf 1/1 2/1 3/1\n", "bad.obj:4: vt coordinate '-inf'");
}

TEST_F(ObjTest, RejectsAFaceOfThousandsOfCornersAndTriangulatesALargeOne) {
  // Ear clipping is quadratic in a face's corners: a 100 000-corner face took 20 s to load.
  auto polygon = [](size_t n) {
    std::string text;
    for (size_t i = 0; i < n; ++i) {
      const double a = 6.283185307179586 * double(i) / double(n);
      text += fmt::format("v {} {} 0\n", std::cos(a), std::sin(a));
    }
    text += "f";
    for (size_t i = 1; i <= n; ++i) text += fmt::format(" {}", i);
    return text + "\n";
  };
  expectRejected(polygon(100000), "bad.obj:100001: a face of more than 1024 vertices");
  Result<Scene> scene = loadObj(write("disc.obj", polygon(1024)));
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_EQ(scene->triangleCount(), 1022u);
}

TEST_F(ObjTest, RejectsNegativeIndexBeforeTheStart) {
  expectRejected("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\nv 1 1 1\n", "bad.obj:4: relative face vertex index -4");
}

TEST_F(ObjTest, RejectsGarbageAndHugeIndices) {
  expectRejected("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", "not a number");
  expectRejected("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999\n", "out of range");
}

TEST_F(ObjTest, RejectsTexturePathLeavingTheFolder) {
  write("up.mtl", "newmtl up\nmap_Kd ../tex.png\n");
  expectRejected(std::string("mtllib up.mtl\nusemtl up\n") + kQuad, "'..' is not allowed");
}

TEST_F(ObjTest, RejectsAbsoluteMtllib) {
  const fs::path mtl = write("abs.mtl", "newmtl a\nKd 1 1 1\n");
  expectRejected("mtllib " + mtl.string() + "\n" + kQuad, "absolute path");
}

TEST_F(ObjTest, RejectsUriTexturePath) {
  write("uri.mtl", "newmtl u\nmap_Kd http://example.com/tex.png\n");
  expectRejected(std::string("mtllib uri.mtl\nusemtl u\n") + kQuad, "URI");
}

TEST_F(ObjTest, RejectsFilesWithoutTriangles) {
  expectRejected("", "no triangles");
  expectRejected("# only points\nv 0 0 0\nv 1 0 0\nl 1 2\n", "no triangles");
}

TEST_F(ObjTest, RejectsNonFiniteVertices) {
  expectRejected("v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n", "bad.obj:2: v coordinate '1e999' is not a finite number");
}

TEST_F(ObjTest, MissingFileIsBadInput) {
  Result<Scene> scene = loadObj(dir_ / "nope.obj");
  ASSERT_FALSE(scene.ok());
  EXPECT_EQ(scene.error().code, ExitCode::BadInput);
  EXPECT_NE(scene.error().message.find("no such file"), std::string::npos);
}
