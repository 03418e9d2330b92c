// The first half of the glTF mutations (gltf_mutations.h): asset, extensions, buffers, buffer views,
// accessors and meshes.
#include "gltf_mutations.h"

namespace rayster::test::mutation {

std::vector<Mutation> dataMutations() {
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
  };
}

}  // namespace rayster::test::mutation
