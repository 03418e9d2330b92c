// glTF files the loader must refuse: each with ExitCode::BadInput and a one-line message that says
// why. Built from the same test quad as test_gltf.cpp, broken one way each.
#include <functional>

#include <gtest/gtest.h>

#include "gltf_test_util.h"

using namespace rayster;
using namespace rayster::test;

namespace {

void expectRefused(const Result<scene::Scene>& result, const std::string& substring) {
  ASSERT_FALSE(result.ok()) << "expected a refusal mentioning: " << substring;
  EXPECT_EQ(result.error().code, ExitCode::BadInput);
  EXPECT_NE(result.error().message.find(substring), std::string::npos) << result.error().message;
  EXPECT_EQ(result.error().message.find('\n'), std::string::npos) << result.error().message;
}

// A PNG whose IHDR claims width x height, with no pixel data behind it.
std::vector<uint8_t> pngHeader(uint32_t width, uint32_t height) {
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A, 0, 0, 0, 13, 'I', 'H', 'D', 'R'};
  for (uint32_t v : {width, height})
    for (int shift = 24; shift >= 0; shift -= 8) png.push_back(uint8_t(v >> shift));
  // bit depth, RGBA, methods, CRC (unchecked by stb), then IEND.
  png.insert(png.end(), {8, 6, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82});
  return png;
}

// Image 0 as the base colour of the quad's material: only images a material shows are decoded
// and required (test_gltf_skip.cpp has the others).
void showImage(Doc& d, const Json& image) {
  d.j["images"] = Json::array({image});
  d.j["textures"] = Json::array({{{"source", 0}}});
  d.j["materials"] = Json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  primitive(d)["material"] = 0;
}

Result<scene::Scene> loadWithBufferUri(const std::string& uri) {
  TempDir dir;
  Doc d = quadDoc();
  return loadBytes(dir, d.gltf(uri), "sub/quad.gltf");
}

TEST(GltfReject, MissingFile) {
  TempDir dir;
  expectRefused(scene::loadGltf(dir.path() / "nothing.gltf"), "nothing.gltf");
}

TEST(GltfReject, TruncatedJson) {
  TempDir dir;
  std::string json = quadDoc().gltf();
  expectRefused(loadBytes(dir, json.substr(0, json.size() / 2)), "invalid JSON");
}

TEST(GltfReject, GarbageGlbLength) {
  TempDir dir;
  std::string glb = quadDoc().glb();
  glb[8] = char(0xff);  // the header's total length now exceeds the file
  glb[9] = char(0xff);
  expectRefused(loadBytes(dir, glb, "bad.glb"), "GLB header says");
  std::string truncated = quadDoc().glb();
  expectRefused(loadBytes(dir, truncated.substr(0, truncated.size() - 16), "short.glb"), "GLB");
}

TEST(GltfReject, DeeplyNestedJson) {
  TempDir dir;
  Doc d = quadDoc();
  std::string json = d.gltf();
  json.insert(json.size() - 1, ",\"extras\":" + std::string(10000, '[') + std::string(10000, ']'));
  expectRefused(loadBytes(dir, json), "nests deeper");
}

TEST(GltfReject, AccessorOutOfBufferBounds) {
  TempDir dir;
  Doc d = quadDoc();
  d.j["accessors"][0]["count"] = 5;
  expectRefused(loadBytes(dir, d.gltf()),
                "accessors[0]: 5 elements of 12 bytes from byteOffset 0 run past buffer view 0");
  Doc e = quadDoc();
  e.j["bufferViews"][0]["byteLength"] = 4096;
  expectRefused(loadBytes(dir, e.gltf()), "bufferViews[0]: byteOffset 0 + byteLength 4096 runs past buffer 0");
}

TEST(GltfReject, AbsurdCount) {
  TempDir dir;
  Doc d = quadDoc();
  d.j["accessors"][0]["count"] = uint64_t(1) << 62;
  expectRefused(loadBytes(dir, d.gltf()), "accessors[0]: 4611686018427387904 elements of 12 bytes");
  Doc e = quadDoc();
  e.j["accessors"][0]["count"] = uint64_t(1) << 62;
  e.j["accessors"][0].erase("bufferView");
  expectRefused(loadBytes(dir, e.gltf()), "POSITION has 4611686018427387904");
  // An unused accessor of zeros is valid, but not one larger than the cap on allocations.
  Doc f = quadDoc();
  f.j["accessors"].push_back({{"componentType", kFloat}, {"count", uint64_t(1) << 40}, {"type", "VEC3"}});
  primitive(f) = {{"attributes", {{"POSITION", 4}}}};
  expectRefused(loadBytes(dir, f.gltf()), "too large");
}

TEST(GltfReject, IndexPastVertexCount) {
  TempDir dir;
  Doc d = quadDoc();
  primitive(d)["indices"] = d.accessor(d.view(std::vector<uint32_t>{0, 1, 4}), kUInt, 3, "SCALAR");
  expectRefused(loadBytes(dir, d.gltf()),
                "meshes[0].primitives[0].indices: index 2 is 4, not below the vertex count 4");
}

TEST(GltfReject, SparseIndexPastCount) {
  TempDir dir;
  Doc d = quadDoc();
  const int idxView = d.view(std::vector<uint16_t>{1, 9});
  const int valView = d.view(std::vector<float>{5, 5, 5, 7, 7, 7});
  d.j["accessors"][0]["sparse"] = {{"count", 2},
                                   {"indices", {{"bufferView", idxView}, {"componentType", kUShort}}},
                                   {"values", {{"bufferView", valView}}}};
  expectRefused(loadBytes(dir, d.gltf()),
                "accessors[0].sparse.indices: element 1 is 9, not below the accessor's count 4");
}

TEST(GltfReject, NonFiniteNodeMatrix) {
  TempDir dir;
  Doc d = quadDoc();
  // JSON cannot spell NaN; 1e39 overflows a float to infinity, which is as bad.
  d.node(0)["matrix"] = {1, 0, 0, 0, 0, 1e39, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  expectRefused(loadBytes(dir, d.gltf()), "non-finite transform");
}

TEST(GltfReject, NanPosition) {
  TempDir dir;
  Doc d = quadDoc();
  primitive(d)["attributes"]["POSITION"] = d.floats({0, 0, 0, 1, 0, 0, NAN, 1, 0, 0, 1, 0}, "VEC3", 3);
  expectRefused(loadBytes(dir, d.gltf()), "accessors[4]: element 2 component 0 is nan, not a finite number");
}

TEST(GltfReject, NodeCycle) {
  TempDir dir;
  Doc d = quadDoc();
  d.j["nodes"] = Json::array({{{"mesh", 0}, {"children", {1}}}, {{"children", {0}}}});
  expectRefused(loadBytes(dir, d.gltf()), "nodes[0]: is part of a cycle of children");
  Doc self = quadDoc();
  self.node(0)["children"] = {0};
  expectRefused(loadBytes(dir, self.gltf()), "nodes[0].children[0]: node 0 is its own child");
  Doc twoParents = quadDoc();
  twoParents.j["nodes"] = Json::array({{{"children", {2}}}, {{"children", {2}}}, {{"mesh", 0}}});
  twoParents.j["scenes"][0]["nodes"] = {0, 1};
  expectRefused(loadBytes(dir, twoParents.gltf()), "nodes[1].children[0]: node 2 already has parent 0");
}

TEST(GltfReject, UriLeavingTheFolder) {
  expectRefused(loadWithBufferUri("../quad.bin"), "leaves the glTF's folder");
  expectRefused(loadWithBufferUri("a/%2e%2e/%2E%2E/quad.bin"), "leaves the glTF's folder");
  expectRefused(loadWithBufferUri("/etc/passwd"), "absolute path");
  expectRefused(loadWithBufferUri("file:///etc/passwd"), "scheme 'file'");
  expectRefused(loadWithBufferUri("http://example.com/a.bin"), "scheme 'http'");
  expectRefused(loadWithBufferUri("C:\\Windows\\a.bin"), "drive or scheme");
}

TEST(GltfReject, BadBase64) {
  expectRefused(loadWithBufferUri("data:application/octet-stream;base64,AAAA!!!!"), "invalid base64");
  expectRefused(loadWithBufferUri("data:application/octet-stream,rawbytes"), "not base64");
}

TEST(GltfReject, MissingExternalFiles) {
  expectRefused(loadWithBufferUri("missing.bin"), "missing.bin");
  TempDir dir;
  Doc d = quadDoc();
  showImage(d, {{"uri", "nowhere.png"}});
  expectRefused(loadBytes(dir, d.gltf()), "nowhere.png");
}

TEST(GltfReject, AbsurdImageDimensions) {
  TempDir dir;
  for (auto [w, h] : {std::pair<uint32_t, uint32_t>{100000, 100000}, {16385, 16}, {16384, 16384 + 1}}) {
    Doc d = quadDoc();
    showImage(d, {{"uri", "data:image/png;base64," + base64(pngHeader(w, h))}});
    expectRefused(loadBytes(dir, d.gltf()), "image 0");
  }
  // Below the limits, the same header fails only for its missing pixels.
  Doc d = quadDoc();
  showImage(d, {{"uri", "data:image/png;base64," + base64(pngHeader(16, 16))}});
  expectRefused(loadBytes(dir, d.gltf()), "cannot be decoded");
}

TEST(GltfReject, ImageBufferViewOutsideBuffer) {
  TempDir dir;
  Doc d = quadDoc();
  d.j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 16}, {"byteLength", 1 << 20}});
  d.j["images"] = Json::array({{{"bufferView", d.j["bufferViews"].size() - 1}, {"mimeType", "image/png"}}});
  expectRefused(loadBytes(dir, d.gltf()), "bufferViews[4]: byteOffset 16 + byteLength 1048576 runs past buffer 0");
}

TEST(GltfReject, RequiredUnknownExtension) {
  TempDir dir;
  Doc d = quadDoc();
  d.j["extensionsUsed"] = {"EXT_rayster_unknown"};
  d.j["extensionsRequired"] = {"EXT_rayster_unknown"};
  expectRefused(loadBytes(dir, d.gltf()), "requires extension EXT_rayster_unknown, which Rayster does not support");
}

TEST(GltfReject, UndefinedMode) {
  TempDir dir;
  Doc d = quadDoc();
  primitive(d)["mode"] = 9;
  expectRefused(loadBytes(dir, d.gltf()), "meshes[0].primitives[0].mode: 9 is not [0, 6]");
}

TEST(GltfReject, PointsAndLinesAreSkipped) {
  // Valid glTF with nothing to shade: the primitive is left out (a warning says so), the file loads.
  for (int mode : {0, 1, 2, 3}) {
    TempDir dir;
    Doc d = quadDoc();
    primitive(d)["mode"] = mode;
    Result<scene::Scene> s = loadBytes(dir, d.gltf());
    ASSERT_TRUE(s.ok()) << mode << ": " << s.error().message;
    EXPECT_EQ(s->triangleCount(), 0u) << mode;
  }
}

TEST(GltfReject, WrongAccessorTypes) {
  TempDir dir;
  Doc d = quadDoc();
  primitive(d)["attributes"]["POSITION"] = 2;  // the VEC2 UV accessor
  expectRefused(loadBytes(dir, d.gltf()), "meshes[0].primitives[0].attributes.POSITION: accessor 2 has type VEC2");
  Doc e = quadDoc();
  primitive(e)["indices"] = 0;  // float positions as indices
  expectRefused(loadBytes(dir, e.gltf()), "meshes[0].primitives[0].indices: accessor 0 is not an unsigned");
  Doc f = quadDoc();
  primitive(f)["attributes"]["NORMAL"] = 42;
  expectRefused(loadBytes(dir, f.gltf()), "meshes[0].primitives[0].attributes.NORMAL: accessor 42 does not exist");
}

}  // namespace

// What glTF 2.0 forbids and tinygltf parses anyway (scene/gltf_validate.cpp): each refused with the
// property named, where the loader used to draw something the file does not say.
namespace {

void expectSpecRefusal(const std::function<void(Doc&)>& edit, const std::string& substring) {
  TempDir dir;
  Doc d = quadDoc();
  edit(d);
  expectRefused(loadBytes(dir, d.gltf()), substring);
}

}  // namespace

TEST(GltfSpec, AssetVersionMustBeTwo) {
  expectSpecRefusal([](Doc& d) { d.j["asset"]["version"] = "3.0"; }, "asset.version: '3.0' is not a glTF 2.x version");
  expectSpecRefusal([](Doc& d) { d.j["asset"]["version"] = "2"; }, "asset.version: '2' is not 'major.minor'");
  expectSpecRefusal([](Doc& d) { d.j["asset"]["minVersion"] = "2.1"; },
                    "asset.minVersion: '2.1' is greater than version '2.0'");
  // 2.1 is a 2.x version a 2.0 loader may read (the spec's forward compatibility).
  TempDir dir;
  Doc d = quadDoc();
  d.j["asset"]["version"] = "2.1";
  EXPECT_TRUE(loadBytes(dir, d.gltf()).ok());
}

TEST(GltfSpec, NodeArraysHaveTheirSizes) {
  expectSpecRefusal([](Doc& d) { d.node(0)["matrix"] = Json(std::vector<double>(15, 0.0)); },
                    "nodes[0].matrix: 15 numbers, need 16");
  expectSpecRefusal([](Doc& d) { d.node(0)["matrix"] = Json(std::vector<double>(17, 0.0)); },
                    "nodes[0].matrix: 17 numbers, need 16");
  expectSpecRefusal([](Doc& d) { d.node(0)["translation"] = {1, 2}; }, "nodes[0].translation: 2 numbers, need 3");
}

TEST(GltfSpec, TextureImageAndSamplerIndicesExist) {
  auto textured = [](Doc& d, Json texture) {
    d.j["images"] = Json::array({{{"uri", "missing.png"}}});
    d.j["textures"] = Json::array({texture});
    d.j["materials"] = Json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    primitive(d)["material"] = 0;
  };
  expectSpecRefusal([&](Doc& d) { textured(d, {{"source", 3}}); }, "textures[0].source: image 3 does not exist");
  expectSpecRefusal(
      [&](Doc& d) {
        textured(d, {{"source", 0}, {"sampler", 1}});
      },
      "textures[0].sampler: sampler 1 does not exist");
  expectSpecRefusal(
      [&](Doc& d) {
        textured(d, {{"source", 0}});
        d.j["materials"][0]["normalTexture"] = {{"index", 5}};
      },
      "materials[0].normalTexture.index: texture 5 does not exist");
}

// The schema allows any integer for filters and wraps (forward compatibility) and the validator only
// warns about values glTF 2.0 does not define: the file loads, with the default for each.
TEST(GltfSpec, SamplerValuesOutsideTheEnumsAreDefaults) {
  for (const Json& sampler :
       {Json{{"magFilter", 9984}}, Json{{"minFilter", 1234}}, Json{{"wrapS", 10496}}, Json{{"wrapT", 0}}}) {
    TempDir dir;
    Doc d = quadDoc();
    d.j["samplers"] = Json::array({sampler});
    d.j["textures"] = Json::array({{{"sampler", 0}}});
    Result<scene::Scene> s = loadBytes(dir, d.gltf());
    ASSERT_TRUE(s.ok()) << sampler.dump() << ": " << s.error().message;
    ASSERT_EQ(s->samplers.size(), 1u);
    EXPECT_EQ(s->samplers[0].wrapS, scene::Wrap::Repeat);
    EXPECT_EQ(s->samplers[0].wrapT, scene::Wrap::Repeat);
    EXPECT_EQ(s->samplers[0].magFilter, scene::Filter::Linear);
  }
}

TEST(GltfSpec, CamerasHaveAPositiveFieldOfViewAndNearPlane) {
  auto camera = [](Doc& d, Json perspective) {
    d.j["cameras"] = Json::array({{{"type", "perspective"}, {"perspective", perspective}}});
    d.node(0)["camera"] = 0;
  };
  expectSpecRefusal(
      [&](Doc& d) {
        camera(d, {{"yfov", 0.0}, {"znear", 0.1}});
      },
      "cameras[0].perspective.yfov: 0 is not above 0");
  expectSpecRefusal(
      [&](Doc& d) {
        camera(d, {{"yfov", -0.5}, {"znear", 0.1}});
      },
      "cameras[0].perspective.yfov: -0.5 is not above 0");
  expectSpecRefusal(
      [&](Doc& d) {
        camera(d, {{"yfov", 0.7}, {"znear", 0.0}});
      },
      "cameras[0].perspective.znear: 0 is not above 0");
  expectSpecRefusal(
      [&](Doc& d) {
        camera(d, {{"yfov", 0.7}, {"znear", 1.0}, {"zfar", 0.5}});
      },
      "cameras[0].perspective.zfar: 0.5 is not beyond znear 1");
  // No zfar is valid: an infinite projection.
  TempDir dir;
  Doc d = quadDoc();
  camera(d, {{"yfov", 0.7}, {"znear", 0.1}});
  EXPECT_TRUE(loadBytes(dir, d.gltf()).ok());
}

TEST(GltfSpec, LightsHaveNonNegativeIntensityAndOrderedCones) {
  auto light = [](Doc& d, Json l) {
    d.j["extensionsUsed"] = {"KHR_lights_punctual"};
    d.j["extensions"]["KHR_lights_punctual"]["lights"] = Json::array({l});
    d.node(0)["extensions"] = {{"KHR_lights_punctual", {{"light", 0}}}};
  };
  expectSpecRefusal(
      [&](Doc& d) {
        light(d, {{"type", "point"}, {"intensity", -3.0}});
      },
      "extensions.KHR_lights_punctual.lights[0].intensity: -3 is not at least 0");
  expectSpecRefusal(
      [&](Doc& d) {
        light(d, {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.6}, {"outerConeAngle", 0.4}}}});
      },
      "lights[0].spot.outerConeAngle: 0.4 is not above innerConeAngle 0.6");
  expectSpecRefusal(
      [&](Doc& d) {
        light(d, {{"type", "spot"}, {"spot", {{"outerConeAngle", 2.0}}}});
      },
      "lights[0].spot.outerConeAngle: 2 is not (0, 1.57");
  expectSpecRefusal(
      [&](Doc& d) {
        light(d, {{"type", "point"}, {"range", -1.0}});
      },
      "lights[0].range: -1 is not above 0");
}

TEST(GltfSpec, PositionBoundsAreTheDatasExtremes) {
  // The test quad spans [0, 1] in x and y; bounds that leave a corner outside contradict the file.
  expectSpecRefusal(
      [](Doc& d) {
        d.j["accessors"][0]["min"] = {0.0, 0.0, 0.0};
        d.j["accessors"][0]["max"] = {0.5, 1.0, 0.0};
      },
      "accessors[0].max[0]: 0.5, but the largest value is 1");
  // Looser bounds too: the validator reports ACCESSOR_MIN_MISMATCH (min and max are the extremes).
  expectSpecRefusal(
      [](Doc& d) {
        d.j["accessors"][0]["min"] = {-1.0, 0.0, 0.0};
      },
      "accessors[0].min[0]: -1, but the smallest value is 0");
  // Bounds written with more digits than a float holds compare as the float they round to.
  TempDir dir;
  Doc d = quadDoc();
  d.j["accessors"][0]["min"] = {0.0, 0.0, 0.0};
  d.j["accessors"][0]["max"] = {1.00000001, 1.0, 0.0};
  EXPECT_TRUE(loadBytes(dir, d.gltf()).ok());
}
