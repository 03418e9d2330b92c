#include "scene/mesh_asset.h"

#include <bit>
#include <cmath>
#include <cstring>

namespace rayster::scene {
namespace {

constexpr uint32_t kVersion = 1;
constexpr size_t kHeaderBytes = 16;

// Byte-wise so the decode is right on any host and never makes an unaligned load.
uint32_t readU32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

// Area-weighted: the un-normalised cross product is twice the triangle's area, so large faces
// dominate and slivers (common in the subdivided teapot's lid) cannot tilt a vertex normal.
void computeSmoothNormals(Primitive& prim) {
  prim.normals.assign(prim.positions.size(), glm::vec3(0.0f));
  for (size_t i = 0; i + 2 < prim.indices.size(); i += 3) {
    const uint32_t a = prim.indices[i], b = prim.indices[i + 1], c = prim.indices[i + 2];
    const glm::vec3 n = glm::cross(prim.positions[b] - prim.positions[a], prim.positions[c] - prim.positions[a]);
    prim.normals[a] += n;
    prim.normals[b] += n;
    prim.normals[c] += n;
  }
  for (glm::vec3& n : prim.normals) {
    const float len = glm::length(n);
    // A vertex used by no triangle, or only by degenerate ones, still needs a unit normal.
    n = (std::isfinite(len) && len > 0.0f) ? n / len : glm::vec3(0, 1, 0);
  }
}

}  // namespace

Result<Primitive> parseMeshAsset(std::span<const uint8_t> bytes, uint32_t material) {
  if (bytes.size() < kHeaderBytes)
    return makeError(ExitCode::BadInput, "mesh asset: {} bytes is shorter than the {}-byte header", bytes.size(),
                     kHeaderBytes);
  if (std::memcmp(bytes.data(), "RMSH", 4) != 0)
    return makeError(ExitCode::BadInput, "mesh asset: bad magic (expected RMSH)");
  const uint32_t version = readU32(bytes.data() + 4);
  if (version != kVersion)
    return makeError(ExitCode::BadInput, "mesh asset: version {} is not supported (expected {})", version, kVersion);
  const uint32_t vertexCount = readU32(bytes.data() + 8);
  const uint32_t triangleCount = readU32(bytes.data() + 12);
  // 64-bit arithmetic: counts near 2^32 cannot wrap the expected size into a small number.
  const uint64_t expected = kHeaderBytes + uint64_t(vertexCount) * 12 + uint64_t(triangleCount) * 12;
  if (bytes.size() != expected)
    return makeError(ExitCode::BadInput, "mesh asset: {} vertices and {} triangles need {} bytes, got {}", vertexCount,
                     triangleCount, expected, bytes.size());
  if (vertexCount == 0 || triangleCount == 0)
    return makeError(ExitCode::BadInput, "mesh asset: empty ({} vertices, {} triangles)", vertexCount, triangleCount);

  Primitive prim;
  prim.material = material;
  prim.positions.resize(vertexCount);
  const uint8_t* p = bytes.data() + kHeaderBytes;
  for (uint32_t v = 0; v < vertexCount; ++v, p += 12) {
    const glm::vec3 pos(std::bit_cast<float>(readU32(p)), std::bit_cast<float>(readU32(p + 4)),
                        std::bit_cast<float>(readU32(p + 8)));
    if (!std::isfinite(pos.x) || !std::isfinite(pos.y) || !std::isfinite(pos.z))
      return makeError(ExitCode::BadInput, "mesh asset: position {} is not finite", v);
    prim.positions[v] = pos;
  }
  prim.indices.resize(size_t(triangleCount) * 3);
  for (size_t i = 0; i < prim.indices.size(); ++i, p += 4) {
    const uint32_t index = readU32(p);
    if (index >= vertexCount)
      return makeError(ExitCode::BadInput, "mesh asset: index {} is {}, past the vertex count {}", i, index,
                       vertexCount);
    prim.indices[i] = index;
  }
  computeSmoothNormals(prim);
  return prim;
}

}  // namespace rayster::scene
