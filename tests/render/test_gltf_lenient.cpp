// glTF files with parts Rayster skips (an image no material uses that is missing, a primitive
// without POSITION, a mesh left empty) render through the real binary with warnings; a file with
// nothing left to render is refused in one line.
#include <gtest/gtest.h>

#include "tests/render/run_rayster.h"
#include "tests/unit/gltf_test_util.h"

namespace rayster::test {
namespace {

size_t countLines(const std::string& text, const std::string& start) {
  size_t count = 0;
  for (size_t at = 0; at < text.size();) {
    size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    if (text.compare(at, start.size(), start) == 0) ++count;
    at = end + 1;
  }
  return count;
}

Json withoutPosition(Doc& d) {
  Json p = primitive(d);
  p["attributes"].erase("POSITION");
  return p;
}

TEST(GltfLenient, SkippedPartsRenderWithWarnings) {
  auto dir = testDir();
  Doc d = quadDoc();
  d.j["images"] = Json::array({{{"uri", "nowhere.png"}}});
  d.j["meshes"][0]["primitives"].push_back(withoutPosition(d));
  d.j["meshes"].push_back({{"name", "ghost"}, {"primitives", Json::array({withoutPosition(d)})}});
  d.j["nodes"].push_back({{"name", "ghost-node"}, {"mesh", 1}});
  d.j["scenes"][0]["nodes"].push_back(1);
  std::ofstream(dir / "skips.gltf") << d.gltf();

  Image8 img = renderOk(dir, "skips", (dir / "skips.gltf").string() + " --frames 2", 96, 64);
  EXPECT_EQ(img.width, 96);
  RunResult r = runRayster("render " + (dir / "skips.gltf").string() + " --size 64x48 --frames 1 -o " +
                           (dir / "again.png").string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_GE(countLines(r.output, "rayster: warning: "), 3u) << r.output;
  EXPECT_NE(r.output.find("nowhere.png"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("POSITION"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ghost"), std::string::npos) << r.output;
  EXPECT_EQ(countLines(r.output, "rayster: error: "), 0u) << r.output;
}

TEST(GltfLenient, NothingLeftToRenderExits3) {
  auto dir = testDir();
  Doc d = quadDoc();
  primitive(d)["attributes"].erase("POSITION");
  std::ofstream(dir / "empty.gltf") << d.gltf();
  RunResult r = runRayster("render " + (dir / "empty.gltf").string() + " --size 64x48 --frames 1 -o " +
                           (dir / "empty.png").string());
  EXPECT_EQ(r.exitCode, 3) << r.output;
  EXPECT_EQ(countLines(r.output, "rayster: error: "), 1u) << r.output;
  EXPECT_NE(r.output.find("nothing to render"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "empty.png"));
}

}  // namespace
}  // namespace rayster::test
