// EXT_meshopt_compression (scene/gltf_meshopt.cpp): streams written here by libmeshoptimizer's own
// encoders, with every mode and filter, decode to the data they were made from, in a GLB and in a
// .gltf with a fallback buffer that has no data; broken streams and lying views are refused in
// one line naming the buffer view.
#include <cmath>
#include <random>

#include <meshoptimizer.h>

#include <gtest/gtest.h>

#include "core/log.h"
#include "tests/unit/gltf_test_util.h"

namespace rayster::test {
namespace {

// A document whose compressed views decode into buffer 1, a fallback buffer without data.
struct MeshoptDoc {
  Doc d;
  size_t fallbackSize = 0;

  MeshoptDoc() {
    d.j["extensionsUsed"] = {"EXT_meshopt_compression"};
    d.j["extensionsRequired"] = {"EXT_meshopt_compression"};
  }

  // Encodes `raw` (count elements of `stride` bytes, already filter-encoded) and adds the view.
  int view(const std::vector<uint8_t>& raw, size_t count, size_t stride, const std::string& mode,
           const std::string& filter = "NONE") {
    std::vector<uint8_t> encoded;
    if (mode == "ATTRIBUTES") {
      encoded.resize(meshopt_encodeVertexBufferBound(count, stride));
      encoded.resize(meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), raw.data(), count, stride));
    } else {
      std::vector<unsigned> indices(count);
      for (size_t i = 0; i < count; ++i) {
        if (stride == 2) {
          uint16_t v;
          std::memcpy(&v, raw.data() + i * 2, 2);
          indices[i] = v;
        } else {
          std::memcpy(&indices[i], raw.data() + i * 4, 4);
        }
      }
      if (mode == "TRIANGLES") {
        encoded.resize(meshopt_encodeIndexBufferBound(count, 1 << 16));
        encoded.resize(meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), indices.data(), count));
      } else {
        encoded.resize(meshopt_encodeIndexSequenceBound(count, 1 << 16));
        encoded.resize(meshopt_encodeIndexSequence(encoded.data(), encoded.size(), indices.data(), count));
      }
    }
    while (d.bin.size() % 4) d.bin.push_back(0);
    const size_t source = d.bin.size();
    d.bin.insert(d.bin.end(), encoded.begin(), encoded.end());
    fallbackSize = (fallbackSize + 3) & ~size_t(3);
    Json v = {{"buffer", 1}, {"byteOffset", fallbackSize}, {"byteLength", count * stride}};
    // No byteStride on the view: tightly packed is its default, and animation data must not have one.
    Json ext = {{"buffer", 0},          {"byteOffset", source}, {"byteLength", encoded.size()},
                {"byteStride", stride}, {"count", count},       {"mode", mode}};
    if (filter != "NONE") ext["filter"] = filter;
    v["extensions"]["EXT_meshopt_compression"] = ext;
    fallbackSize += count * stride;
    d.j["bufferViews"].push_back(v);
    d.extraBuffers = Json::array(
        {{{"byteLength", fallbackSize}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}});
    return int(d.j["bufferViews"].size()) - 1;
  }

  Json& ext(int view) { return d.j["bufferViews"][size_t(view)]["extensions"]["EXT_meshopt_compression"]; }
};

template <class T>
std::vector<uint8_t> bytesOf(const std::vector<T>& v) {
  std::vector<uint8_t> out(v.size() * sizeof(T));
  std::memcpy(out.data(), v.data(), out.size());
  return out;
}

const std::vector<float> kPositions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5f, 0.5f, 0.25f};
const std::vector<float> kUvs = {0, 1, 1, 1, 1, 0, 0, 0, 0.5f, 0.5f};
const std::vector<uint16_t> kTriangles = {0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};

// A five-vertex pyramid quad with every mode and filter: positions plain, normals OCTAHEDRAL,
// UVs EXPONENTIAL, triangles as TRIANGLES (u16) and, in a second primitive, as INDICES (u32), and
// an animation whose rotations are QUATERNION-filtered.
MeshoptDoc everyModeAndFilter() {
  MeshoptDoc m;
  Doc& d = m.d;
  const int pos = d.accessor(m.view(bytesOf(kPositions), 5, 12, "ATTRIBUTES"), kFloat, 5, "VEC3");
  d.j["accessors"][size_t(pos)]["min"] = {0, 0, 0};
  d.j["accessors"][size_t(pos)]["max"] = {1, 1, 0.25};
  std::vector<float> normals;
  for (int i = 0; i < 5; ++i) normals.insert(normals.end(), {0.6f, 0.0f, 0.8f, 0.0f});
  std::vector<uint8_t> oct(5 * 4);
  meshopt_encodeFilterOct(oct.data(), 5, 4, 8, normals.data());
  const int nrm = d.accessor(m.view(oct, 5, 4, "ATTRIBUTES", "OCTAHEDRAL"), kByte, 5, "VEC3", true);
  std::vector<uint8_t> exp(5 * 8);
  meshopt_encodeFilterExp(exp.data(), 5, 8, 15, kUvs.data());
  const int uv = d.accessor(m.view(exp, 5, 8, "ATTRIBUTES", "EXPONENTIAL"), kFloat, 5, "VEC2");
  const int tri = d.accessor(m.view(bytesOf(kTriangles), 12, 2, "TRIANGLES"), kUShort, 12, "SCALAR");
  std::vector<uint32_t> wide(kTriangles.begin(), kTriangles.end());
  const int seq = d.accessor(m.view(bytesOf(wide), 12, 4, "INDICES"), kUInt, 12, "SCALAR");
  Json attributes = {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}};
  d.j["meshes"] = Json::array({{{"name", "pyramid"},
                                {"primitives", Json::array({{{"attributes", attributes}, {"indices", tri}},
                                                            {{"attributes", attributes}, {"indices", seq}}})}}});
  d.j["nodes"] = Json::array({{{"name", "pyramid"}, {"mesh", 0}}});
  d.j["scenes"] = Json::array({{{"nodes", {0}}}});
  d.j["scene"] = 0;

  const std::vector<float> times = {0.0f, 1.0f};
  const float s = std::sqrt(0.5f);
  const std::vector<float> rotations = {0, 0, 0, 1, 0, s, 0, s};
  std::vector<uint8_t> quat(2 * 8);
  meshopt_encodeFilterQuat(quat.data(), 2, 8, 12, rotations.data());
  const int input = d.accessor(m.view(bytesOf(times), 2, 4, "ATTRIBUTES"), kFloat, 2, "SCALAR");
  d.j["accessors"][size_t(input)]["min"] = {0};
  d.j["accessors"][size_t(input)]["max"] = {1};
  const int output = d.accessor(m.view(quat, 2, 8, "ATTRIBUTES", "QUATERNION"), kShort, 2, "VEC4", true);
  d.j["animations"] =
      Json::array({{{"samplers", Json::array({{{"input", input}, {"output", output}}})},
                    {"channels", Json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "rotation"}}}}})}}});
  return m;
}

std::vector<uint32_t> canonical(std::vector<uint32_t> indices) {
  for (size_t t = 0; t + 2 < indices.size(); t += 3)
    while (indices[t] > indices[t + 1] || indices[t] > indices[t + 2])
      std::rotate(indices.begin() + long(t), indices.begin() + long(t) + 1, indices.begin() + long(t) + 3);
  return indices;
}

void expectDecoded(const Result<scene::Scene>& scene) {
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  ASSERT_EQ(scene->meshes.size(), 1u);
  ASSERT_EQ(scene->meshes[0].primitives.size(), 2u);
  for (const scene::Primitive& p : scene->meshes[0].primitives) {
    ASSERT_EQ(p.positions.size(), 5u);
    for (size_t i = 0; i < 5; ++i) {
      EXPECT_EQ(p.positions[i], glm::vec3(kPositions[3 * i], kPositions[3 * i + 1], kPositions[3 * i + 2])) << i;
      // 8-bit octahedral: within a degree or so of (0.6, 0, 0.8).
      EXPECT_NEAR(p.normals[i].x / glm::length(p.normals[i]), 0.6f, 0.02f) << i;
      EXPECT_NEAR(p.normals[i].z / glm::length(p.normals[i]), 0.8f, 0.02f) << i;
      // 15-bit mantissa shared by the pair: relative error 2^-15 of the larger component.
      EXPECT_NEAR(p.uvs[i].x, kUvs[2 * i], 1e-4f) << i;
      EXPECT_NEAR(p.uvs[i].y, kUvs[2 * i + 1], 1e-4f) << i;
    }
    // The index codec may rotate a triangle's corners (never its winding): compare rotated to
    // start at each triangle's smallest index.
    EXPECT_EQ(canonical(p.indices), canonical(std::vector<uint32_t>(kTriangles.begin(), kTriangles.end())));
  }
  ASSERT_EQ(scene->animations.size(), 1u);
  const scene::AnimationChannel& c = scene->animations[0].channels.at(0);
  ASSERT_EQ(c.values.size(), 2u);
  EXPECT_NEAR(std::abs(c.values[1].y), std::sqrt(0.5f), 2e-3f);
  EXPECT_NEAR(std::abs(c.values[1].w), std::sqrt(0.5f), 2e-3f);
  EXPECT_NEAR(std::abs(c.values[0].w), 1.0f, 1e-3f);
}

void expectRefused(const Result<scene::Scene>& scene, const std::string& part) {
  ASSERT_FALSE(scene.ok()) << "expected a refusal containing: " << part;
  EXPECT_NE(scene.error().message.find(part), std::string::npos) << scene.error().message;
  EXPECT_EQ(scene.error().message.find('\n'), std::string::npos) << scene.error().message;
}

TEST(GltfMeshopt, EveryModeAndFilterDecodesInAGlb) {
  TempDir dir;
  MeshoptDoc m = everyModeAndFilter();
  expectDecoded(loadBytes(dir, m.d.glb(), "pyramid.glb"));
}

TEST(GltfMeshopt, EveryModeAndFilterDecodesInAGltfWithExternalBin) {
  TempDir dir;
  MeshoptDoc m = everyModeAndFilter();
  dir.write("pyramid.bin", std::string(m.d.bin.begin(), m.d.bin.end()));
  expectDecoded(loadBytes(dir, m.d.gltf("pyramid.bin"), "pyramid.gltf"));
  expectDecoded(loadBytes(dir, m.d.gltf(), "embedded.gltf"));
}

TEST(GltfMeshopt, AFallbackBufferWithDataIsOverwrittenByTheDecodedViews) {
  TempDir dir;
  MeshoptDoc m = everyModeAndFilter();
  // What a loader without the extension would read: zeros here, so only decoding gives the pyramid.
  m.d.extraBuffers[0]["uri"] = "fallback.bin";
  dir.write("fallback.bin", std::string(m.fallbackSize, '\0'));
  expectDecoded(loadBytes(dir, m.d.gltf(), "withfallback.gltf"));
}

TEST(GltfMeshopt, BrokenStreamsAndLyingViewsAreRefusedNamingTheView) {
  TempDir dir;
  const std::string at = "bufferViews[0].extensions.EXT_meshopt_compression";
  {
    MeshoptDoc m = everyModeAndFilter();
    m.d.bin[size_t(m.ext(0)["byteOffset"]) + 5] ^= 0xFF;  // a corrupt vertex stream
    m.ext(0)["byteLength"] = 8;                           // and cut short
    expectRefused(loadBytes(dir, m.d.glb(), "short.glb"), at + ": is not a valid meshoptimizer ATTRIBUTES stream");
  }
  {
    MeshoptDoc m = everyModeAndFilter();
    m.d.bin[size_t(m.ext(0)["byteOffset"])] = 0xA1;  // vertex codec version 1
    expectRefused(loadBytes(dir, m.d.glb(), "v1.glb"), "vertex codec version 1");
  }
  {
    MeshoptDoc m = everyModeAndFilter();
    m.ext(0)["byteStride"] = 6;
    expectRefused(loadBytes(dir, m.d.glb(), "stride.glb"), at + ": byteStride 6 for ATTRIBUTES");
  }
  {
    MeshoptDoc m = everyModeAndFilter();
    m.ext(3)["count"] = 13;
    expectRefused(loadBytes(dir, m.d.glb(), "count.glb"), "count 13 for TRIANGLES is not a multiple of 3");
  }
  {
    MeshoptDoc m = everyModeAndFilter();
    m.ext(1)["filter"] = "QUATERNION";  // needs stride 8, the normals have 4
    expectRefused(loadBytes(dir, m.d.glb(), "filter.glb"), "byteStride 4 for the QUATERNION filter is not 8");
  }
  {
    MeshoptDoc m = everyModeAndFilter();
    m.ext(0)["count"] = 40;  // more than the view holds
    expectRefused(loadBytes(dir, m.d.glb(), "big.glb"), "480 decoded bytes do not fit bufferViews[0] (60 bytes");
    m.ext(0)["count"] = 100000000;  // more than the stream could ever hold
    expectRefused(loadBytes(dir, m.d.glb(), "huge.glb"), "is more than the compressed data can decode to");
  }
  {
    MeshoptDoc m = everyModeAndFilter();
    m.ext(0)["byteLength"] = 100000;  // past the end of the source buffer
    expectRefused(loadBytes(dir, m.d.glb(), "past.glb"), "lie outside buffer 0");
  }
  {
    MeshoptDoc m = everyModeAndFilter();
    m.d.extraBuffers[0]["byteLength"] = uint64_t(1) << 40;  // a terabyte from a few hundred bytes
    expectRefused(loadBytes(dir, m.d.glb(), "tera.glb"), "more than its");
  }
  {
    MeshoptDoc m = everyModeAndFilter();
    m.d.j["bufferViews"][0].erase("extensions");  // plain data in a buffer that has none
    expectRefused(loadBytes(dir, m.d.glb(), "plain.glb"), "bufferViews[0] is not compressed but uses buffer 1");
  }
  {
    MeshoptDoc m = everyModeAndFilter();
    m.ext(2)["mode"] = "VERTICES";
    expectRefused(loadBytes(dir, m.d.glb(), "mode.glb"),
                  "bufferViews[2].extensions.EXT_meshopt_compression.mode 'VERTICES' is not");
  }
}

TEST(GltfMeshopt, RandomCorruptionIsRefusedOrDecodedNeverACrash) {
  TempDir dir;
  const log::Level previous = log::level();
  log::setLevel(log::Level::Error);
  MeshoptDoc m = everyModeAndFilter();
  std::mt19937 rng(15);
  for (int round = 0; round < 200; ++round) {
    Doc d = m.d;
    for (int k = 0; k < 4; ++k) d.bin[rng() % d.bin.size()] = uint8_t(rng());
    Result<scene::Scene> scene = loadBytes(dir, d.glb(), "random.glb");
    if (!scene.ok()) {
      EXPECT_EQ(scene.error().message.find('\n'), std::string::npos);
    }
  }
  log::setLevel(previous);
}

}  // namespace
}  // namespace rayster::test
