#pragma once
// Rayster's own triangle-mesh asset format (.mesh), used for the meshes compiled into the binary.
// Layout, little-endian (assets/meshes/README.md; written by tools/convert-npm-meshes.js):
//   char magic[4] = "RMSH"; uint32 version = 1; uint32 vertexCount; uint32 triangleCount;
//   float32 positions[3 * vertexCount]; uint32 indices[3 * triangleCount]
#include <cstdint>
#include <span>

#include "core/error.h"
#include "scene/scene.h"

namespace rayster::scene {

// Decodes a .mesh buffer into one primitive with area-weighted smooth normals and no uvs.
// Anything malformed (short or overlong buffer, bad magic or version, an index past the vertex
// count, a non-finite position) is ExitCode::BadInput; the buffer is never read out of bounds.
Result<Primitive> parseMeshAsset(std::span<const uint8_t> bytes, uint32_t material);

// The .mesh files embedded at build time (scene/embedded_assets.cpp).
enum class EmbeddedMesh { Teapot, Bunny };
std::span<const uint8_t> embeddedMeshBytes(EmbeddedMesh mesh);

}  // namespace rayster::scene
