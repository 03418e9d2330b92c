#pragma once
// Writes a static scene (scene::bakePose's output: no skins, targets or animations) as a glTF file
// with its meshes in base64 buffers, material factors, instance matrices and one camera, so a
// test can render "the same pose, pre-deformed" through the CLI like any user file.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "scene/scene.h"
#include "tests/render/fixtures.h"

namespace rayster::test {

inline std::filesystem::path writeBakedGltf(const scene::Scene& scene, const scene::Camera& camera,
                                            const std::filesystem::path& path) {
  using nlohmann::json;
  std::vector<uint8_t> bin;
  json accessors = json::array(), views = json::array(), meshes = json::array(), nodes = json::array();
  auto addView = [&](const auto& values, int components, int componentType, const char* type) {
    while (bin.size() % 4) bin.push_back(0);
    const size_t offset = bin.size();
    appendBytes(bin, values);
    views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bin.size() - offset}});
    json acc = {{"bufferView", views.size() - 1},
                {"componentType", componentType},
                {"count", values.size() * sizeof(values[0]) / (components * 4)},
                {"type", type}};
    accessors.push_back(acc);
    return int(accessors.size() - 1);
  };
  for (const scene::Mesh& mesh : scene.meshes) {
    json prims = json::array();
    for (const scene::Primitive& p : mesh.primitives) {
      json attributes;
      const int pos = addView(p.positions, 3, 5126, "VEC3");
      glm::vec3 lo(1e30f), hi(-1e30f);
      for (const glm::vec3& v : p.positions) lo = glm::min(lo, v), hi = glm::max(hi, v);
      accessors[size_t(pos)]["min"] = {lo.x, lo.y, lo.z};
      accessors[size_t(pos)]["max"] = {hi.x, hi.y, hi.z};
      attributes["POSITION"] = pos;
      attributes["NORMAL"] = addView(p.normals, 3, 5126, "VEC3");
      if (!p.tangents.empty()) attributes["TANGENT"] = addView(p.tangents, 4, 5126, "VEC4");
      if (!p.uvs.empty()) attributes["TEXCOORD_0"] = addView(p.uvs, 2, 5126, "VEC2");
      if (!p.colors.empty()) attributes["COLOR_0"] = addView(p.colors, 4, 5126, "VEC4");
      json prim = {
          {"attributes", attributes}, {"indices", addView(p.indices, 1, 5125, "SCALAR")}, {"material", p.material}};
      prims.push_back(prim);
    }
    meshes.push_back({{"primitives", prims}});
  }
  json materials = json::array();
  for (const scene::Material& m : scene.materials)
    materials.push_back({{"pbrMetallicRoughness",
                          {{"baseColorFactor", {m.baseColor.r, m.baseColor.g, m.baseColor.b, m.baseColor.a}},
                           {"metallicFactor", m.metallic},
                           {"roughnessFactor", m.roughness}}},
                         {"emissiveFactor", {m.emissive.r, m.emissive.g, m.emissive.b}},
                         {"doubleSided", m.doubleSided}});
  json roots = json::array();
  for (const scene::Instance& inst : scene.instances) {
    json matrix = json::array();
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) matrix.push_back(inst.worldFromObject[c][r]);
    nodes.push_back({{"mesh", inst.mesh}, {"matrix", matrix}});
    roots.push_back(nodes.size() - 1);
  }
  // The camera node: the inverse of the view matrix (a glTF camera looks down its -Z).
  const glm::mat4 world = glm::inverse(glm::lookAt(camera.position, camera.target, camera.up));
  json cameraMatrix = json::array();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) cameraMatrix.push_back(world[c][r]);
  nodes.push_back({{"camera", 0}, {"matrix", cameraMatrix}});
  roots.push_back(nodes.size() - 1);
  json doc = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", roots}}}},
      {"nodes", nodes},
      {"meshes", meshes},
      {"materials", materials},
      {"cameras",
       {{{"type", "perspective"},
         {"perspective", {{"yfov", camera.yFov}, {"znear", camera.zNear}, {"zfar", camera.zFar}}}}}},
      {"accessors", accessors},
      {"bufferViews", views},
      {"buffers", {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}}}};
  std::ofstream(path) << doc.dump();
  return path;
}

}  // namespace rayster::test
