#pragma once
// glTF 2.0 (.gltf with external or data-URI buffers, and .glb) through Debian's tinygltf.
#include <filesystem>

#include "core/error.h"
#include "scene/scene.h"

namespace rayster::scene {

// The default scene (or scene 0, or every root node when the file has no scenes) becomes one
// Instance per node with a mesh, one Mesh per glTF mesh (instancing shares it), triangle
// primitives only. Cameras, KHR_lights_punctual lights, metallic-roughness materials with the
// KHR_materials_* extensions in scene.h, textures decoded to RGBA8. A file without a camera gets
// none (applyDefaults() adds one). Missing normals become flat normals, as the glTF spec asks.
//
// The file is untrusted: every accessor is bounds-checked here, URIs must stay inside the file's
// folder (no absolute paths, "..", or schemes other than data:), and images larger than
// 16384 per side are refused. Every failure is ExitCode::BadInput with one line naming the file
// and the cause, e.g. "box.gltf: accessor 3 reads past the end of buffer view 1".
Result<Scene> loadGltf(const std::filesystem::path& path);

}  // namespace rayster::scene
