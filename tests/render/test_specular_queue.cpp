// The specular paths' continuation queue (render/passes/rt_specular.cpp, shaders/specular.rgen.glsl
// SPECULAR_QUEUE): the paths that go on after their first segment are traced by a second, dense
// launch. The image must be the one the in-place loop (--specular-queue off) renders, also when more
// paths go on than the queue holds (one per kSpecularQueueDivisor pixels) and the rest loop on in
// their own invocation.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

class SpecularQueue : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testDir(); }

  // Renders `scene` with the queue on or off; checks the run and its image, and whether the
  // continuation pass was recorded.
  ImageF render(const std::string& scene, bool queue, const std::string& extra = "") {
    const std::string name = std::string(queue ? "queue" : "loop");
    const auto out = dir_ / (name + ".exr");
    RunResult r =
        runRayster("render " + scene + " --size 64x48 --frames 2 --seed 5 --exposure 0 --primary raster --timings " +
                   extra + " --specular-queue " + (queue ? "on" : "off") + " -o " + out.string());
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("\nrt-specular-continue ") != std::string::npos, queue) << r.output;
    auto img = readExr(out);
    EXPECT_TRUE(img.ok()) << r.output;
    if (!img.ok()) return {};
    auto empty = rejectEmpty(*img, 64, 48);
    EXPECT_FALSE(empty.has_value()) << name << ": " << empty.value_or("");
    return std::move(*img);
  }

  // The queue carries a path's throughput and radiance as half floats: every pixel within a few
  // half-float steps of the loop's value.
  static void expectSame(const ImageF& queued, const ImageF& looped) {
    ASSERT_EQ(queued.rgba.size(), looped.rgba.size());
    size_t off = 0;
    double worst = 0;
    for (size_t i = 0; i < looped.rgba.size(); ++i) {
      const double a = queued.rgba[i], b = looped.rgba[i];
      const double err = std::abs(a - b) / std::max(std::abs(b), 0.01);
      worst = std::max(worst, err);
      if (err > 4e-3) ++off;
    }
    EXPECT_EQ(off, 0u) << "worst relative difference " << worst;
  }

  std::filesystem::path dir_;
};

TEST_F(SpecularQueue, WhittedRendersTheSameWithTheQueue) {
  // The chrome teapot, the ice bunny (paths of up to 7 segments) and the glossy marble floor.
  expectSame(render("builtin:whitted", true), render("builtin:whitted", false));
}

TEST_F(SpecularQueue, AFullQueueLoopsTheRestInPlace) {
  // A box of mirrors around the camera: every pixel's path goes on after its first segment, four
  // times as many as the queue holds.
  std::ofstream(dir_ / "mirror.mtl") << "newmtl mirror\nKs 0.9 0.85 0.8\nillum 3\n"
                                     << "newmtl floor\nKd 0.7 0.6 0.5\nNs 0\nillum 2\n";
  std::ofstream obj(dir_ / "box.obj");
  obj << "mtllib mirror.mtl\n";
  obj << "v -2 0 -2\nv 2 0 -2\nv 2 3 -2\nv -2 3 -2\nv -2 0 2\nv 2 0 2\nv 2 3 2\nv -2 3 2\n";
  // Flat normals, facing into the box (without them the corners' averaged normals curve the walls).
  obj << "vn 0 1 0\nvn 0 0 1\nvn 0 0 -1\nvn 1 0 0\nvn -1 0 0\nvn 0 -1 0\n";
  obj << "usemtl floor\nf 1//1 5//1 6//1 2//1\n";
  obj << "usemtl mirror\nf 1//2 2//2 3//2 4//2\nf 6//3 5//3 8//3 7//3\nf 5//4 1//4 4//4 8//4\n"
      << "f 2//5 6//5 7//5 3//5\nf 4//6 3//6 7//6 8//6\n";  // walls and ceiling
  obj.close();
  std::ofstream(dir_ / "box.json") << R"({"models": [{"path": "box.obj"}],
  "lights": [{"type": "point", "position": [0.5, 2.2, 0.3], "intensity": 8}],
  "cameras": [{"name": "in", "position": [0.3, 1.6, 1.2], "target": [-1.5, 1.4, -2], "yfov": 60}]})";
  const std::string scene = (dir_ / "box.json").string();
  expectSame(render(scene, true), render(scene, false));
}

}  // namespace
}  // namespace rayster::test
