#pragma once
// Pieces the built-in scenes share (scene/builtin_*.cpp); not part of the scene API.
#include <cstdint>
#include <string>

#include "core/error.h"
#include "scene/mesh_asset.h"
#include "scene/scene.h"

namespace rayster::scene::builtin {

uint32_t addMaterial(Scene& scene, Material material);

// One mesh holding `prim`; returns the mesh index.
uint32_t addMesh(Scene& scene, std::string name, Primitive prim);
void addInstance(Scene& scene, std::string name, uint32_t mesh, const glm::mat4& worldFromObject = glm::mat4(1.0f),
                 bool castsShadows = true);

// A square floor of side `size` at y = 0 centred on `centre`, uvs 0..1 across it.
uint32_t addFloor(Scene& scene, glm::vec3 centre, float size, uint32_t material);

// A sphere light plus its visible emissive sphere (which casts no shadow, so it does not
// block its own light).
void addSphereLight(Scene& scene, std::string name, glm::vec3 position, float radius, glm::vec3 color, float intensity);

// A sun: directional light with the sun's ~0.5 degree angular radius for soft shadow edges.
void addSun(Scene& scene, glm::vec3 direction, float irradiance);
Environment blueSky();

// An embedded mesh scaled uniformly to `height`, standing on y = 0 and centred on x = z = 0,
// so an instance transform only needs to place and turn it.
Result<Primitive> loadStandingMesh(EmbeddedMesh which, float height, uint32_t material);

// A tileable procedural marble, sRGB RGBA8, size x size (marble_texture.cpp).
ImageData makeMarbleImage(int size);

}  // namespace rayster::scene::builtin
