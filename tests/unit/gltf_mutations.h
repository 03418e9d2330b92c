#pragma once
// The glTF mutations of the validator cross-check (test_gltf_mutations.cpp): small valid files, each
// broken one way per schema check the loader makes, or bent into a valid edge case; the helpers
// that build them, and the two halves of the list.
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "gltf_test_util.h"

namespace rayster::test::mutation {

struct Mutation {
  std::string name;
  std::function<void(Doc&)> edit;
  // The JSON path Rayster's refusal names, or nullptr for a valid edge case it must load.
  const char* refusal;
  // An edit of the written JSON, for what Doc::gltf() writes itself (the buffers).
  std::function<void(Json&)> written = {};
  // Written as GLB: the JSON (after `written`) and the BIN chunk, which `bin` may edit.
  bool glb = false;
  std::function<void(std::vector<uint8_t>&)> bin = {};
};

// A GLB of `json` and `bin` (no BIN chunk when empty), chunks padded as the format asks.
inline std::string glbBytes(const Json& json, std::vector<uint8_t> bin) {
  std::string text = json.dump();
  while (text.size() % 4) text += ' ';
  while (bin.size() % 4) bin.push_back(0);
  std::string out = "glTF";
  auto u32 = [&](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  u32(2);
  u32(uint32_t(12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin.size())));
  u32(uint32_t(text.size()));
  u32(0x4E4F534A);
  out += text;
  if (!bin.empty()) {
    u32(uint32_t(bin.size()));
    u32(0x004E4942);
    out.append(reinterpret_cast<const char*>(bin.data()), bin.size());
  }
  return out;
}

inline void use(Doc& d, const std::string& extension) {
  Json& used = d.j["extensionsUsed"];
  for (const Json& e : used)
    if (e == extension) return;
  used.push_back(extension);
}

// The test quad with the POSITION bounds the validator requires.
inline Doc boundedQuad() {
  Doc d = quadDoc();
  d.j["accessors"][0]["min"] = {0.0, 0.0, 0.0};
  d.j["accessors"][0]["max"] = {1.0, 1.0, 0.0};
  return d;
}

// A new root node in the default scene; returns its index.
inline size_t addNode(Doc& d, Json node) {
  d.j["nodes"].push_back(std::move(node));
  const size_t n = d.j["nodes"].size() - 1;
  d.j["scenes"][0]["nodes"].push_back(n);
  return n;
}

inline void camera(Doc& d, Json c) {
  d.j["cameras"] = Json::array({std::move(c)});
  addNode(d, {{"camera", 0}});
}

inline Json perspective(Json p) { return {{"type", "perspective"}, {"perspective", std::move(p)}}; }
inline Json orthographic(Json o) { return {{"type", "orthographic"}, {"orthographic", std::move(o)}}; }

inline void light(Doc& d, Json l) {
  use(d, "KHR_lights_punctual");
  d.j["extensions"]["KHR_lights_punctual"]["lights"] = Json::array({std::move(l)});
  addNode(d, {{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
}

// Material 0 on the quad, with textures[0] (no source: valid) for its texture slots.
inline void material(Doc& d, Json m) {
  if (m.contains("extensions"))
    for (auto it = m["extensions"].begin(); it != m["extensions"].end(); ++it) use(d, it.key());
  d.j["materials"] = Json::array({std::move(m)});
  d.j["textures"] = Json::array({Json::object()});
  primitive(d)["material"] = 0;
}

inline void pbr(Doc& d, Json p) { material(d, {{"pbrMetallicRoughness", std::move(p)}}); }
inline void ext(Doc& d, const char* name, Json e) { material(d, {{"extensions", {{name, std::move(e)}}}}); }

// A float SCALAR accessor with its bounds (animation inputs need them).
inline int times(Doc& d, const std::vector<float>& t) {
  const int a = d.floats(t, "SCALAR", 1);
  d.j["accessors"][size_t(a)]["min"] = {*std::min_element(t.begin(), t.end())};
  d.j["accessors"][size_t(a)]["max"] = {*std::max_element(t.begin(), t.end())};
  return a;
}

// Node 0 moves along x over one second.
inline Json& animate(Doc& d) {
  const int input = times(d, {0, 1});
  const int output = d.floats({0, 0, 0, 1, 0, 0}, "VEC3", 3);
  d.j["animations"] = Json::array(
      {{{"samplers", Json::array({{{"input", input}, {"output", output}}})},
        {"channels", Json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}})}}});
  return d.j["animations"][0];
}

// The quad skinned to joint node 1 (a root); returns the skin's JSON.
inline Json& skin(Doc& d) {
  Json& attributes = primitive(d)["attributes"];
  attributes["JOINTS_0"] = d.accessor(d.view(std::vector<uint8_t>(16, 0)), kUByte, 4, "VEC4");
  attributes["WEIGHTS_0"] = d.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4", 4);
  const size_t joint = addNode(d, {{"name", "joint"}});
  d.node(0)["skin"] = 0;
  d.j["skins"] = Json::array({{{"joints", {joint}}}});
  return d.j["skins"][0];
}

inline int identityMatrices(Doc& d, size_t count) {
  std::vector<float> m;
  for (size_t i = 0; i < count; ++i)
    for (int k = 0; k < 16; ++k) m.push_back(k % 5 == 0 ? 1.0f : 0.0f);
  return d.floats(m, "MAT4", 16);
}

// A position accessor whose bounds fit its data.
inline int positions(Doc& d, const std::vector<float>& p) {
  const int a = d.floats(p, "VEC3", 3);
  Json lo = {p[0], p[1], p[2]}, hi = lo;
  for (size_t i = 0; i < p.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3].get<float>(), p[i]);
    hi[i % 3] = std::max(hi[i % 3].get<float>(), p[i]);
  }
  d.j["accessors"][size_t(a)]["min"] = lo;
  d.j["accessors"][size_t(a)]["max"] = hi;
  return a;
}

inline void sparse(Doc& d, const std::vector<uint16_t>& indices, const std::vector<float>& values) {
  d.j["accessors"][0]["sparse"] = {{"count", indices.size()},
                                   {"indices", {{"bufferView", d.view(indices)}, {"componentType", kUShort}}},
                                   {"values", {{"bufferView", d.view(values)}}}};
}

// Asset, extensions, buffers, buffer views, accessors and meshes (gltf_mutations_data.cpp).
std::vector<Mutation> dataMutations();
// Nodes, scenes, cameras, lights, materials, images, samplers, skins and animations
// (gltf_mutations_scene.cpp).
std::vector<Mutation> sceneMutations();

}  // namespace rayster::test::mutation
