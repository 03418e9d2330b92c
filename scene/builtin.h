#pragma once
// Scenes compiled into the binary, so every test and first run works without asset files.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "scene/scene.h"

namespace rayster::scene {

// Accepts "NAME" and "builtin:NAME"; "instances" also takes a count, "instances:N". Unknown
// names and bad counts: ExitCode::BadInput listing what exists.
Result<Scene> makeBuiltinScene(std::string_view name);
// The bare names (no "builtin:" and no parameters), in the order help text lists them.
std::vector<std::string> builtinSceneNames();

// Built-in models, for scene files to compose ("path": "builtin:teapot:mirror"): one object and its
// material, no light, camera or environment. NAME[:MATERIAL] with NAME teapot (0.8 m tall, 3,968
// triangles), bunny (1 m, 14,696 triangles), sphere (analytic, 1 m across) or floor (20 m square)
// standing on y = 0 about the origin, and MATERIAL white (the default; the floor's grey), grey,
// red, green, blue (diffuse) or mirror. Rendered alone, a model gets a file's defaults (a sun, the
// sky, a framing camera: docs/scene-format.md). Unknown names or materials: ExitCode::BadInput.
std::vector<std::string> builtinModelNames();
bool isBuiltinModel(std::string_view name);
Result<Scene> makeBuiltinModel(std::string_view name);

// The Cornell box from Cornell University's measured data, millimetres * 0.01 (room ~5.5 m),
// with a mirror-like tall block and a sphere light under the ceiling.
Scene makeCornellBox();

// Chrome Utah teapot and ice Stanford bunny on a procedural marble floor, sphere light, sky.
// Fails only if an embedded mesh asset is corrupt.
Result<Scene> makeWhittedScene();

// A 5 x 3 grid of analytic spheres of assorted materials on a triangle floor, sun and sky.
Scene makeSpheresScene();

// `count` bunny instances (one mesh) on a square grid, sun and sky; count in 1..kMaxBuiltinInstances.
inline constexpr uint32_t kDefaultBuiltinInstances = 64;
inline constexpr uint32_t kMaxBuiltinInstances = 1'000'000;  // ~100 MB of instances; TLAS-sized tests
Result<Scene> makeInstancesScene(uint32_t count);

// The 16-bunny grid lit by `count` point lights on a ring (no sun): the light-count sweep of
// `rayster bench`; count in 1..kMaxBuiltinLights.
inline constexpr uint32_t kDefaultBuiltinLights = 16;
inline constexpr uint32_t kMaxBuiltinLights = 4096;
Result<Scene> makeLightsScene(uint32_t count);

}  // namespace rayster::scene
