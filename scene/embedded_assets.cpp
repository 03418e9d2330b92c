// Mesh assets compiled into the binary, so built-in scenes work from any working directory and
// after installation. `.incbin` keeps the data out of the C++ source (a text dump of the bunny
// would be megabytes) and out of the compiler's memory. RAYSTER_ASSET_DIR comes from CMake, which
// also lists the .mesh files as OBJECT_DEPENDS (the compiler's depfile cannot see an .incbin).
#include <cstdint>
#include <span>

#include "scene/mesh_asset.h"

#ifndef RAYSTER_ASSET_DIR
#error "RAYSTER_ASSET_DIR must name the assets/ folder (set by CMake)"
#endif

// Each blob gets a start and an end label; .balign 4 so a debugger or a future direct view of the
// floats sees aligned data (the parser itself reads byte-wise).
// One assembler line per source line reads best, so clang-format leaves the macro alone.
// clang-format off
#define RAYSTER_EMBED(symbol, file)                   \
  asm(".pushsection .rodata\n"                        \
      ".balign 4\n"                                   \
      ".global " #symbol "\n"                         \
      #symbol ":\n"                                   \
      ".incbin \"" RAYSTER_ASSET_DIR "/" file "\"\n"  \
      ".global " #symbol "_end\n"                     \
      #symbol "_end:\n"                               \
      ".popsection\n")
// clang-format on

RAYSTER_EMBED(rayster_teapot_mesh, "meshes/teapot.mesh");
RAYSTER_EMBED(rayster_bunny_mesh, "meshes/bunny.mesh");

extern "C" const uint8_t rayster_teapot_mesh[], rayster_teapot_mesh_end[];
extern "C" const uint8_t rayster_bunny_mesh[], rayster_bunny_mesh_end[];

namespace rayster::scene {
namespace {

// Through uintptr_t: start and end are distinct symbols, so pointer subtraction between them is
// not something the language promises.
std::span<const uint8_t> between(const uint8_t* begin, const uint8_t* end) {
  return {begin, static_cast<size_t>(reinterpret_cast<uintptr_t>(end) - reinterpret_cast<uintptr_t>(begin))};
}

}  // namespace

std::span<const uint8_t> embeddedMeshBytes(EmbeddedMesh mesh) {
  switch (mesh) {
    case EmbeddedMesh::Teapot:
      return between(rayster_teapot_mesh, rayster_teapot_mesh_end);
    case EmbeddedMesh::Bunny:
      return between(rayster_bunny_mesh, rayster_bunny_mesh_end);
  }
  RAYSTER_ASSERT(false, "unknown embedded mesh");
}

}  // namespace rayster::scene
