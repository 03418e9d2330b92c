#pragma once
// Scenes compiled into the binary, so every test and first run works without asset files.
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "scene/scene.h"

namespace rayster::scene {

// Accepts "cornell" and "builtin:cornell". Unknown: ExitCode::BadInput listing what exists.
Result<Scene> makeBuiltinScene(std::string_view name);
std::vector<std::string> builtinSceneNames();

// The Cornell box from Cornell University's measured data, millimetres * 0.01 (room ~5.5 m),
// with a mirror-like tall block and a sphere light under the ceiling.
Scene makeCornellBox();

} // namespace rayster::scene
