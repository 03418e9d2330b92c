#pragma once
// Builds small glTF documents in tests: nlohmann JSON plus one binary buffer, written as a .gltf
// with a data URI, a .gltf with a .bin, or a .glb, into a per-test temporary folder.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "scene/gltf_loader.h"
#include "tests/support/test_dirs.h"

namespace rayster::test {

using Json = nlohmann::json;

// glTF component types.
constexpr int kByte = 5120, kUByte = 5121, kShort = 5122, kUShort = 5123, kUInt = 5125, kFloat = 5126;

inline std::string base64(const std::vector<uint8_t>& data) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < data.size(); i += 3) {
    uint32_t v = uint32_t(data[i]) << 16;
    if (i + 1 < data.size()) v |= uint32_t(data[i + 1]) << 8;
    if (i + 2 < data.size()) v |= data[i + 2];
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < data.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += i + 2 < data.size() ? kAlphabet[v & 63] : '=';
  }
  return out;
}

// A fresh folder of the running test (tests/support/test_dirs.h: removed when the test passes).
class TempDir {
 public:
  TempDir() : path_(uniqueTestDir("gltf")) {}
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path write(const std::string& name, const std::string& bytes) const {
    std::filesystem::path p = path_ / name;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    return p;
  }

 private:
  std::filesystem::path path_;
};

// A glTF document under construction.
struct Doc {
  Json j = Json::object();
  std::vector<uint8_t> bin;
  Json extraBuffers = Json::array();  // buffers 1, 2, … as given (e.g. EXT_meshopt_compression fallbacks)

  Doc() { j["asset"] = {{"version", "2.0"}}; }

  template <class T>
  int view(const std::vector<T>& data, size_t stride = 0) {
    while (bin.size() % 4) bin.push_back(0);
    const size_t offset = bin.size();
    bin.resize(offset + data.size() * sizeof(T));
    std::memcpy(bin.data() + offset, data.data(), data.size() * sizeof(T));
    Json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", data.size() * sizeof(T)}};
    if (stride) v["byteStride"] = stride;
    j["bufferViews"].push_back(v);
    return int(j["bufferViews"].size()) - 1;
  }

  int accessor(int view, int componentType, size_t count, const char* type, bool normalized = false,
               size_t byteOffset = 0) {
    Json a = {{"componentType", componentType}, {"count", count}, {"type", type}};
    if (view >= 0) a["bufferView"] = view;
    if (byteOffset) a["byteOffset"] = byteOffset;
    if (normalized) a["normalized"] = true;
    j["accessors"].push_back(a);
    return int(j["accessors"].size()) - 1;
  }

  // A float accessor over new data.
  int floats(const std::vector<float>& data, const char* type, int components) {
    return accessor(view(data), kFloat, data.size() / size_t(components), type);
  }

  Json& node(int index) { return j["nodes"][size_t(index)]; }

  // Buffer 0 as a data URI (the default) or as an external file name.
  std::string gltf(const std::string& binUri = {}) {
    Json out = j;
    if (!bin.empty() || out.contains("bufferViews")) {
      Json buffer = {{"byteLength", bin.size()}};
      buffer["uri"] = binUri.empty() ? "data:application/octet-stream;base64," + base64(bin) : binUri;
      out["buffers"] = Json::array({buffer});
    }
    for (const Json& b : extraBuffers) out["buffers"].push_back(b);
    return out.dump();
  }

  std::string glb() {
    Json out = j;
    while (bin.size() % 4) bin.push_back(0);
    if (!bin.empty()) out["buffers"] = Json::array({Json{{"byteLength", bin.size()}}});
    for (const Json& b : extraBuffers) out["buffers"].push_back(b);
    std::string json = out.dump();
    while (json.size() % 4) json += ' ';
    std::string bytes = "glTF";
    auto u32 = [&](uint32_t v) { bytes.append(reinterpret_cast<const char*>(&v), 4); };
    const uint32_t total = uint32_t(12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size()));
    u32(2);
    u32(total);
    u32(uint32_t(json.size()));
    u32(0x4E4F534A);
    bytes += json;
    if (!bin.empty()) {
      u32(uint32_t(bin.size()));
      u32(0x004E4942);
      bytes.append(reinterpret_cast<const char*>(bin.data()), bin.size());
    }
    return bytes;
  }
};

// A unit quad in z = 0 facing +Z: 4 vertices with normals and UVs, 6 u16 indices; mesh 0 on node 0.
inline Doc quadDoc() {
  Doc d;
  const int pos = d.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3", 3);
  const int nrm = d.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
  const int uv = d.floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2", 2);
  const int idx = d.accessor(d.view(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}), kUShort, 6, "SCALAR");
  d.j["meshes"] = Json::array(
      {{{"name", "quad"},
        {"primitives", Json::array({{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}}},
                                     {"indices", idx}}})}}});
  d.j["nodes"] = Json::array({{{"name", "quad"}, {"mesh", 0}}});
  d.j["scenes"] = Json::array({{{"nodes", {0}}}});
  d.j["scene"] = 0;
  return d;
}

inline Json& primitive(Doc& d, int mesh = 0, int prim = 0) {
  return d.j["meshes"][size_t(mesh)]["primitives"][size_t(prim)];
}

// Writes `bytes` as `name` into `dir` and loads it.
inline Result<scene::Scene> loadBytes(const TempDir& dir, const std::string& bytes,
                                      const std::string& name = "test.gltf") {
  return scene::loadGltf(dir.write(name, bytes));
}

}  // namespace rayster::test
