#pragma once
// glTF files shaped like the ones users bring (the Khronos sample models, Blender exports), built
// here so no downloaded asset is needed: a sphere row seen through a 1 mm near plane, mirror / glass /
// gold spheres under physically scaled lights, single-sided geometry and a mirrored node.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/image_io.h"
#include "tests/unit/gltf_test_util.h"

namespace rayster::test {

// Adds a primitive (positions, normals, u32 indices, optional UVs) to mesh `mesh` of `d`, creating
// the mesh when it does not exist yet.
inline void addPrimitive(Doc& d, int mesh, const std::vector<float>& pos, const std::vector<float>& nrm,
                         const std::vector<uint32_t>& idx, int material, const std::vector<float>& uv = {}) {
  Json attributes = {{"POSITION", d.floats(pos, "VEC3", 3)}, {"NORMAL", d.floats(nrm, "VEC3", 3)}};
  // POSITION needs min and max (glTF 2.0 §5.1.1).
  Json& acc = d.j["accessors"][size_t(attributes["POSITION"].get<int>())];
  std::vector<float> lo(3, 1e30f), hi(3, -1e30f);
  for (size_t i = 0; i < pos.size(); ++i)
    lo[i % 3] = std::min(lo[i % 3], pos[i]), hi[i % 3] = std::max(hi[i % 3], pos[i]);
  acc["min"] = lo;
  acc["max"] = hi;
  if (!uv.empty()) attributes["TEXCOORD_0"] = d.floats(uv, "VEC2", 2);
  const int indices = d.accessor(d.view(idx), kUInt, idx.size(), "SCALAR");
  while (int(d.j["meshes"].size()) <= mesh) d.j["meshes"].push_back({{"primitives", Json::array()}});
  d.j["meshes"][size_t(mesh)]["primitives"].push_back(
      {{"attributes", attributes}, {"indices", indices}, {"material", material}});
}

// A UV sphere of `rings` × 2·rings quads, counter-clockwise seen from outside.
inline void addUvSphere(Doc& d, int mesh, glm::vec3 c, float r, int material, int rings = 24) {
  std::vector<float> pos, nrm;
  std::vector<uint32_t> idx;
  const int cols = 2 * rings;
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j <= cols; ++j) {
      const float th = float(M_PI) * float(i) / float(rings), ph = 2.0f * float(M_PI) * float(j) / float(cols);
      const glm::vec3 n(std::sin(th) * std::cos(ph), std::cos(th), -std::sin(th) * std::sin(ph));
      for (int k = 0; k < 3; ++k) pos.push_back(c[k] + r * n[k]), nrm.push_back(n[k]);
    }
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < cols; ++j) {
      const uint32_t a = uint32_t(i * (cols + 1) + j), b = a + uint32_t(cols + 1);
      idx.insert(idx.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  addPrimitive(d, mesh, pos, nrm, idx, material);
}

// A horizontal square at height y facing +Y, UVs 0..tiles.
inline void addFloor(Doc& d, int mesh, float half, float y, int material, float tiles = 1.0f) {
  addPrimitive(d, mesh, {-half, y, half, half, y, half, half, y, -half, -half, y, -half},
               {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0}, {0, 1, 2, 0, 2, 3}, material,
               {0, 0, tiles, 0, tiles, tiles, 0, tiles});
}

inline Json pbr(glm::vec3 base, float metallic, float roughness, bool doubleSided = true) {
  return {{"pbrMetallicRoughness",
           {{"baseColorFactor", {base.r, base.g, base.b, 1.0}},
            {"metallicFactor", metallic},
            {"roughnessFactor", roughness}}},
          {"doubleSided", doubleSided}};
}

// A camera node looking from `eye` at `target` (y up), as a glTF node rotation.
inline Json cameraNode(glm::vec3 eye, glm::vec3 target, int camera) {
  const glm::vec3 f = glm::normalize(target - eye), r = glm::normalize(glm::cross(f, glm::vec3(0, 1, 0)));
  const glm::vec3 u = glm::cross(r, f);
  const glm::quat q = glm::quat_cast(glm::mat3(r, u, -f));
  return {{"camera", camera}, {"translation", {eye.x, eye.y, eye.z}}, {"rotation", {q.x, q.y, q.z, q.w}}};
}

inline void addLights(Doc& d, const Json& lights) {
  d.j["extensionsUsed"].push_back("KHR_lights_punctual");
  d.j["extensions"]["KHR_lights_punctual"]["lights"] = lights;
}

// Item 1 of the first issue of this wave, as the Khronos EnvironmentTest has it: a row of seven
// spheres (metal and dielectric) on a floor, seen from ~28 m through a camera with znear = 1 mm,
// lit by a sun. Traced primaries used to bend by pixels here and shadow themselves.
inline std::filesystem::path writeSphereRowGltf(const std::filesystem::path& dir, double znear) {
  Doc d;
  for (int k = 0; k < 7; ++k) addUvSphere(d, 0, {-9.0f + 3.0f * float(k), 1.3f, 0.0f}, 1.2f, k % 2);
  addFloor(d, 0, 15.0f, 0.0f, 2);
  d.j["materials"] = {pbr({0.9f, 0.7f, 0.3f}, 1.0f, 0.3f), pbr({0.8f, 0.8f, 0.8f}, 0.0f, 0.6f),
                      pbr({0.5f, 0.5f, 0.5f}, 0.0f, 0.9f)};
  d.j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.6}, {"znear", znear}, {"zfar", 200.0}}}}};
  addLights(d, {{{"type", "directional"}, {"intensity", 3.0}}});
  d.j["nodes"] = {
      {{"mesh", 0}, {"name", "spheres"}},
      cameraNode({-0.76f, 7.7f, 27.7f}, {-0.5f, 1.0f, 0.0f}, 0),
      {{"rotation", {-0.3535, 0.3535, 0.1464, 0.8535}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}};
  d.j["scenes"] = {{{"nodes", {0, 1, 2}}}};
  d.j["scene"] = 0;
  auto path = dir / "sphere-row.gltf";
  std::ofstream(path) << d.gltf();
  return path;
}

// Item 2: a mirror, a glass and a gold sphere on a checkered ground under a sun and a point light,
// `lightScale` × the built-in scenes' light levels (1000: what Blender writes in lux and candela for
// 3 W/m² and 48 W/sr-like sources). Rendered at −log2(lightScale) EV, every scale must look the same.
inline std::filesystem::path writeSpecularSpheresGltf(const std::filesystem::path& dir, double lightScale) {
  Image8 checker = Image8::make(64, 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool dark = ((x / 8) + (y / 8)) % 2 == 1;
      uint8_t* p = checker.pixel(x, y);
      p[0] = dark ? 40 : 220, p[1] = dark ? 60 : 200, p[2] = dark ? 90 : 160, p[3] = 255;
    }
  (void)writePng(dir / "ground.png", checker);
  Doc d;
  addUvSphere(d, 0, {-1.25f, 0.55f, 0.0f}, 0.55f, 0);
  addUvSphere(d, 0, {0.0f, 0.55f, 0.4f}, 0.55f, 1);
  addUvSphere(d, 0, {1.25f, 0.55f, 0.0f}, 0.55f, 2);
  addFloor(d, 0, 4.0f, 0.0f, 3, 4.0f);
  Json glass = pbr({1.0f, 1.0f, 1.0f}, 0.0f, 0.0f);
  glass["extensions"] = {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                         {"KHR_materials_ior", {{"ior", 1.5}}},
                         {"KHR_materials_volume", {{"thicknessFactor", 1.1}}}};
  Json ground = pbr({1.0f, 1.0f, 1.0f}, 0.0f, 0.8f);
  ground["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
  d.j["materials"] = {pbr({0.97f, 0.97f, 0.97f}, 1.0f, 0.0f), glass, pbr({1.0f, 0.78f, 0.34f}, 1.0f, 0.05f), ground};
  d.j["extensionsUsed"] = {"KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume"};
  d.j["textures"] = {{{"source", 0}}};
  d.j["images"] = {{{"uri", "ground.png"}}};
  d.j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.55}, {"znear", 0.05}, {"zfar", 100.0}}}}};
  addLights(d, {{{"type", "directional"}, {"intensity", 3.0 * lightScale}, {"color", {1.0, 0.96, 0.9}}},
                {{"type", "point"}, {"intensity", 48.0 * lightScale}, {"extras", {{"radius", 0.1}}}}});
  d.j["nodes"] = {
      {{"mesh", 0}, {"name", "spheres"}},
      cameraNode({0.0f, 1.6f, 5.0f}, {0.0f, 0.45f, 0.0f}, 0),
      {{"rotation", {-0.3827, 0.0, 0.0, 0.9239}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
      {{"translation", {2.0, 3.0, 2.5}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}}};
  d.j["scenes"] = {{{"nodes", {0, 1, 2, 3}}}};
  d.j["scene"] = 0;
  auto path = dir / "specular-spheres.gltf";
  std::ofstream(path) << d.gltf();
  return path;
}

// Item 3: glTF's doubleSided. A double-sided blue backdrop; before it, seen from the camera on +Z,
// four single-sided quads at the same depth (left to right): green facing the camera, red facing away
// (its back faces the camera: must not be seen), and the same two under a node with scale (−1, 1, 1)
// (NegativeScaleTest): yellow facing the camera after the mirror, red facing away. Above a floor,
// two horizontal single-sided quads: one facing up (towards the sun: rays from the floor meet its
// back, so it casts no shadow) and one facing down (it shadows the floor, and the camera above
// sees only its back: invisible).
inline std::filesystem::path writeSidednessGltf(const std::filesystem::path& dir) {
  Doc d;
  // Vertical quads in z = 0 of half-size h centred at (cx, cy), counter-clockwise seen from +Z or −Z.
  auto quad = [&](int mesh, float cx, float cy, float h, bool facesPlusZ, int material) {
    std::vector<float> pos = {cx - h, cy - h, 0, cx + h, cy - h, 0, cx + h, cy + h, 0, cx - h, cy + h, 0};
    const float nz = facesPlusZ ? 1.0f : -1.0f;
    std::vector<uint32_t> idx =
        facesPlusZ ? std::vector<uint32_t>{0, 1, 2, 0, 2, 3} : std::vector<uint32_t>{0, 2, 1, 0, 3, 2};
    addPrimitive(d, mesh, pos, {0, 0, nz, 0, 0, nz, 0, 0, nz, 0, 0, nz}, idx, material);
  };
  quad(0, -3.0f, 1.5f, 0.7f, true, 0);   // green, seen
  quad(0, -1.0f, 1.5f, 0.7f, false, 1);  // red, back to the camera
  // Mesh 1 sits under the mirroring node: object x = −3 lands at world x = +3.
  quad(1, -3.0f, 1.5f, 0.7f, true, 2);   // yellow, front to the camera after the mirror
  quad(1, -1.0f, 1.5f, 0.7f, false, 1);  // red, back to the camera after the mirror
  addPrimitive(d, 2, {-6, -1, -1, 6, -1, -1, 6, 4, -1, -6, 4, -1}, {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1},
               {0, 2, 1, 0, 3, 2},
               3);  // the backdrop, wound to face −Z: only double-sidedness shows it
  // One mesh for the backdrop, the floor and the horizontal quads: it mixes sidedness, so its
  // single-sided triangles take the any-hit path (render/gpu_scene.cpp).
  addFloor(d, 2, 6.0f, -1.0f, 4);
  // Horizontal quads at y = 0, z 1 .. 2: facing up (x < 0) and facing down (x > 0). The sun shines
  // from the camera's side at 45°, so their shadows fall on the floor at z 0 .. 1.
  addPrimitive(d, 2, {-2.5f, 0, 1, -1.5f, 0, 1, -1.5f, 0, 2, -2.5f, 0, 2}, {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0},
               {0, 2, 1, 0, 3, 2}, 5);
  addPrimitive(d, 2, {1.5f, 0, 1, 2.5f, 0, 1, 2.5f, 0, 2, 1.5f, 0, 2}, {0, -1, 0, 0, -1, 0, 0, -1, 0, 0, -1, 0},
               {0, 1, 2, 0, 2, 3}, 5);
  auto single = [](glm::vec3 c) { return pbr(c, 0.0f, 1.0f, false); };
  d.j["materials"] = {single({0.1f, 0.8f, 0.1f}),  single({0.9f, 0.05f, 0.05f}),
                      single({0.9f, 0.8f, 0.05f}), pbr({0.1f, 0.2f, 0.9f}, 0.0f, 1.0f, true),
                      single({0.7f, 0.7f, 0.7f}),  single({0.8f, 0.5f, 0.2f})};
  d.j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.05}, {"zfar", 100.0}}}}};
  // The sun (light 0: the shadow-raw AOV) and a point light by the camera that shows the colours.
  addLights(d, {{{"type", "directional"}, {"intensity", 3.0}}, {{"type", "point"}, {"intensity", 40.0}}});
  d.j["nodes"] = {
      {{"mesh", 0}, {"name", "quads"}},
      {{"mesh", 1}, {"name", "mirrored"}, {"scale", {-1.0, 1.0, 1.0}}},
      {{"mesh", 2}, {"name", "backdrop and floor"}},
      cameraNode({0.0f, 3.5f, 9.0f}, {0.0f, 0.5f, 0.0f}, 0),
      {{"rotation", {-0.3827, 0.0, 0.0, 0.9239}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
      {{"translation", {0.5, 3.0, 6.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}}};
  d.j["scenes"] = {{{"nodes", {0, 1, 2, 3, 4, 5}}}};
  d.j["scene"] = 0;
  auto path = dir / "sidedness.gltf";
  std::ofstream(path) << d.gltf();
  return path;
}

}  // namespace rayster::test
