#pragma once
// Wavefront OBJ + MTL, through Debian's tinyobjloader.
#include <filesystem>

#include "core/error.h"
#include "scene/scene.h"

namespace rayster::scene {

// One Mesh (and one identity Instance) per object/group, one Primitive per material it uses;
// polygons are triangulated. Normals come from the file or are generated (area-weighted, smooth);
// UVs are flipped to glTF's top-down convention. MTL: Kd -> baseColor, d/Tr -> alpha (Blend below
// 1), Ke -> emissive, Ns -> roughness sqrt(2/(Ns+2)), map_Kd -> baseColorTexture, norm ->
// normalTexture, illum 3/5 -> mirror, illum 4/6/7/9 -> glass (transmission 1, ior Ni). Materials
// are double-sided: OBJ has no notion of back faces and its windings are often inconsistent.
// mtllib and texture paths must stay inside the OBJ's folder. A missing .mtl or texture is a
// warning; bad face indices (naming the line), escaping paths and files without triangles are
// ExitCode::BadInput.
Result<Scene> loadObj(const std::filesystem::path& path);

}  // namespace rayster::scene
