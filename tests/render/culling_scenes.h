#pragma once
// Scenes of the culling tests, written by the tests themselves.
#include <filesystem>
#include <fstream>

namespace rayster::test {

// builtin:instances:64 (a floor and an 8 × 8 grid of bunnies 1.5 m apart, x and z in ±5.25) behind
// a wall at z = 6.5 with a small window (x ±0.4, y 0.35..1.25); the camera looks through the window
// from z = 9 (as bench/scenes/culling-wall.json). The grid's outer columns lie outside the view, most
// bunnies behind the wall, and a few show partly through the window.
inline std::filesystem::path writeWallScene(const std::filesystem::path& dir) {
  std::ofstream(dir / "wall.obj") << R"(v -12 0 6.5
v -0.4 0 6.5
v -0.4 6 6.5
v -12 6 6.5
v 0.4 0 6.5
v 12 0 6.5
v 12 6 6.5
v 0.4 6 6.5
v -0.4 0 6.5
v 0.4 0 6.5
v 0.4 0.35 6.5
v -0.4 0.35 6.5
v -0.4 1.25 6.5
v 0.4 1.25 6.5
v 0.4 6 6.5
v -0.4 6 6.5
f 1 2 3 4
f 5 6 7 8
f 9 10 11 12
f 13 14 15 16
)";
  auto file = dir / "wall.json";
  std::ofstream(file) << R"({"models": [{"path": "builtin:instances:64"}, {"path": "wall.obj"}],
  "cameras": [{"name": "window", "position": [0, 0.8, 9], "target": [0, 0.8, 0], "yfov": 40, "znear": 0.05, "zfar": 60}]})";
  return file;
}

}  // namespace rayster::test
