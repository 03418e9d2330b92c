// rayster-make-scene: writes the load-time benchmark scenes (BENCHMARKS.md, docs/architecture.md
// "Loading"), nothing downloaded:
//   sponza  OUT_DIR [TRIANGLES] [IMAGES]  a .gltf + .bin + images/ folder shaped like Sponza: about
//           260k triangles over 100 meshes and 70 textures of 1024² (base colour JPEG, normal and
//           metallic-roughness PNG), noisy enough that they do not compress to nothing
//   big     OUT.glb [TRIANGLES]          a GLB of 10M triangles in 40 tiles and 2 textures
// Meshes have no TANGENT (the loader generates them, as it must for many real files).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <stb_image_write.h>  // the implementation is in rayster_core (core/image_io.cpp)
#include <nlohmann/json.hpp>

namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

uint32_t hash(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

// Value noise in [0, 1] on a lattice of `cell` pixels, bilinear, seeded.
float valueNoise(int x, int y, int cell, uint32_t seed) {
  const int cx = x / cell, cy = y / cell;
  const float fx = float(x % cell) / float(cell), fy = float(y % cell) / float(cell);
  auto at = [&](int i, int j) {
    return float(hash(uint32_t(i) * 73856093u ^ uint32_t(j) * 19349663u ^ seed) & 0xffff) / 65535.0f;
  };
  const float a = at(cx, cy), b = at(cx + 1, cy), c = at(cx, cy + 1), d = at(cx + 1, cy + 1);
  const float sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
  return (a * (1 - sx) + b * sx) * (1 - sy) + (c * (1 - sx) + d * sx) * sy;
}

float fbm(int x, int y, uint32_t seed) {
  float v = 0, amplitude = 0.5f;
  for (int cell = 128; cell >= 2; cell /= 2, amplitude *= 0.5f) v += amplitude * valueNoise(x, y, cell, seed + cell);
  return v;
}

// kind 0: base colour (bricks and noise), 1: normal map (from a noise height), 2: metal/rough.
std::vector<uint8_t> makeImage(int side, int kind, uint32_t seed) {
  std::vector<uint8_t> rgb(size_t(side) * side * 3);
  const float hue = float(hash(seed) % 1000) / 1000.0f;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      uint8_t* p = &rgb[(size_t(y) * side + x) * 3];
      const float n = fbm(x, y, seed);
      const float grain = float(hash(uint32_t(x * 7919 + y * 104729) ^ seed) & 0xff) / 255.0f;
      if (kind == 0) {
        const bool mortar = (y % 64) < 4 || ((x + (y / 64 % 2) * 64) % 128) < 4;
        const float v = mortar ? 0.35f + 0.1f * grain : 0.5f + 0.4f * n + 0.1f * grain;
        p[0] = uint8_t(255 * std::min(1.0f, v * (0.6f + 0.4f * hue)));
        p[1] = uint8_t(255 * std::min(1.0f, v * 0.8f));
        p[2] = uint8_t(255 * std::min(1.0f, v * (1.0f - 0.4f * hue)));
      } else if (kind == 1) {
        const float dx = fbm(x + 1, y, seed) - n, dy = fbm(x, y + 1, seed) - n;
        const float sx = -dx * 24, sy = -dy * 24, len = std::sqrt(sx * sx + sy * sy + 1);
        p[0] = uint8_t(127.5f + 127.5f * sx / len);
        p[1] = uint8_t(127.5f + 127.5f * sy / len);
        p[2] = uint8_t(127.5f + 127.5f / len);
      } else {
        p[0] = 255;
        p[1] = uint8_t(255 * (0.3f + 0.6f * n + 0.1f * grain));  // roughness
        p[2] = uint8_t(n > 0.6f ? 255 : 0);                      // metallic
      }
    }
  return rgb;
}

void writeBytes(std::vector<uint8_t>& out, const void* data, size_t size) {
  const auto* b = static_cast<const uint8_t*>(data);
  out.insert(out.end(), b, b + size);
}

struct Builder {
  Json root;
  std::vector<uint8_t> bin;

  int view(const void* data, size_t size, int target) {
    while (bin.size() % 4) bin.push_back(0);
    Json v{{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", size}};
    if (target) v["target"] = target;
    writeBytes(bin, data, size);
    root["bufferViews"].push_back(v);
    return int(root["bufferViews"].size()) - 1;
  }
  int accessor(int view, int componentType, size_t count, const char* type, Json min = nullptr, Json max = nullptr) {
    Json a{{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}};
    if (!min.is_null()) a["min"] = min, a["max"] = max;
    root["accessors"].push_back(a);
    return int(root["accessors"].size()) - 1;
  }

  // A displaced grid of about `triangles` triangles, a tile at `origin` of `size` units.
  int addGrid(size_t triangles, float ox, float oz, float size, int material, uint32_t seed) {
    const int n = std::max(1, int(std::sqrt(double(triangles) / 2)));
    const int verts = n + 1;
    std::vector<float> pos, nor, uv;
    pos.reserve(size_t(verts) * verts * 3);
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    const float f = 1.0f + float(seed % 5), a = 0.05f * size;
    for (int j = 0; j < verts; ++j)
      for (int i = 0; i < verts; ++i) {
        const float u = float(i) / n, v = float(j) / n;
        const float x = ox + u * size, z = oz + v * size;
        const float y = a * std::sin(u * 6.28f * f) * std::cos(v * 6.28f * f);
        const float dx = a * 6.28f * f / size * std::cos(u * 6.28f * f) * std::cos(v * 6.28f * f);
        const float dz = -a * 6.28f * f / size * std::sin(u * 6.28f * f) * std::sin(v * 6.28f * f);
        const float l = std::sqrt(dx * dx + 1 + dz * dz);
        const float p[3] = {x, y, z};
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
        pos.insert(pos.end(), {x, y, z});
        nor.insert(nor.end(), {-dx / l, 1 / l, -dz / l});
        uv.insert(uv.end(), {u * 4, v * 4});
      }
    std::vector<uint32_t> idx;
    idx.reserve(size_t(n) * n * 6);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const uint32_t a0 = uint32_t(j * verts + i), b0 = a0 + 1, c0 = a0 + uint32_t(verts), d0 = c0 + 1;
        idx.insert(idx.end(), {a0, c0, b0, b0, c0, d0});
      }
    const size_t count = size_t(verts) * verts;
    Json attributes{{"POSITION", accessor(view(pos.data(), pos.size() * 4, 34962), 5126, count, "VEC3",
                                          Json::array({lo[0], lo[1], lo[2]}), Json::array({hi[0], hi[1], hi[2]}))},
                    {"NORMAL", accessor(view(nor.data(), nor.size() * 4, 34962), 5126, count, "VEC3")},
                    {"TEXCOORD_0", accessor(view(uv.data(), uv.size() * 4, 34962), 5126, count, "VEC2")}};
    const int indices = accessor(view(idx.data(), idx.size() * 4, 34963), 5125, idx.size(), "SCALAR");
    root["meshes"].push_back(
        {{"primitives", Json::array({{{"attributes", attributes}, {"indices", indices}, {"material", material}}})}});
    const int mesh = int(root["meshes"].size()) - 1;
    root["nodes"].push_back({{"mesh", mesh}});
    root["scenes"][0]["nodes"].push_back(int(root["nodes"].size()) - 1);
    return mesh;
  }

  void finish() {
    root["asset"] = {{"version", "2.0"}, {"generator", "rayster-make-scene"}};
    root["scene"] = 0;
    // A camera above the tiles looking down at them, and a sun.
    root["cameras"].push_back({{"type", "perspective"}, {"perspective", {{"yfov", 0.9}, {"znear", 0.05}}}});
    root["nodes"].push_back(
        {{"camera", 0}, {"translation", {0.0, 30.0, 45.0}}, {"rotation", {-0.3826834, 0, 0, 0.9238795}}});
    root["scenes"][0]["nodes"].push_back(int(root["nodes"].size()) - 1);
    root["extensionsUsed"] = {"KHR_lights_punctual"};
    root["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "directional"}, {"intensity", 3.0}}};
    root["nodes"].push_back(
        {{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}, {"rotation", {-0.5, 0.3, 0.1, 0.8}}});
    root["scenes"][0]["nodes"].push_back(int(root["nodes"].size()) - 1);
  }
};

// Encodes image i (of `count`, in material order: base colour, normal, metal/rough) in parallel.
std::vector<std::vector<uint8_t>> encodeImages(int count, int side) {
  std::vector<std::vector<uint8_t>> encoded(static_cast<size_t>(count));
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      for (int i = int(t); i < count; i += int(threads)) {
        const int kind = i % 3;
        const std::vector<uint8_t> rgb = makeImage(side, kind, uint32_t(i) * 2654435761u);
        auto sink = [](void* ctx, void* data, int size) {
          writeBytes(*static_cast<std::vector<uint8_t>*>(ctx), data, size_t(size));
        };
        if (kind == 0)
          stbi_write_jpg_to_func(sink, &encoded[size_t(i)], side, side, 3, rgb.data(), 90);
        else
          stbi_write_png_to_func(sink, &encoded[size_t(i)], side, side, 3, rgb.data(), side * 3);
      }
    });
  for (std::thread& t : pool) t.join();
  return encoded;
}

void addMaterials(Builder& b, int images, const std::vector<std::string>& uris) {
  for (int i = 0; i < images; ++i) {
    Json image = i < int(uris.size()) ? Json{{"uri", uris[size_t(i)]}} : Json{};
    b.root["images"].push_back(image);
    b.root["textures"].push_back({{"source", i}, {"sampler", 0}});
  }
  b.root["samplers"].push_back({{"magFilter", 9729}, {"minFilter", 9987}});
  for (int m = 0; m * 3 < images; ++m) {
    Json mat{{"name", "material" + std::to_string(m)},
             {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", m * 3}}}}}};
    if (m * 3 + 1 < images) mat["normalTexture"] = {{"index", m * 3 + 1}};
    if (m * 3 + 2 < images) mat["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {{"index", m * 3 + 2}};
    b.root["materials"].push_back(mat);
  }
}

bool writeFile(const fs::path& path, const void* data, size_t size) {
  std::ofstream out(path, std::ios::binary);
  out.write(static_cast<const char*>(data), std::streamsize(size));
  return bool(out);
}

int sponza(const fs::path& dir, size_t triangles, int images) {
  fs::create_directories(dir / "images");
  constexpr int kSide = 1024, kMeshes = 100;
  const std::vector<std::vector<uint8_t>> encoded = encodeImages(images, kSide);
  std::vector<std::string> uris;
  for (int i = 0; i < images; ++i) {
    const std::string uri = "images/tex" + std::to_string(i) + (i % 3 == 0 ? ".jpg" : ".png");
    if (!writeFile(dir / uri, encoded[size_t(i)].data(), encoded[size_t(i)].size())) return 1;
    uris.push_back(uri);
  }
  Builder b;
  addMaterials(b, images, uris);
  const int materials = int(b.root["materials"].size());
  for (int m = 0; m < kMeshes; ++m)
    b.addGrid(triangles / kMeshes, float(m % 10) * 6 - 30, float(m / 10) * 6 - 30, 5.5f, m % materials, uint32_t(m));
  b.finish();
  b.root["buffers"].push_back({{"uri", "scene.bin"}, {"byteLength", b.bin.size()}});
  if (!writeFile(dir / "scene.bin", b.bin.data(), b.bin.size())) return 1;
  const std::string json = b.root.dump();
  if (!writeFile(dir / "scene.gltf", json.data(), json.size())) return 1;
  std::printf("wrote %s (%zu triangles, %d meshes, %d images)\n", (dir / "scene.gltf").c_str(), triangles, kMeshes,
              images);
  return 0;
}

// Images embedded in the GLB's binary chunk.
int big(const fs::path& out, size_t triangles) {
  constexpr int kTiles = 40, kImages = 2, kSide = 1024;
  Builder b;
  const std::vector<std::vector<uint8_t>> encoded = encodeImages(kImages, kSide);
  addMaterials(b, kImages, {});
  for (int i = 0; i < kImages; ++i) {
    const int v = b.view(encoded[size_t(i)].data(), encoded[size_t(i)].size(), 0);
    b.root["images"][size_t(i)] = {{"bufferView", v}, {"mimeType", i % 3 == 0 ? "image/jpeg" : "image/png"}};
  }
  for (int t = 0; t < kTiles; ++t)
    b.addGrid(triangles / kTiles, float(t % 8) * 8 - 32, float(t / 8) * 8 - 20, 7.5f, 0, uint32_t(t));
  b.finish();
  while (b.bin.size() % 4) b.bin.push_back(0);
  b.root["buffers"].push_back({{"byteLength", b.bin.size()}});
  std::string json = b.root.dump();
  while (json.size() % 4) json += ' ';
  std::vector<uint8_t> glb;
  const uint32_t total = uint32_t(12 + 8 + json.size() + 8 + b.bin.size());
  const uint32_t header[3] = {0x46546C67u, 2u, total};
  writeBytes(glb, header, 12);
  const uint32_t jsonChunk[2] = {uint32_t(json.size()), 0x4E4F534Au};
  writeBytes(glb, jsonChunk, 8);
  writeBytes(glb, json.data(), json.size());
  const uint32_t binChunk[2] = {uint32_t(b.bin.size()), 0x004E4942u};
  writeBytes(glb, binChunk, 8);
  writeBytes(glb, b.bin.data(), b.bin.size());
  if (out.has_parent_path()) fs::create_directories(out.parent_path());
  if (!writeFile(out, glb.data(), glb.size())) return 1;
  std::printf("wrote %s (%zu triangles, %d meshes, %d images, %zu MB)\n", out.c_str(), triangles, kTiles, kImages,
              glb.size() >> 20);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string what = argc > 2 ? argv[1] : "";
  if (what == "sponza")
    return sponza(argv[2], argc > 3 ? std::stoul(argv[3]) : 260000, argc > 4 ? std::stoi(argv[4]) : 70);
  if (what == "big") return big(argv[2], argc > 3 ? std::stoul(argv[3]) : 10000000);
  std::fprintf(stderr,
               "usage: rayster-make-scene sponza OUT_DIR [TRIANGLES] [IMAGES]\n"
               "       rayster-make-scene big OUT.glb [TRIANGLES]\n");
  return 2;
}
