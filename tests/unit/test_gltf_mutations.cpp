// The mutation cross-check against the Khronos glTF-Validator: small valid files, each broken one
// way per schema check the loader makes (and bent into valid edge cases the spec allows), written
// as .gltf and validated in one node call. Rayster must refuse exactly the files the validator
// reports errors in, with a message naming the JSON path, and load the rest, except for the
// differences gltf_validator_exceptions.h lists, each with its reason.
#include <cmath>
#include <functional>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "core/log.h"
#include "gltf_test_util.h"
#include "gltf_validator_exceptions.h"
#include "gltf_validator_util.h"

using namespace rayster;
using namespace rayster::test;

namespace {

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
std::string glbBytes(const Json& json, std::vector<uint8_t> bin) {
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

void use(Doc& d, const std::string& extension) {
  Json& used = d.j["extensionsUsed"];
  for (const Json& e : used)
    if (e == extension) return;
  used.push_back(extension);
}

// The test quad with the POSITION bounds the validator requires.
Doc boundedQuad() {
  Doc d = quadDoc();
  d.j["accessors"][0]["min"] = {0.0, 0.0, 0.0};
  d.j["accessors"][0]["max"] = {1.0, 1.0, 0.0};
  return d;
}

// A new root node in the default scene; returns its index.
size_t addNode(Doc& d, Json node) {
  d.j["nodes"].push_back(std::move(node));
  const size_t n = d.j["nodes"].size() - 1;
  d.j["scenes"][0]["nodes"].push_back(n);
  return n;
}

void camera(Doc& d, Json c) {
  d.j["cameras"] = Json::array({std::move(c)});
  addNode(d, {{"camera", 0}});
}

Json perspective(Json p) { return {{"type", "perspective"}, {"perspective", std::move(p)}}; }
Json orthographic(Json o) { return {{"type", "orthographic"}, {"orthographic", std::move(o)}}; }

void light(Doc& d, Json l) {
  use(d, "KHR_lights_punctual");
  d.j["extensions"]["KHR_lights_punctual"]["lights"] = Json::array({std::move(l)});
  addNode(d, {{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
}

// Material 0 on the quad, with textures[0] (no source: valid) for its texture slots.
void material(Doc& d, Json m) {
  if (m.contains("extensions"))
    for (auto it = m["extensions"].begin(); it != m["extensions"].end(); ++it) use(d, it.key());
  d.j["materials"] = Json::array({std::move(m)});
  d.j["textures"] = Json::array({Json::object()});
  primitive(d)["material"] = 0;
}

void pbr(Doc& d, Json p) { material(d, {{"pbrMetallicRoughness", std::move(p)}}); }
void ext(Doc& d, const char* name, Json e) { material(d, {{"extensions", {{name, std::move(e)}}}}); }

// A float SCALAR accessor with its bounds (animation inputs need them).
int times(Doc& d, const std::vector<float>& t) {
  const int a = d.floats(t, "SCALAR", 1);
  d.j["accessors"][size_t(a)]["min"] = {*std::min_element(t.begin(), t.end())};
  d.j["accessors"][size_t(a)]["max"] = {*std::max_element(t.begin(), t.end())};
  return a;
}

// Node 0 moves along x over one second.
Json& animate(Doc& d) {
  const int input = times(d, {0, 1});
  const int output = d.floats({0, 0, 0, 1, 0, 0}, "VEC3", 3);
  d.j["animations"] = Json::array(
      {{{"samplers", Json::array({{{"input", input}, {"output", output}}})},
        {"channels", Json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}})}}});
  return d.j["animations"][0];
}

// The quad skinned to joint node 1 (a root); returns the skin's JSON.
Json& skin(Doc& d) {
  Json& attributes = primitive(d)["attributes"];
  attributes["JOINTS_0"] = d.accessor(d.view(std::vector<uint8_t>(16, 0)), kUByte, 4, "VEC4");
  attributes["WEIGHTS_0"] = d.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4", 4);
  const size_t joint = addNode(d, {{"name", "joint"}});
  d.node(0)["skin"] = 0;
  d.j["skins"] = Json::array({{{"joints", {joint}}}});
  return d.j["skins"][0];
}

int identityMatrices(Doc& d, size_t count) {
  std::vector<float> m;
  for (size_t i = 0; i < count; ++i)
    for (int k = 0; k < 16; ++k) m.push_back(k % 5 == 0 ? 1.0f : 0.0f);
  return d.floats(m, "MAT4", 16);
}

// A position accessor whose bounds fit its data.
int positions(Doc& d, const std::vector<float>& p) {
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

void sparse(Doc& d, const std::vector<uint16_t>& indices, const std::vector<float>& values) {
  d.j["accessors"][0]["sparse"] = {{"count", indices.size()},
                                   {"indices", {{"bufferView", d.view(indices)}, {"componentType", kUShort}}},
                                   {"values", {{"bufferView", d.view(values)}}}};
}

std::vector<Mutation> mutations() {
  const double halfPi = std::acos(0.0);
  return {
      // Valid as they are.
      {"the bounded quad", [](Doc&) {}, nullptr},
      {"asset version 2.1", [](Doc& d) { d.j["asset"]["version"] = "2.1"; }, nullptr},
      // asset, extensions, top level
      {"asset version 3.0", [](Doc& d) { d.j["asset"]["version"] = "3.0"; }, "asset.version"},
      {"asset version 2", [](Doc& d) { d.j["asset"]["version"] = "2"; }, "asset.version"},
      {"minVersion above version", [](Doc& d) { d.j["asset"]["minVersion"] = "2.1"; }, "asset.minVersion"},
      {"asset without version", [](Doc& d) { d.j["asset"].erase("version"); }, "asset"},
      {"extensionsRequired not used",
       [](Doc& d) {
         use(d, "KHR_materials_unlit");
         d.j["extensionsRequired"] = {"KHR_materials_ior"};
       },
       "extensionsRequired[0]"},
      {"extensionsUsed twice",
       [](Doc& d) {
         d.j["extensionsUsed"] = {"KHR_materials_ior", "KHR_materials_ior"};
       },
       "extensionsUsed[1]"},
      {"extensionsUsed empty", [](Doc& d) { d.j["extensionsUsed"] = Json::array(); }, "extensionsUsed"},
      {"an unknown extension used", [](Doc& d) { use(d, "FOO_bar"); }, nullptr},
      {"requires an unknown extension",
       [](Doc& d) {
         use(d, "FOO_bar");
         d.j["extensionsRequired"] = {"FOO_bar"};
       },
       nullptr},
      {"scene out of range", [](Doc& d) { d.j["scene"] = 3; }, "scene"},
      {"samplers empty", [](Doc& d) { d.j["samplers"] = Json::array(); }, "samplers"},
      // buffers
      {"buffer byteLength 0", [](Doc&) {}, "buffers[1].byteLength",
       [](Json& j) {
         j["buffers"].push_back({{"byteLength", 0}, {"uri", "data:application/octet-stream;base64,AAAA"}});
       }},
      {"buffer without byteLength", [](Doc&) {}, "buffers[0]", [](Json& j) { j["buffers"][0].erase("byteLength"); }},
      {"data URI of the wrong media type", [](Doc&) {}, "buffers[0].uri",
       [](Json& j) {
         std::string uri = j["buffers"][0]["uri"];
         j["buffers"][0]["uri"] = "data:text/plain" + uri.substr(uri.find(';'));
       }},
      {"data URI shorter than byteLength", [](Doc&) {}, "buffers[0].byteLength",
       [](Json& j) { j["buffers"][0]["byteLength"] = j["buffers"][0]["byteLength"].get<int>() + 4; }},
      {"a GLB", [](Doc&) {}, nullptr, {}, true},
      {"a GLB without its BIN chunk", [](Doc&) {}, "buffers[0]", {}, true, [](std::vector<uint8_t>& b) { b.clear(); }},
      {"a GLB BIN chunk shorter than byteLength",
       [](Doc&) {},
       "buffers[0].byteLength",
       {},
       true,
       [](std::vector<uint8_t>& b) { b.resize(b.size() - 16); }},
      {"gltf-buffer data URI", [](Doc&) {}, nullptr,
       [](Json& j) {
         std::string uri = j["buffers"][0]["uri"];
         j["buffers"][0]["uri"] = "data:application/gltf-buffer" + uri.substr(uri.find(';'));
       }},
      // buffer views
      {"bufferView buffer out of range", [](Doc& d) { d.j["bufferViews"][2]["buffer"] = 5; }, "bufferViews[2].buffer"},
      {"bufferView byteLength 0", [](Doc& d) { d.j["bufferViews"][2]["byteLength"] = 0; }, "bufferViews[2].byteLength"},
      {"bufferView past its buffer", [](Doc& d) { d.j["bufferViews"][3]["byteLength"] = 64; }, "bufferViews[3]"},
      {"byteStride 2", [](Doc& d) { d.j["bufferViews"][0]["byteStride"] = 2; }, "bufferViews[0].byteStride"},
      {"byteStride 14", [](Doc& d) { d.j["bufferViews"][0]["byteStride"] = 14; }, "bufferViews[0].byteStride"},
      {"byteStride 256", [](Doc& d) { d.j["bufferViews"][0]["byteStride"] = 256; }, "bufferViews[0].byteStride"},
      {"byteStride above byteLength", [](Doc& d) { d.j["bufferViews"][2]["byteStride"] = 48; },
       "bufferViews[2].byteStride"},
      {"byteStride 12 on positions", [](Doc& d) { d.j["bufferViews"][0]["byteStride"] = 12; }, nullptr},
      {"unknown bufferView target", [](Doc& d) { d.j["bufferViews"][0]["target"] = 1234; }, nullptr},
      // accessors
      {"accessor count 0", [](Doc& d) { d.j["accessors"][2]["count"] = 0; }, "accessors[2].count"},
      {"accessor without componentType", [](Doc& d) { d.j["accessors"][2].erase("componentType"); }, "accessors[2]"},
      {"accessor without type", [](Doc& d) { d.j["accessors"][2].erase("type"); }, "accessors[2]"},
      {"accessor bufferView out of range", [](Doc& d) { d.j["accessors"][2]["bufferView"] = 9; },
       "accessors[2].bufferView"},
      {"accessor byteOffset not a multiple of the component",
       [](Doc& d) {
         d.j["accessors"][2]["byteOffset"] = 2;
         d.j["accessors"][2]["count"] = 3;
       },
       "accessors[2].byteOffset"},
      {"accessor byteOffset without bufferView",
       [](Doc& d) {
         d.j["accessors"].push_back({{"componentType", kFloat}, {"count", 1}, {"type", "SCALAR"}, {"byteOffset", 4}});
       },
       "accessors[4].byteOffset"},
      {"normalized float accessor", [](Doc& d) { d.j["accessors"][1]["normalized"] = true; },
       "accessors[1].normalized"},
      {"accessor past its bufferView", [](Doc& d) { d.j["accessors"][2]["count"] = 5; }, "accessors[2]"},
      {"min with 2 numbers for VEC3",
       [](Doc& d) {
         d.j["accessors"][0]["min"] = {0.0, 0.0};
       },
       "accessors[0].min"},
      {"max contradicting the data",
       [](Doc& d) {
         d.j["accessors"][0]["max"] = {0.5, 1.0, 0.0};
       },
       "accessors[0].max[0]"},
      {"min looser than the data",
       [](Doc& d) {
         d.j["accessors"][0]["min"] = {-1.0, 0.0, 0.0};
       },
       "accessors[0].min[0]"},
      {"max rounded below the data",
       [](Doc& d) {
         d.j["accessors"][0]["max"] = {0.9999999, 1.0, 0.0};
       },
       "accessors[0].max[0]"},
      {"max rounded to the same float",
       [](Doc& d) {
         d.j["accessors"][0]["max"] = {1.00000001, 1.0, 0.0};
       },
       nullptr},
      {"normals with exact bounds",
       [](Doc& d) {
         d.j["accessors"][1]["min"] = {0.0, 0.0, 1.0};
         d.j["accessors"][1]["max"] = {0.0, 0.0, 1.0};
       },
       nullptr},
      {"index bounds contradicting the data",
       [](Doc& d) {
         d.j["accessors"][3]["min"] = {1};
         d.j["accessors"][3]["max"] = {3};
       },
       "accessors[3].min[0]"},
      {"POSITION without min/max", [](Doc& d) { d.j["accessors"][0].erase("min"), d.j["accessors"][0].erase("max"); },
       nullptr},
      {"unknown componentType on an unused accessor",
       [](Doc& d) {
         d.j["accessors"].push_back({{"componentType", 5124}, {"count", 1}, {"type", "SCALAR"}});
       },
       nullptr},
      {"unused accessor without bufferView",
       [](Doc& d) {
         d.j["accessors"].push_back({{"componentType", kFloat}, {"count", 3}, {"type", "VEC2"}});
       },
       nullptr},
      {"a NaN normal",
       [](Doc& d) {
         primitive(d)["attributes"]["NORMAL"] = d.floats({0, 0, 1, 0, 0, 1, NAN, 0, 1, 0, 0, 1}, "VEC3", 3);
       },
       "accessors[4]"},
      {"sparse positions",
       [](Doc& d) {
         sparse(d, {2}, {1, 1, 0.5f});
         d.j["accessors"][0]["max"] = {1.0, 1.0, 0.5};
       },
       nullptr},
      {"sparse count above the count",
       [](Doc& d) {
         sparse(d, {0, 1, 2, 3, 3}, std::vector<float>(15, 0.0f));
       },
       "accessors[0].sparse.count"},
      {"sparse indices of float type",
       [](Doc& d) {
         sparse(d, {2}, {1, 1, 0});
         d.j["accessors"][0]["sparse"]["indices"]["componentType"] = kFloat;
       },
       "accessors[0].sparse.indices.componentType"},
      {"sparse indices not increasing",
       [](Doc& d) {
         sparse(d, {2, 1}, {1, 1, 0, 1, 0, 0});
       },
       "accessors[0].sparse.indices"},
      {"sparse index past the count",
       [](Doc& d) {
         sparse(d, {1, 9}, {1, 0, 0, 1, 1, 0});
       },
       "accessors[0].sparse.indices"},
      {"sparse values bufferView out of range",
       [](Doc& d) {
         sparse(d, {2}, {1, 1, 0});
         d.j["accessors"][0]["sparse"]["values"]["bufferView"] = 40;
       },
       "accessors[0].sparse.values.bufferView"},
      // meshes
      {"primitives empty", [](Doc& d) { d.j["meshes"][0]["primitives"] = Json::array(); }, "meshes[0].primitives"},
      {"attributes empty", [](Doc& d) { primitive(d)["attributes"] = Json::object(); },
       "meshes[0].primitives[0].attributes"},
      {"mode 7", [](Doc& d) { primitive(d)["mode"] = 7; }, "meshes[0].primitives[0].mode"},
      {"points", [](Doc& d) { primitive(d)["mode"] = 0; }, nullptr},
      {"triangle strip", [](Doc& d) { primitive(d)["mode"] = 5; }, nullptr},
      {"an attribute glTF does not name", [](Doc& d) { primitive(d)["attributes"]["FOO"] = 2; },
       "meshes[0].primitives[0].attributes.FOO"},
      {"an application-specific attribute", [](Doc& d) { primitive(d)["attributes"]["_TEMPERATURE"] = 2; }, nullptr},
      {"TEXCOORD_1 without TEXCOORD_0",
       [](Doc& d) {
         Json& a = primitive(d)["attributes"];
         a["TEXCOORD_1"] = a["TEXCOORD_0"];
         a.erase("TEXCOORD_0");
       },
       "meshes[0].primitives[0].attributes"},
      {"NORMAL of type VEC2", [](Doc& d) { primitive(d)["attributes"]["NORMAL"] = 2; },
       "meshes[0].primitives[0].attributes.NORMAL"},
      {"TEXCOORD_0 shorter than POSITION", [](Doc& d) { d.j["accessors"][2]["count"] = 3; },
       "meshes[0].primitives[0].attributes.TEXCOORD_0"},
      {"float indices", [](Doc& d) { primitive(d)["indices"] = 2; }, "meshes[0].primitives[0].indices"},
      {"indices out of range", [](Doc& d) { primitive(d)["indices"] = 9; }, "meshes[0].primitives[0].indices"},
      {"material out of range", [](Doc& d) { primitive(d)["material"] = 3; }, "meshes[0].primitives[0].material"},
      {"an index past the vertices",
       [](Doc& d) {
         primitive(d)["indices"] = d.accessor(d.view(std::vector<uint16_t>{0, 1, 4}), kUShort, 3, "SCALAR");
       },
       "meshes[0].primitives[0].indices"},
      {"the primitive restart index",
       [](Doc& d) {
         primitive(d)["indices"] = d.accessor(d.view(std::vector<uint16_t>{0, 1, 65535}), kUShort, 3, "SCALAR");
       },
       "meshes[0].primitives[0].indices"},
      {"a primitive without POSITION", [](Doc& d) { primitive(d)["attributes"].erase("POSITION"); }, nullptr},
      {"a primitive without indices, 4 vertices", [](Doc& d) { primitive(d).erase("indices"); }, nullptr},
      {"mesh weights without targets", [](Doc& d) { d.j["meshes"][0]["weights"] = {0.5}; }, "meshes[0].weights"},
      {"a morph target",
       [](Doc& d) {
         primitive(d)["targets"] = {{{"POSITION", positions(d, std::vector<float>(12, 0.0f))}}};
         d.j["meshes"][0]["weights"] = {0.5};
       },
       nullptr},
      {"a morph target of the wrong count",
       [](Doc& d) {
         primitive(d)["targets"] = {{{"POSITION", positions(d, std::vector<float>(9, 0.0f))}}};
       },
       "meshes[0].primitives[0].targets[0].POSITION"},
      {"two attributes in one bufferView without byteStride", [](Doc& d) { d.j["accessors"][2]["bufferView"] = 1; },
       "bufferViews[1]"},
      {"two meshes' positions in one bufferView without byteStride",
       [](Doc& d) {
         d.j["accessors"].push_back({{"bufferView", 0},
                                     {"byteOffset", 12},
                                     {"componentType", kFloat},
                                     {"count", 3},
                                     {"type", "VEC3"},
                                     {"min", {0.0, 0.0, 0.0}},
                                     {"max", {1.0, 1.0, 0.0}}});
         d.j["meshes"].push_back({{"primitives", Json::array({{{"attributes", {{"POSITION", 4}}}}})}});
         addNode(d, {{"mesh", 1}});
       },
       "bufferViews[0]"},
      {"two meshes' positions in one bufferView with byteStride",
       [](Doc& d) {
         d.j["bufferViews"][0]["byteStride"] = 12;
         d.j["accessors"].push_back({{"bufferView", 0},
                                     {"byteOffset", 12},
                                     {"componentType", kFloat},
                                     {"count", 3},
                                     {"type", "VEC3"},
                                     {"min", {0.0, 0.0, 0.0}},
                                     {"max", {1.0, 1.0, 0.0}}});
         d.j["meshes"].push_back({{"primitives", Json::array({{{"attributes", {{"POSITION", 4}}}}})}});
         addNode(d, {{"mesh", 1}});
       },
       nullptr},
      {"an unknown extension's texture reading TEXCOORD_1",
       [](Doc& d) {
         ext(d, "EXT_something", {{"glowTexture", {{"index", 0}, {"texCoord", 1}}}});
       },
       nullptr},
      {"a clearcoat normal map without tangents or normal map",
       [](Doc& d) {
         ext(d, "KHR_materials_clearcoat", {{"clearcoatNormalTexture", {{"index", 0}}}});
       },
       "meshes[0].primitives[0].material"},
      {"anisotropy without tangents or normal map", [](Doc& d) { ext(d, "KHR_materials_anisotropy", Json::object()); },
       nullptr},
      {"a clearcoat normal map with a normal map",
       [](Doc& d) {
         ext(d, "KHR_materials_clearcoat", {{"clearcoatNormalTexture", {{"index", 0}}}});
         d.j["materials"][0]["normalTexture"] = {{"index", 0}};
       },
       nullptr},
      {"a texture reading a missing TEXCOORD_1",
       [](Doc& d) {
         material(d, {{"emissiveTexture", {{"index", 0}, {"texCoord", 1}}}});
       },
       "meshes[0].primitives[0].material"},
      // nodes
      {"matrix with 15 numbers", [](Doc& d) { d.node(0)["matrix"] = Json(std::vector<double>(15, 0.0)); },
       "nodes[0].matrix"},
      {"matrix with 17 numbers", [](Doc& d) { d.node(0)["matrix"] = Json(std::vector<double>(17, 0.0)); },
       "nodes[0].matrix"},
      {"translation with 2 numbers",
       [](Doc& d) {
         d.node(0)["translation"] = {1, 2};
       },
       "nodes[0].translation"},
      {"scale with 4 numbers",
       [](Doc& d) {
         d.node(0)["scale"] = {1, 1, 1, 1};
       },
       "nodes[0].scale"},
      {"rotation of length 0.9",
       [](Doc& d) {
         d.node(0)["rotation"] = {0, 0, 0, 0.9};
       },
       "nodes[0].rotation"},
      {"rotation of length 0.99",
       [](Doc& d) {
         d.node(0)["rotation"] = {0, 0, 0, 0.99};
       },
       "nodes[0].rotation"},
      {"rotation within the tolerance",
       [](Doc& d) {
         d.node(0)["rotation"] = {0, 0, 0, 0.995};
       },
       nullptr},
      {"rotation component above 1",
       [](Doc& d) {
         d.node(0)["rotation"] = {0, 0, 0, 1.001};
       },
       "nodes[0].rotation[3]"},
      {"matrix and scale",
       [](Doc& d) {
         d.node(0)["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
         d.node(0)["scale"] = {1, 1, 1};
       },
       "nodes[0]"},
      {"a projective matrix", [](Doc& d) { d.node(0)["matrix"] = {1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; },
       "nodes[0].matrix"},
      {"a matrix of scale 0", [](Doc& d) { d.node(0)["matrix"] = {0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; },
       "nodes[0].matrix"},
      {"a sheared matrix", [](Doc& d) { d.node(0)["matrix"] = {1, 0, 0, 0, 0.01, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; },
       "nodes[0].matrix"},
      {"a matrix with a shear of 1e-4",
       [](Doc& d) { d.node(0)["matrix"] = {1, 0, 0, 0, 0.0001, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }, nullptr},
      {"a mirroring, rotating and scaling matrix",
       [](Doc& d) { d.node(0)["matrix"] = {0, -3, 0, 0, 2, 0, 0, 0, 0, 0, -1, 0, 5, 6, 7, 1}; }, nullptr},
      {"a translating matrix", [](Doc& d) { d.node(0)["matrix"] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 1, 2, 3, 1}; },
       nullptr},
      {"node mesh out of range", [](Doc& d) { d.node(0)["mesh"] = 5; }, "nodes[0].mesh"},
      {"node camera out of range", [](Doc& d) { d.node(0)["camera"] = 2; }, "nodes[0].camera"},
      {"a node that is its own child", [](Doc& d) { d.node(0)["children"] = {0}; }, "nodes[0].children[0]"},
      {"a cycle of children",
       [](Doc& d) {
         d.j["nodes"].push_back({{"children", {2}}});
         d.j["nodes"].push_back({{"children", {1}}});
       },
       "nodes[1]"},
      {"a node with two parents",
       [](Doc& d) {
         d.j["nodes"].push_back({{"children", {3}}});
         d.j["nodes"].push_back({{"children", {3}}});
         d.j["nodes"].push_back(Json::object());
       },
       "nodes[2].children[0]"},
      {"children empty", [](Doc& d) { d.node(0)["children"] = Json::array(); }, "nodes[0].children"},
      {"a child listed twice",
       [](Doc& d) {
         d.j["nodes"].push_back(Json::object());
         d.node(0)["children"] = {1, 1};
       },
       "nodes[0].children[1]"},
      {"a scene listing a child",
       [](Doc& d) {
         d.j["nodes"].push_back(Json::object());
         d.node(0)["children"] = {1};
         d.j["scenes"][0]["nodes"].push_back(1);
       },
       "scenes[0].nodes[1]"},
      {"scene nodes empty", [](Doc& d) { d.j["scenes"][0]["nodes"] = Json::array(); }, "scenes[0].nodes"},
      {"scene node out of range", [](Doc& d) { d.j["scenes"][0]["nodes"] = {7}; }, "scenes[0].nodes[0]"},
      {"another scene without nodes", [](Doc& d) { d.j["scenes"].push_back(Json::object()); }, nullptr},
      {"a node with no mesh",
       [](Doc& d) {
         addNode(d, {{"name", "empty"}});
       },
       nullptr},
      {"node weights without morph targets", [](Doc& d) { d.node(0)["weights"] = {1.0}; }, "nodes[0].weights"},
      // cameras
      {"a perspective camera",
       [](Doc& d) {
         camera(d, perspective({{"yfov", 0.8}, {"znear", 0.1}}));
       },
       nullptr},
      {"a perspective camera with zfar and aspect ratio",
       [](Doc& d) {
         camera(d, perspective({{"yfov", 0.8}, {"znear", 0.1}, {"zfar", 100}, {"aspectRatio", 1.5}}));
       },
       nullptr},
      {"yfov above pi",
       [](Doc& d) {
         camera(d, perspective({{"yfov", 4.0}, {"znear", 0.1}}));
       },
       nullptr},
      {"yfov 0",
       [](Doc& d) {
         camera(d, perspective({{"yfov", 0.0}, {"znear", 0.1}}));
       },
       "cameras[0].perspective.yfov"},
      {"znear 0",
       [](Doc& d) {
         camera(d, perspective({{"yfov", 0.8}, {"znear", 0.0}}));
       },
       "cameras[0].perspective.znear"},
      {"zfar before znear",
       [](Doc& d) {
         camera(d, perspective({{"yfov", 0.8}, {"znear", 1.0}, {"zfar", 0.5}}));
       },
       "cameras[0].perspective.zfar"},
      {"aspectRatio 0",
       [](Doc& d) {
         camera(d, perspective({{"yfov", 0.8}, {"znear", 0.1}, {"aspectRatio", 0}}));
       },
       "cameras[0].perspective.aspectRatio"},
      {"perspective camera without perspective",
       [](Doc& d) {
         camera(d, {{"type", "perspective"}});
       },
       "cameras[0]"},
      {"a camera both perspective and orthographic",
       [](Doc& d) {
         Json c = perspective({{"yfov", 0.8}, {"znear", 0.1}});
         c["orthographic"] = {{"xmag", 1}, {"ymag", 1}, {"znear", 0}, {"zfar", 1}};
         camera(d, c);
       },
       "cameras[0]"},
      {"an unknown camera type",
       [](Doc& d) {
         Json c = perspective({{"yfov", 0.8}, {"znear", 0.1}});
         c["type"] = "fisheye";
         camera(d, c);
       },
       nullptr},
      {"an orthographic camera",
       [](Doc& d) {
         camera(d, orthographic({{"xmag", 1}, {"ymag", 1}, {"znear", 0}, {"zfar", 10}}));
       },
       nullptr},
      {"orthographic xmag 0",
       [](Doc& d) {
         camera(d, orthographic({{"xmag", 0}, {"ymag", 1}, {"znear", 0}, {"zfar", 10}}));
       },
       "cameras[0].orthographic.xmag"},
      {"orthographic znear -1",
       [](Doc& d) {
         camera(d, orthographic({{"xmag", 1}, {"ymag", 1}, {"znear", -1}, {"zfar", 10}}));
       },
       "cameras[0].orthographic.znear"},
      {"orthographic zfar at znear",
       [](Doc& d) {
         camera(d, orthographic({{"xmag", 1}, {"ymag", 1}, {"znear", 2}, {"zfar", 2}}));
       },
       "cameras[0].orthographic.zfar"},
      // KHR_lights_punctual
      {"a spot light",
       [&](Doc& d) {
         light(d, {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.0}, {"outerConeAngle", halfPi}}}});
       },
       nullptr},
      {"a light type glTF does not define",
       [](Doc& d) {
         light(d, {{"type", "area"}});
       },
       nullptr},
      {"light not in extensionsUsed",
       [](Doc& d) {
         light(d, {{"type", "point"}});
         d.j.erase("extensionsUsed");
       },
       nullptr},
      {"light without type", [](Doc& d) { light(d, Json::object()); }, "extensions.KHR_lights_punctual.lights[0]"},
      {"negative intensity",
       [](Doc& d) {
         light(d, {{"type", "point"}, {"intensity", -1}});
       },
       "KHR_lights_punctual.lights[0].intensity"},
      {"range 0",
       [](Doc& d) {
         light(d, {{"type", "point"}, {"range", 0}});
       },
       "KHR_lights_punctual.lights[0].range"},
      {"light colour above 1",
       [](Doc& d) {
         light(d, {{"type", "point"}, {"color", {2, 0, 0}}});
       },
       "KHR_lights_punctual.lights[0].color[0]"},
      {"spot outer below inner",
       [](Doc& d) {
         light(d, {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.6}, {"outerConeAngle", 0.4}}}});
       },
       "lights[0].spot.outerConeAngle"},
      {"spot outer equal to inner",
       [](Doc& d) {
         light(d, {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.4}, {"outerConeAngle", 0.4}}}});
       },
       "lights[0].spot.outerConeAngle"},
      {"spot outer above pi/2",
       [](Doc& d) {
         light(d, {{"type", "spot"}, {"spot", {{"outerConeAngle", 2.0}}}});
       },
       "lights[0].spot.outerConeAngle"},
      {"spot inner negative",
       [](Doc& d) {
         light(d, {{"type", "spot"}, {"spot", {{"innerConeAngle", -0.1}}}});
       },
       "lights[0].spot.innerConeAngle"},
      {"spot light without spot",
       [](Doc& d) {
         light(d, {{"type", "spot"}});
       },
       "lights[0]"},
      {"node light out of range",
       [](Doc& d) {
         light(d, {{"type", "point"}});
         d.j["nodes"].back()["extensions"]["KHR_lights_punctual"]["light"] = 3;
       },
       "extensions.KHR_lights_punctual.light"},
      // materials
      {"a material with factors at their limits",
       [](Doc& d) {
         material(d, {{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 0}}, {"metallicFactor", 0}}},
                      {"emissiveFactor", {1, 1, 1}},
                      {"alphaMode", "MASK"},
                      {"alphaCutoff", 0}});
       },
       nullptr},
      {"metallicFactor 2",
       [](Doc& d) {
         pbr(d, {{"metallicFactor", 2}});
       },
       "materials[0].pbrMetallicRoughness.metallicFactor"},
      {"roughnessFactor -0.1",
       [](Doc& d) {
         pbr(d, {{"roughnessFactor", -0.1}});
       },
       "materials[0].pbrMetallicRoughness.roughnessFactor"},
      {"baseColorFactor with 3 numbers",
       [](Doc& d) {
         pbr(d, {{"baseColorFactor", {1, 1, 1}}});
       },
       "materials[0].pbrMetallicRoughness.baseColorFactor"},
      {"baseColorFactor 1.5",
       [](Doc& d) {
         pbr(d, {{"baseColorFactor", {1.5, 1, 1, 1}}});
       },
       "materials[0].pbrMetallicRoughness.baseColorFactor[0]"},
      {"emissiveFactor 2",
       [](Doc& d) {
         material(d, {{"emissiveFactor", {2, 0, 0}}});
       },
       "materials[0].emissiveFactor[0]"},
      {"alphaCutoff -1",
       [](Doc& d) {
         material(d, {{"alphaMode", "MASK"}, {"alphaCutoff", -1}});
       },
       "materials[0].alphaCutoff"},
      {"an alphaMode glTF does not define",
       [](Doc& d) {
         material(d, {{"alphaMode", "DITHER"}});
       },
       nullptr},
      {"a texture index out of range",
       [](Doc& d) {
         material(d, {{"emissiveTexture", {{"index", 4}}}});
       },
       "materials[0].emissiveTexture.index"},
      {"a texture without index",
       [](Doc& d) {
         material(d, {{"emissiveTexture", Json::object()}});
       },
       "materials[0].emissiveTexture"},
      {"texCoord -1",
       [](Doc& d) {
         material(d, {{"emissiveTexture", {{"index", 0}, {"texCoord", -1}}}});
       },
       "materials[0].emissiveTexture.texCoord"},
      {"occlusion strength 2",
       [](Doc& d) {
         material(d, {{"occlusionTexture", {{"index", 0}, {"strength", 2}}}});
       },
       "materials[0].occlusionTexture.strength"},
      {"a texture without source",
       [](Doc& d) {
         material(d, {{"emissiveTexture", {{"index", 0}}}});
       },
       nullptr},
      {"emissiveStrength -1",
       [](Doc& d) {
         ext(d, "KHR_materials_emissive_strength", {{"emissiveStrength", -1}});
         d.j["materials"][0]["emissiveFactor"] = {1, 1, 1};
       },
       "KHR_materials_emissive_strength.emissiveStrength"},
      {"ior 0.5",
       [](Doc& d) {
         ext(d, "KHR_materials_ior", {{"ior", 0.5}});
       },
       "KHR_materials_ior.ior"},
      {"ior 0",
       [](Doc& d) {
         ext(d, "KHR_materials_ior", {{"ior", 0}});
       },
       nullptr},
      {"transmissionFactor 2",
       [](Doc& d) {
         ext(d, "KHR_materials_transmission", {{"transmissionFactor", 2}});
       },
       "KHR_materials_transmission.transmissionFactor"},
      {"volume thickness -1",
       [](Doc& d) {
         material(
             d,
             {{"extensions",
               {{"KHR_materials_transmission", Json::object()}, {"KHR_materials_volume", {{"thicknessFactor", -1}}}}}});
       },
       "KHR_materials_volume.thicknessFactor"},
      {"volume attenuationDistance 0",
       [](Doc& d) {
         material(d, {{"extensions",
                       {{"KHR_materials_transmission", Json::object()},
                        {"KHR_materials_volume", {{"attenuationDistance", 0}}}}}});
       },
       "KHR_materials_volume.attenuationDistance"},
      {"volume attenuationColor 2",
       [](Doc& d) {
         material(d, {{"extensions",
                       {{"KHR_materials_transmission", Json::object()},
                        {"KHR_materials_volume", {{"attenuationColor", {2, 1, 1}}}}}}});
       },
       "KHR_materials_volume.attenuationColor[0]"},
      {"specularFactor 2",
       [](Doc& d) {
         ext(d, "KHR_materials_specular", {{"specularFactor", 2}});
       },
       "KHR_materials_specular.specularFactor"},
      {"specularColorFactor 2",
       [](Doc& d) {
         ext(d, "KHR_materials_specular", {{"specularColorFactor", {2, 1, 1}}});
       },
       nullptr},
      {"clearcoatFactor 2",
       [](Doc& d) {
         ext(d, "KHR_materials_clearcoat", {{"clearcoatFactor", 2}});
       },
       "KHR_materials_clearcoat.clearcoatFactor"},
      {"sheenRoughnessFactor 2",
       [](Doc& d) {
         ext(d, "KHR_materials_sheen", {{"sheenRoughnessFactor", 2}});
       },
       "KHR_materials_sheen.sheenRoughnessFactor"},
      {"iridescenceIor 0.5",
       [](Doc& d) {
         ext(d, "KHR_materials_iridescence", {{"iridescenceIor", 0.5}});
       },
       "KHR_materials_iridescence.iridescenceIor"},
      {"anisotropyStrength 2",
       [](Doc& d) {
         ext(d, "KHR_materials_anisotropy", {{"anisotropyStrength", 2}});
       },
       "KHR_materials_anisotropy.anisotropyStrength"},
      {"an extension texture out of range",
       [](Doc& d) {
         ext(d, "KHR_materials_specular", {{"specularTexture", {{"index", 3}}}});
       },
       "KHR_materials_specular.specularTexture.index"},
      {"texture transform scale with 1 number",
       [](Doc& d) {
         material(d,
                  {{"emissiveTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"scale", {2}}}}}}}}});
         use(d, "KHR_texture_transform");
       },
       "KHR_texture_transform.scale"},
      // images, samplers, textures
      {"an image with uri and bufferView",
       [](Doc& d) {
         d.j["images"] = Json::array(
             {{{"uri", "a.png"}, {"bufferView", d.view(std::vector<uint8_t>(16, 7))}, {"mimeType", "image/png"}}});
       },
       "images[0]"},
      {"an image with neither uri nor bufferView", [](Doc& d) { d.j["images"] = Json::array({Json::object()}); },
       "images[0]"},
      {"an image bufferView without mimeType",
       [](Doc& d) {
         d.j["images"] = Json::array({{{"bufferView", d.view(std::vector<uint8_t>(16, 7))}}});
       },
       "images[0].bufferView"},
      {"an image in a bufferView with byteStride",
       [](Doc& d) {
         d.j["images"] =
             Json::array({{{"bufferView", d.view(std::vector<uint8_t>(16, 7), 4)}, {"mimeType", "image/png"}}});
       },
       "images[0].bufferView"},
      {"an unused image in a bufferView",
       [](Doc& d) {
         d.j["images"] =
             Json::array({{{"bufferView", d.view(std::vector<uint8_t>(16, 7))}, {"mimeType", "image/png"}}});
       },
       nullptr},
      {"texture source out of range",
       [](Doc& d) {
         d.j["textures"] = Json::array({{{"source", 3}}});
       },
       "textures[0].source"},
      {"texture sampler out of range",
       [](Doc& d) {
         d.j["textures"] = Json::array({{{"sampler", 3}}});
       },
       "textures[0].sampler"},
      {"sampler wrapS 12345",
       [](Doc& d) {
         d.j["samplers"] = Json::array({{{"wrapS", 12345}}});
         d.j["textures"] = Json::array({{{"sampler", 0}}});
       },
       nullptr},
      {"sampler magFilter 9984",
       [](Doc& d) {
         d.j["samplers"] = Json::array({{{"magFilter", 9984}}});
         d.j["textures"] = Json::array({{{"sampler", 0}}});
       },
       nullptr},
      // skins
      {"a skin", [](Doc& d) { skin(d); }, nullptr},
      {"a skin with inverse bind matrices", [](Doc& d) { skin(d)["inverseBindMatrices"] = identityMatrices(d, 1); },
       nullptr},
      {"skin joints empty", [](Doc& d) { skin(d)["joints"] = Json::array(); }, "skins[0].joints"},
      {"skin joint out of range", [](Doc& d) { skin(d)["joints"] = {9}; }, "skins[0].joints[0]"},
      {"inverse bind matrices of type VEC4",
       [](Doc& d) { skin(d)["inverseBindMatrices"] = d.floats(std::vector<float>(4, 1.0f), "VEC4", 4); },
       "skins[0].inverseBindMatrices"},
      {"fewer inverse bind matrices than joints",
       [](Doc& d) {
         Json& s = skin(d);
         d.j["nodes"][1]["children"] = {2};
         d.j["nodes"].push_back({{"name", "joint2"}});
         s["joints"] = {1, 2};
         s["inverseBindMatrices"] = identityMatrices(d, 1);
       },
       "skins[0].inverseBindMatrices"},
      {"joints without a common root",
       [](Doc& d) {
         Json& s = skin(d);
         const size_t other = addNode(d, {{"name", "joint2"}});
         s["joints"] = {1, other};
       },
       "skins[0].joints[1]"},
      {"a skeleton that is no ancestor", [](Doc& d) { skin(d)["skeleton"] = 0; }, "skins[0].skeleton"},
      {"a skin on a node without mesh",
       [](Doc& d) {
         skin(d);
         addNode(d, {{"skin", 0}});
       },
       "nodes[2].skin"},
      {"a skin on a mesh without joints",
       [](Doc& d) {
         const size_t joint = addNode(d, {{"name", "joint"}});
         d.j["skins"] = Json::array({{{"joints", {joint}}}});
         d.node(0)["skin"] = 0;
       },
       "nodes[0].skin"},
      // animations
      {"an animation", [](Doc& d) { animate(d); }, nullptr},
      {"a STEP animation", [](Doc& d) { animate(d)["samplers"][0]["interpolation"] = "STEP"; }, nullptr},
      {"an interpolation glTF does not define", [](Doc& d) { animate(d)["samplers"][0]["interpolation"] = "SMOOTH"; },
       nullptr},
      {"a channel without node", [](Doc& d) { animate(d)["channels"][0]["target"].erase("node"); }, nullptr},
      {"an animation without channels", [](Doc& d) { animate(d).erase("channels"); }, "animations[0]"},
      {"a channel sampler out of range", [](Doc& d) { animate(d)["channels"][0]["sampler"] = 3; },
       "animations[0].channels[0].sampler"},
      {"a sampler input out of range", [](Doc& d) { animate(d)["samplers"][0]["input"] = 30; },
       "animations[0].samplers[0].input"},
      {"key times of type VEC3",
       [](Doc& d) {
         animate(d)["samplers"][0]["input"] = d.floats({0, 0, 0, 1, 1, 1}, "VEC3", 3);
       },
       "animations[0].samplers[0].input"},
      {"key times without min/max",
       [](Doc& d) {
         animate(d)["samplers"][0]["input"] = d.floats({0, 1}, "SCALAR", 1);
       },
       nullptr},
      {"an output of the wrong count",
       [](Doc& d) {
         animate(d)["samplers"][0]["output"] = d.floats({0, 0, 0, 1, 0, 0, 2, 0, 0}, "VEC3", 3);
       },
       "animations[0].channels[0]"},
      {"an output of the wrong type",
       [](Doc& d) {
         animate(d)["samplers"][0]["output"] = d.floats({0, 0, 0, 1, 0, 0, 2, 0}, "VEC4", 4);
       },
       "animations[0].channels[0]"},
      {"animating a node with a matrix",
       [](Doc& d) {
         animate(d);
         d.node(0)["matrix"] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1};
       },
       "animations[0].channels[0].target"},
      {"animating weights without morph targets",
       [](Doc& d) {
         Json& a = animate(d);
         a["samplers"][0]["output"] = d.floats({0, 1}, "SCALAR", 1);
         a["channels"][0]["target"]["path"] = "weights";
       },
       "animations[0].channels[0].target"},
      {"the same target twice",
       [](Doc& d) {
         Json& a = animate(d);
         a["channels"].push_back(a["channels"][0]);
       },
       "animations[0].channels[1].target"},
      {"key times not increasing",
       [](Doc& d) {
         animate(d)["samplers"][0]["input"] = times(d, {1, 0.5f});
       },
       "animations[0].samplers[0].input"},
      {"a negative key time",
       [](Doc& d) {
         animate(d)["samplers"][0]["input"] = times(d, {-1, 1});
       },
       "animations[0].samplers[0].input"},
      {"a rotation key of length 0.9",
       [](Doc& d) {
         Json& a = animate(d);
         a["samplers"][0]["output"] = d.floats({0, 0, 0, 1, 0, 0, 0, 0.9f}, "VEC4", 4);
         a["channels"][0]["target"]["path"] = "rotation";
       },
       "animations[0].samplers[0].output"},
      {"a rotation key within the tolerance",
       [](Doc& d) {
         Json& a = animate(d);
         a["samplers"][0]["output"] = d.floats({0, 0, 0, 1, 0, 0, 0, 0.995f}, "VEC4", 4);
         a["channels"][0]["target"]["path"] = "rotation";
       },
       nullptr},
      {"CUBICSPLINE with one key",
       [](Doc& d) {
         Json& a = animate(d);
         a["samplers"][0] = {{"input", times(d, {0})},
                             {"output", d.floats({0, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3", 3)},
                             {"interpolation", "CUBICSPLINE"}};
       },
       "animations[0].samplers[0].input"},
  };
}

}  // namespace

TEST(GltfMutations, RaysterRefusesExactlyWhatTheValidatorReports) {
  if (const std::string missing = validatorMissing(); !missing.empty()) GTEST_SKIP() << missing;
  TempDir dir;
  const std::vector<Mutation> list = mutations();
  std::vector<std::string> files;
  for (size_t i = 0; i < list.size(); ++i) {
    Doc d = boundedQuad();
    list[i].edit(d);
    std::string json = d.gltf();
    Json j = Json::parse(json);
    if (list[i].written) list[i].written(j);
    if (list[i].glb) {
      j["buffers"][0].erase("uri");
      std::vector<uint8_t> bin = d.bin;
      if (list[i].bin) list[i].bin(bin);
      files.push_back(dir.write(fmt::format("m{:03}.glb", i), glbBytes(j, bin)).string());
      continue;
    }
    files.push_back(dir.write(fmt::format("m{:03}.gltf", i), j.dump()).string());
  }
  const std::map<std::string, Json> reports = runValidator(files);
  ASSERT_EQ(reports.size(), files.size()) << "the validator reported on every file";

  const log::Level previous = log::level();
  log::setLevel(log::Level::Error);
  std::set<std::string> seenExceptions, seenLoadedCodes;
  for (size_t i = 0; i < list.size(); ++i) {
    const Mutation& m = list[i];
    const Json& r = reports.at(files[i]);
    ASSERT_GE(r["errors"].get<int>(), 0) << m.name << ": " << r["first"];
    const bool invalid = validatorRefuses(r);
    if (!invalid)
      for (const Json& code : r["codes"]) seenLoadedCodes.insert(code.get<std::string>());
    const Result<scene::Scene> loaded = scene::loadGltf(files[i]);
    const bool refused = !loaded.ok();
    const std::string rayster = refused ? "refuses it: " + loaded.error().message : "loads it";
    const std::string validator = r["errors"].get<int>() > 0
                                      ? "reports " + r["codes"].dump() + " " + r["first"].get<std::string>()
                                      : "finds no error";
    if (kRefusedValidFiles.count("mutation:" + m.name)) {
      if (!invalid && refused) seenExceptions.insert("mutation:" + m.name);
      continue;
    }
    // The list says what each mutation is; the validator must agree, or the mutation tests nothing.
    EXPECT_EQ(invalid, m.refusal != nullptr) << m.name << " (" << files[i] << "): validator " << validator;
    if (invalid != refused) {
      ADD_FAILURE() << m.name << " (" << files[i] << "): validator " << validator << ", Rayster " << rayster;
      continue;
    }
    if (refused && m.refusal) {
      EXPECT_EQ(loaded.error().code, ExitCode::BadInput) << m.name;
      EXPECT_NE(loaded.error().message.find(m.refusal), std::string::npos)
          << m.name << ": the message should name " << m.refusal << ": " << loaded.error().message;
      EXPECT_EQ(loaded.error().message.find('\n'), std::string::npos) << m.name << ": " << loaded.error().message;
    }
  }
  log::setLevel(previous);
  for (const auto& [name, why] : kRefusedValidFiles)
    if (name.rfind("mutation:", 0) == 0)
      EXPECT_TRUE(seenExceptions.count(name))
          << name << " is listed as an exception but no longer differs (" << why << ")";
  // Every validator error Rayster loads through is exercised by a mutation here.
  for (const auto& [code, why] : kLoadedValidatorErrors)
    EXPECT_TRUE(seenLoadedCodes.count(code)) << "no mutation makes the validator report " << code;
}
