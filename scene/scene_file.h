#pragma once
// Rayster's JSON scene files: models placed in one world, plus lights, cameras, environment and a
// camera path. The format is documented in docs/scene-format.md.
#include <filesystem>

#include "core/error.h"
#include "scene/scene.h"

namespace rayster::scene {

// Paths inside the file are relative to its folder (absolute paths, ".." and URIs are refused).
// Angles are degrees in the file, radians in the Scene. Failures are ExitCode::BadInput naming the
// file and the JSON path ("scene.json: models[2].scale must be ..."); unknown keys are warnings.
// The file's cameras come before any the models bring, so camera 0 is the author's.
Result<Scene> loadSceneFile(const std::filesystem::path& path);

}  // namespace rayster::scene
