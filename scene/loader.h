#pragma once
// The one entry point the CLI and tests use to turn a name on the command line into a Scene, plus
// the path policy every file format shares.
#include <filesystem>
#include <string>
#include <string_view>

#include "core/error.h"
#include "scene/scene.h"

namespace rayster::scene {

// "builtin:NAME" -> makeBuiltinScene; otherwise by extension (case-insensitive): .gltf/.glb -> glTF,
// .obj -> OBJ, .json -> scene file (docs/scene-format.md). Files get applyDefaults(); built-in
// scenes define everything themselves. Failures: ExitCode::BadInput naming the file and the cause.
Result<Scene> loadScene(const std::string& nameOrPath);

// One model file by extension: .gltf/.glb or .obj (what a scene file's "models" may name).
Result<Scene> loadModelFile(const std::filesystem::path& path);

// Makes a scene from a bare model file renderable: a "default sun" plus a sky when there is no
// light, a "default" camera framing scene.bounds() when there is none. Leaves a named scene's name.
void applyDefaults(Scene& scene);

// The camera applyDefaults adds: looks at the bounds' centre from the +Z side, slightly above,
// with the bounding sphere inside a 45-degree vertical field of view.
Camera makeFramingCamera(const Aabb& bounds);

// Resolves a path written inside a scene, OBJ or MTL file against the folder of that file. A file
// must not reach outside its folder (scene files get shared and downloaded), so absolute paths,
// ".." components and URIs ("http://", "file:") are refused with ExitCode::BadInput. Backslashes
// are read as separators because Windows exporters write them. `what` names the reference in the
// message ("scene.json: models[0].path").
Result<std::filesystem::path> resolveRelativePath(const std::filesystem::path& baseDir, std::string_view ref,
                                                  std::string_view what);

}  // namespace rayster::scene
