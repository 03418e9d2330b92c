// KHR_draco_mesh_compression (scene/gltf_draco.cpp): meshes encoded here by libdraco's own encoder,
// with every attribute Rayster reads (two UV sets, tangents, colours, joints and weights), quantized
// and not, edgebreaker and sequential, decode to the data they were made from; broken Draco data
// and accessors that contradict it are refused in one line naming the primitive.
#include <dlfcn.h>

#include <cmath>
#include <random>

#include <draco/compression/encode.h>
#include <tiny_gltf.h>

#include <gtest/gtest.h>

#include "core/log.h"
#include "tests/unit/gltf_test_util.h"

namespace rayster::test {
namespace {

// A 4 × 4 vertex grid in z = 0 (9 quads, 18 triangles). Every attribute is a function of the
// position, so a decoder that reorders the points (edgebreaker does) can still be checked.
constexpr int kGrid = 4;
glm::vec3 gridPosition(int i) { return {float(i % kGrid) / 3.0f, float(i / kGrid) / 3.0f, 0.0f}; }
glm::vec2 uv0Of(glm::vec3 p) { return {p.x, 1.0f - p.y}; }
glm::vec2 uv1Of(glm::vec3 p) { return {0.5f * p.y, 0.25f + 0.5f * p.x}; }
glm::vec4 tangentOf(glm::vec3) { return {1, 0, 0, -1}; }
glm::vec4 colorOf(glm::vec3 p) { return {p.x, p.y, 0.5f, 1.0f}; }

struct DracoOptions {
  bool quantize = false;
  bool sequential = false;
};

struct Encoded {
  std::vector<uint8_t> bytes;
  std::map<std::string, int> ids;  // glTF semantic -> Draco unique id
};

template <class T>
int addAttribute(draco::Mesh& mesh, draco::GeometryAttribute::Type type, int components, draco::DataType dataType,
                 bool normalized, const std::vector<T>& values) {
  draco::GeometryAttribute ga;
  ga.Init(type, nullptr, int8_t(components), dataType, normalized, int64_t(sizeof(T)) * components, 0);
  const int id = mesh.AddAttribute(ga, true, mesh.num_points());
  for (uint32_t i = 0; i < mesh.num_points(); ++i)
    mesh.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(i), &values[size_t(i) * size_t(components)]);
  return int(mesh.attribute(id)->unique_id());
}

Encoded encodeGrid(const DracoOptions& options) {
  draco::Mesh mesh;
  const int n = kGrid * kGrid;
  mesh.set_num_points(uint32_t(n));
  std::vector<float> pos, nrm, uv0, uv1, tan, weights;
  std::vector<uint8_t> col, joints;
  for (int i = 0; i < n; ++i) {
    const glm::vec3 p = gridPosition(i);
    pos.insert(pos.end(), {p.x, p.y, p.z});
    nrm.insert(nrm.end(), {0, 0, 1});
    uv0.insert(uv0.end(), {uv0Of(p).x, uv0Of(p).y});
    uv1.insert(uv1.end(), {uv1Of(p).x, uv1Of(p).y});
    const glm::vec4 t = tangentOf(p);
    tan.insert(tan.end(), {t.x, t.y, t.z, t.w});
    const glm::vec4 c = colorOf(p) * 255.0f + 0.5f;
    col.insert(col.end(), {uint8_t(c.x), uint8_t(c.y), uint8_t(c.z), uint8_t(c.w)});
    joints.insert(joints.end(), {0, 1, 0, 0});
    weights.insert(weights.end(), {1.0f - p.x, p.x, 0, 0});
  }
  Encoded e;
  using GA = draco::GeometryAttribute;
  e.ids["POSITION"] = addAttribute(mesh, GA::POSITION, 3, draco::DT_FLOAT32, false, pos);
  e.ids["NORMAL"] = addAttribute(mesh, GA::NORMAL, 3, draco::DT_FLOAT32, false, nrm);
  e.ids["TEXCOORD_0"] = addAttribute(mesh, GA::TEX_COORD, 2, draco::DT_FLOAT32, false, uv0);
  e.ids["TEXCOORD_1"] = addAttribute(mesh, GA::TEX_COORD, 2, draco::DT_FLOAT32, false, uv1);
  e.ids["TANGENT"] = addAttribute(mesh, GA::GENERIC, 4, draco::DT_FLOAT32, false, tan);
  e.ids["COLOR_0"] = addAttribute(mesh, GA::COLOR, 4, draco::DT_UINT8, true, col);
  e.ids["JOINTS_0"] = addAttribute(mesh, GA::GENERIC, 4, draco::DT_UINT8, false, joints);
  e.ids["WEIGHTS_0"] = addAttribute(mesh, GA::GENERIC, 4, draco::DT_FLOAT32, false, weights);
  for (int y = 0; y + 1 < kGrid; ++y)
    for (int x = 0; x + 1 < kGrid; ++x) {
      const uint32_t a = uint32_t(y * kGrid + x);
      using P = draco::PointIndex;
      mesh.AddFace({P(a), P(a + 1), P(a + kGrid + 1)});
      mesh.AddFace({P(a), P(a + kGrid + 1), P(a + kGrid)});
    }
  draco::Encoder encoder;
  if (options.quantize) {
    encoder.SetAttributeQuantization(GA::POSITION, 14);
    encoder.SetAttributeQuantization(GA::NORMAL, 10);
    encoder.SetAttributeQuantization(GA::TEX_COORD, 12);
  }
  if (options.sequential) encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(mesh, &buffer);
  EXPECT_TRUE(status.ok()) << status.error_msg_string();
  e.bytes.assign(buffer.data(), buffer.data() + buffer.size());
  return e;
}

// The grid as a glTF primitive whose accessors have no buffer views: Draco supplies the data.
Doc dracoDoc(const Encoded& e, bool withJoints = false) {
  Doc d;
  d.j["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  d.j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  const int view = d.view(e.bytes);
  const size_t n = kGrid * kGrid;
  Json attributes, ids;
  auto add = [&](const char* name, int componentType, const char* type, bool normalized = false) {
    attributes[name] = d.accessor(-1, componentType, n, type, normalized);
    ids[name] = e.ids.at(name);
  };
  add("POSITION", kFloat, "VEC3");
  d.j["accessors"][0]["min"] = {0, 0, 0};
  d.j["accessors"][0]["max"] = {1, 1, 0};
  add("NORMAL", kFloat, "VEC3");
  add("TEXCOORD_0", kFloat, "VEC2");
  add("TEXCOORD_1", kFloat, "VEC2");
  add("TANGENT", kFloat, "VEC4");
  add("COLOR_0", kUByte, "VEC4", true);
  if (withJoints) {
    add("JOINTS_0", kUByte, "VEC4");
    add("WEIGHTS_0", kFloat, "VEC4");
  }
  const int indices = d.accessor(-1, kUShort, 54, "SCALAR");
  d.j["meshes"] = Json::array(
      {{{"name", "grid"},
        {"primitives",
         Json::array(
             {{{"attributes", attributes},
               {"indices", indices},
               {"extensions", {{"KHR_draco_mesh_compression", {{"bufferView", view}, {"attributes", ids}}}}}}})}}});
  d.j["nodes"] = Json::array({{{"name", "grid"}, {"mesh", 0}}});
  d.j["scenes"] = Json::array({{{"nodes", {0}}}});
  d.j["scene"] = 0;
  return d;
}

void expectGrid(const Result<scene::Scene>& scene, float tolerance) {
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  ASSERT_EQ(scene->meshes.size(), 1u);
  const scene::Primitive& p = scene->meshes[0].primitives.at(0);
  ASSERT_EQ(p.positions.size(), size_t(kGrid * kGrid));
  ASSERT_EQ(p.indices.size(), 54u);
  float area = 0.0f;
  for (size_t t = 0; t < 54; t += 3) {
    const glm::vec3 a = p.positions[p.indices[t]], b = p.positions[p.indices[t + 1]], c = p.positions[p.indices[t + 2]];
    const glm::vec3 n = glm::cross(b - a, c - a);
    EXPECT_GT(n.z, 0.0f) << "triangle " << t / 3 << " keeps its counter-clockwise winding";
    area += 0.5f * glm::length(n);
  }
  EXPECT_NEAR(area, 1.0f, 4 * tolerance);
  for (size_t i = 0; i < p.positions.size(); ++i) {
    const glm::vec3 q = p.positions[i];
    // Every decoded point lies on the grid (within the quantization step) ...
    EXPECT_NEAR(q.x * 3.0f, std::round(q.x * 3.0f), 3 * tolerance) << i;
    EXPECT_NEAR(q.y * 3.0f, std::round(q.y * 3.0f), 3 * tolerance) << i;
    // ... and carries the attributes of its position.
    EXPECT_NEAR(glm::length(p.normals[i] - glm::vec3(0, 0, 1)), 0.0f, 0.01f) << i;
    EXPECT_NEAR(glm::length(p.uvs[i] - uv0Of(q)), 0.0f, 2 * tolerance) << i;
    EXPECT_NEAR(glm::length(p.uvs1[i] - uv1Of(q)), 0.0f, 2 * tolerance) << i;
    EXPECT_EQ(p.tangents[i], tangentOf(q)) << i;
    EXPECT_NEAR(glm::length(p.colors[i] - colorOf(q)), 0.0f, 1.0f / 255.0f + 2 * tolerance) << i;
  }
}

void expectRefused(const Result<scene::Scene>& scene, const std::string& part) {
  ASSERT_FALSE(scene.ok()) << "expected a refusal containing: " << part;
  EXPECT_NE(scene.error().message.find(part), std::string::npos) << scene.error().message;
  EXPECT_EQ(scene.error().message.find('\n'), std::string::npos) << scene.error().message;
}

TEST(GltfDraco, EveryAttributeDecodesLosslessAndQuantized) {
  TempDir dir;
  expectGrid(loadBytes(dir, dracoDoc(encodeGrid({false, false})).glb(), "edgebreaker.glb"), 1e-6f);
  expectGrid(loadBytes(dir, dracoDoc(encodeGrid({false, true})).gltf(), "sequential.gltf"), 1e-6f);
  // 14-bit positions over a unit box: steps of 1/16383; 12-bit UVs: 1/4095.
  expectGrid(loadBytes(dir, dracoDoc(encodeGrid({true, false})).glb(), "quantized.glb"), 1.0f / 4095.0f);
}

TEST(GltfDraco, JointsAndWeightsDecodeForSkinning) {
  TempDir dir;
  Doc d = dracoDoc(encodeGrid({}), true);
  Result<scene::Scene> scene = loadBytes(dir, d.glb(), "skinned.glb");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  const scene::Primitive& p = scene->meshes[0].primitives.at(0);
  ASSERT_EQ(p.influences.size(), 1u);
  for (size_t i = 0; i < p.positions.size(); ++i) {
    EXPECT_EQ(p.influences[0].joints[i], glm::u16vec4(0, 1, 0, 0)) << i;
    EXPECT_NEAR(p.influences[0].weights[i].y, p.positions[i].x, 1e-6f) << i;
  }
}

TEST(GltfDraco, BrokenDataAndContradictingAccessorsAreRefused) {
  TempDir dir;
  const Encoded e = encodeGrid({});
  const std::string at = "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression";
  {
    Doc d = dracoDoc(e);
    d.j["bufferViews"][0]["byteLength"] = 12;  // truncated
    expectRefused(loadBytes(dir, d.glb(), "short.glb"), at + ": Draco cannot decode bufferViews[0]");
  }
  {
    Doc d = dracoDoc(e);
    for (size_t i = 0; i < 8; ++i) d.bin[i] = 'x';  // not a Draco header
    expectRefused(loadBytes(dir, d.glb(), "header.glb"), "Draco cannot decode");
  }
  {
    Doc d = dracoDoc(e);
    d.j["accessors"][0]["count"] = 17;
    // The schema check sees the mismatch with the other attributes before Draco decodes.
    expectRefused(loadBytes(dir, d.glb(), "count.glb"), "POSITION has 17");
  }
  {
    Doc d = dracoDoc(e);
    primitive(d)["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 40;
    expectRefused(loadBytes(dir, d.glb(), "id.glb"), "the Draco mesh has no attribute 40");
  }
  {
    Doc d = dracoDoc(e);
    d.j["accessors"][1]["type"] = "VEC2";
    expectRefused(loadBytes(dir, d.glb(), "components.glb"), "accessor 1 has type VEC2, which NORMAL cannot have");
  }
  {
    Doc d = dracoDoc(e);
    primitive(d)["extensions"]["KHR_draco_mesh_compression"]["bufferView"] = 7;
    expectRefused(loadBytes(dir, d.glb(), "view.glb"), at + ".bufferView is missing or names no buffer view");
  }
  {
    Doc d = dracoDoc(e);
    d.j["accessors"].back()["count"] = 51;
    expectRefused(loadBytes(dir, d.glb(), "indices.glb"), "count 51 is not the 54 decoded indices");
  }
  {
    Doc d = dracoDoc(e);
    primitive(d)["attributes"].erase("TEXCOORD_1");
    expectRefused(loadBytes(dir, d.glb(), "missing.glb"), "the primitive has no TEXCOORD_1 attribute");
  }
}

TEST(GltfDraco, RandomCorruptionIsRefusedOrDecodedNeverACrash) {
  TempDir dir;
  const log::Level previous = log::level();
  log::setLevel(log::Level::Error);
  const Doc base = dracoDoc(encodeGrid({true, false}));
  std::mt19937 rng(15);
  for (int round = 0; round < 200; ++round) {
    Doc d = base;
    for (int k = 0; k < 3; ++k) d.bin[rng() % d.bin.size()] = uint8_t(rng());
    Result<scene::Scene> scene = loadBytes(dir, d.glb(), "random.glb");
    if (!scene.ok()) {
      EXPECT_EQ(scene.error().message.find('\n'), std::string::npos);
    }
  }
  log::setLevel(previous);
}

// libdraco carries a tinygltf of its own (another version and Model layout): the loader must call
// Debian's libtinygltf, never that copy (CMakeLists.txt links libdraco's archive so that it cannot).
TEST(GltfDraco, TheLoadersTinygltfIsDebiansNotDracos) {
  auto member = &tinygltf::TinyGLTF::LoadBinaryFromMemory;
  void* address = nullptr;
  static_assert(sizeof member >= sizeof address);
  std::memcpy(&address, &member, sizeof address);  // Itanium ABI: a non-virtual member's code address first
  Dl_info info{};
  ASSERT_NE(dladdr(address, &info), 0);
  ASSERT_NE(info.dli_fname, nullptr);
  EXPECT_NE(std::string(info.dli_fname).find("libtinygltf"), std::string::npos) << info.dli_fname;
}

}  // namespace
}  // namespace rayster::test
