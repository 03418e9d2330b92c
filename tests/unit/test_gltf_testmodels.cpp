// Every glTF in Debian's assimp-testmodels (real exporters' output plus deliberately broken files)
// either loads or is refused cleanly: BadInput, one non-empty line. Never a crash or a hang.
#include <algorithm>
#include <array>
#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "core/log.h"
#include "scene/gltf_loader.h"

using namespace rayster;
namespace fs = std::filesystem;

namespace {

const fs::path kModels = "/usr/share/assimp/models";

std::vector<fs::path> gltfFiles() {
  std::vector<fs::path> files;
  for (const char* sub : {"glTF", "glTF2"}) {
    std::error_code ec;
    if (!fs::is_directory(kModels / sub, ec)) continue;
    for (auto it = fs::recursive_directory_iterator(kModels / sub, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec)) {
      std::string ext = it->path().extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
      if (it->is_regular_file() && (ext == ".gltf" || ext == ".glb")) files.push_back(it->path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(GltfTestModels, EachLoadsOrIsRefusedCleanly) {
  const std::vector<fs::path> files = gltfFiles();
  if (files.empty()) GTEST_SKIP() << "assimp-testmodels is not installed";
  // The broken models warn on purpose; their warnings are not what this test reads.
  const log::Level previous = log::level();
  log::setLevel(log::Level::Error);
  size_t loaded = 0;
  std::vector<std::string> refusals;
  for (const fs::path& file : files) {
    Result<scene::Scene> scene = scene::loadGltf(file);
    if (scene.ok()) {
      ++loaded;
      continue;
    }
    const Error& error = scene.error();
    EXPECT_EQ(error.code, ExitCode::BadInput) << file;
    EXPECT_FALSE(error.message.empty()) << file;
    EXPECT_EQ(error.message.find('\n'), std::string::npos) << file << ": " << error.message;
    refusals.push_back(error.message);
  }
  log::setLevel(previous);
  std::printf("glTF test models: %zu files, %zu loaded, %zu refused\n", files.size(), loaded, refusals.size());
  for (size_t i = 0; i < refusals.size() && i < 12; ++i) std::printf("  refused: %s\n", refusals[i].c_str());
  // Debian 12's package has 53 files: 25 load; the rest are glTF 1.0, Draco, or broken on purpose.
  EXPECT_GE(loaded, 20u) << "the valid glTF 2.0 test models must keep loading";
}

TEST(GltfTestModels, BoxTexturedHasItsTexture) {
  const fs::path box = kModels / "glTF2/BoxTextured-glTF/BoxTextured.gltf";
  if (!fs::exists(box)) GTEST_SKIP() << box << " is not installed";
  Result<scene::Scene> scene = scene::loadGltf(box);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  ASSERT_EQ(scene->images.size(), 1u);
  EXPECT_GT(scene->images[0].width, 0);
  EXPECT_GT(scene->images[0].height, 0);
  EXPECT_EQ(scene->images[0].rgba.size(), size_t(scene->images[0].width) * size_t(scene->images[0].height) * 4);
  ASSERT_FALSE(scene->meshes.empty());
  ASSERT_FALSE(scene->meshes[0].primitives.empty());
  const scene::Material& material = scene->materials.at(scene->meshes[0].primitives[0].material);
  EXPECT_TRUE(material.baseColorTexture.valid());
  EXPECT_EQ(scene->instances.size(), 1u);
}

}  // namespace

namespace {

// What a primitive's triangles cover: their count and the sum of their (winding-signed) area
// vectors, which is the quad's area times its facing whichever diagonal splits it.
struct Coverage {
  size_t triangles = 0;
  glm::vec3 area{0.0f};
};
Coverage coverage(const scene::Scene& s) {
  Coverage c;
  for (const scene::Mesh& m : s.meshes)
    for (const scene::Primitive& p : m.primitives)
      for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
        const glm::vec3 a = p.positions[p.indices[t]], b = p.positions[p.indices[t + 1]],
                        d = p.positions[p.indices[t + 2]];
        c.area += 0.5f * glm::cross(b - a, d - a);
        ++c.triangles;
      }
  return c;
}

}  // namespace

TEST(GltfTestModels, TriangleStripsAndFansAreTheTrianglesTheyDescribe) {
  // glTF-Asset-Generator's Mesh_PrimitiveMode: 04 strip, 05 fan, 11 indexed strip, 12 indexed fan,
  // all the same quad as 06 (triangles) and 13 (indexed triangles), with the same winding.
  const fs::path dir = "/usr/share/assimp/models/glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode";
  if (!fs::exists(dir)) GTEST_SKIP() << "assimp-testmodels is not installed";
  auto load = [&](const char* n) {
    Result<scene::Scene> s = scene::loadGltf(dir / (std::string("Mesh_PrimitiveMode_") + n + ".gltf"));
    EXPECT_TRUE(s.ok()) << n << ": " << (s.ok() ? "" : s.error().message);
    return s.ok() ? coverage(*s) : Coverage{};
  };
  const Coverage quad = load("06");
  ASSERT_EQ(quad.triangles, 2u);
  ASSERT_GT(glm::length(quad.area), 0.5f);
  for (const char* n : {"13", "04", "05", "11", "12"}) {
    const Coverage c = load(n);
    EXPECT_EQ(c.triangles, 2u) << n;
    EXPECT_NEAR(glm::distance(c.area, quad.area), 0.0f, 1e-5f) << n << ": same area, same facing";
  }
}
