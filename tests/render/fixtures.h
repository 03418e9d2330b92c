#pragma once
// Small scene files written by the tests themselves: an alpha-masked glTF and a scene file with an
// HDR environment. Every byte is generated here, so the tests need no downloaded assets.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/image_io.h"

namespace rayster::test {

inline std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = uint32_t(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= uint32_t(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) v |= bytes[i + 2];
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? k[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? k[v & 63] : '=';
  }
  return out;
}

template <class T>
void appendBytes(std::vector<uint8_t>& buf, const std::vector<T>& values) {
  size_t at = buf.size();
  buf.resize(at + values.size() * sizeof(T));
  std::memcpy(buf.data() + at, values.data(), values.size() * sizeof(T));
}

// A white floor (y = 0, 6×6 m) and, standing on it, a 2×2 m quad facing +Z with a checkerboard
// texture whose dark squares are transparent (alphaMode MASK, cutoff 0.5). A point light behind the
// camera throws the checker's shadow on the floor; the camera looks at the quad from +Z.
inline std::filesystem::path writeAlphaMaskGltf(const std::filesystem::path& dir) {
  Image8 checker = Image8::make(64, 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      bool hole = ((x / 16) + (y / 16)) % 2 == 1;
      uint8_t* p = checker.pixel(x, y);
      p[0] = 230, p[1] = 60, p[2] = 40, p[3] = hole ? 0 : 255;
    }
  (void)writePng(dir / "checker.png", checker);

  // Floor quad then the masked quad: position, normal, uv; indices.
  std::vector<float> pos = {-3, 0, -3, 3, 0, -3, 3, 0, 3, -3, 0, 3, -1, 0.2f, 0, 1, 0.2f, 0, 1, 2.2f, 0, -1, 2.2f, 0};
  std::vector<float> nrm = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  std::vector<float> uv = {0, 0, 1, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 0, 0, 0};
  std::vector<uint16_t> idx = {0, 2, 1, 0, 3, 2, 0, 1, 2, 0, 2, 3};
  std::vector<uint8_t> buf;
  appendBytes(buf, pos);
  appendBytes(buf, nrm);
  appendBytes(buf, uv);
  appendBytes(buf, idx);
  const size_t posOff = 0, nrmOff = 96, uvOff = 192, idxOff = 256;
  std::string json = R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_lights_punctual"],
  "scene": 0,
  "scenes": [{"nodes": [0, 1, 2, 3]}],
  "nodes": [
    {"mesh": 0, "name": "floor"},
    {"mesh": 1, "name": "masked"},
    {"camera": 0, "translation": [0, 1.6, 5.5], "rotation": [-0.0998, 0, 0, 0.995]},
    {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [1.5, 3.5, 6], "extras": {}}
  ],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.6, "znear": 0.05, "zfar": 50, "aspectRatio": 1.333}}],
  "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 60, "color": [1, 1, 1], "extras": {"radius": 0.05}}]}},
  "meshes": [
    {"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 2}, "indices": 4, "material": 0}]},
    {"primitives": [{"attributes": {"POSITION": 1, "NORMAL": 3, "TEXCOORD_0": 6}, "indices": 5, "material": 1}]}
  ],
  "materials": [
    {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0, "roughnessFactor": 1}},
    {"name": "checker", "doubleSided": true, "alphaMode": "MASK", "alphaCutoff": 0.5,
     "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0, "roughnessFactor": 1}}
  ],
  "textures": [{"source": 0, "sampler": 0}],
  "samplers": [{"magFilter": 9728, "minFilter": 9728}],
  "images": [{"uri": "checker.png"}],
  "buffers": [{"byteLength": )" +
                     std::to_string(buf.size()) + R"(, "uri": "data:application/octet-stream;base64,)" + base64(buf) +
                     R"("}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 96, "byteStride": 12},
    {"buffer": 0, "byteOffset": 96, "byteLength": 96, "byteStride": 12},
    {"buffer": 0, "byteOffset": 192, "byteLength": 64},
    {"buffer": 0, "byteOffset": 256, "byteLength": 24}
  ],
  "accessors": [
    {"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-3, 0, -3], "max": [3, 0, 3]},
    {"bufferView": 0, "byteOffset": 48, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, 0.2, 0], "max": [1, 2.2, 0]},
    {"bufferView": 1, "byteOffset": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 1, "byteOffset": 48, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 3, "byteOffset": 0, "componentType": 5123, "count": 6, "type": "SCALAR"},
    {"bufferView": 3, "byteOffset": 12, "componentType": 5123, "count": 6, "type": "SCALAR"},
    {"bufferView": 2, "byteOffset": 32, "componentType": 5126, "count": 4, "type": "VEC2"}
  ]
})";
  (void)posOff, (void)nrmOff, (void)uvOff, (void)idxOff;
  auto path = dir / "alpha-mask.gltf";
  std::ofstream(path) << json;
  return path;
}

// A scene file placing the alpha-mask model under an HDR environment: an equirect map with a warm
// bright band above the horizon and a blue-to-dark gradient, written as EXR.
inline std::filesystem::path writeEnvironmentSceneFile(const std::filesystem::path& dir) {
  writeAlphaMaskGltf(dir);
  ImageF env = ImageF::make(128, 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 128; ++x) {
      float v = (y + 0.5f) / 64.0f;  // 0 at the zenith
      float* p = env.pixel(x, y);
      bool sunBand = v > 0.30f && v < 0.36f && x > 40 && x < 56;
      p[0] = sunBand ? 40.0f : 0.2f + 0.4f * (1 - v);
      p[1] = sunBand ? 30.0f : 0.3f + 0.5f * (1 - v);
      p[2] = sunBand ? 20.0f : 0.6f + 0.6f * (1 - v) * (v < 0.5f ? 1.0f : 0.1f);
      p[3] = 1.0f;
    }
  (void)writeExr(dir / "env.exr", env);
  auto path = dir / "env-scene.json";
  std::ofstream(path) << R"({
  "models": [{"path": "alpha-mask.gltf"}],
  "environment": {"map": "env.exr", "intensity": 1.0, "rotation": 30},
  "cameras": [{"name": "wide", "position": [3.5, 2.5, 6], "target": [0, 1, 0], "yfov": 50}]
})";
  return path;
}

}  // namespace rayster::test

namespace rayster::test {

// A grey floor and a red 1×2 m quad standing on it, facing +Z, that slides from x = −1.5 (t = 0 s)
// to x = +1.5 (t = 1 s) by a LINEAR translation animation and rests there until t = 2 s (the loop
// point); a hard point light above the camera.
inline std::filesystem::path writeAnimatedGltf(const std::filesystem::path& dir) {
  std::vector<float> pos = {-3, 0, -3, 3, 0, -3, 3, 0, 3, -3, 0, 3, -0.5f, 0, 0, 0.5f, 0, 0, 0.5f, 2, 0, -0.5f, 2, 0};
  std::vector<float> nrm = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  std::vector<uint16_t> idx = {0, 2, 1, 0, 3, 2, 0, 1, 2, 0, 2, 3};
  std::vector<float> times = {0, 1, 2};
  std::vector<float> moves = {-1.5f, 0, 0, 1.5f, 0, 0, 1.5f, 0, 0};
  std::vector<uint8_t> buf;
  appendBytes(buf, pos);    // 0..96
  appendBytes(buf, nrm);    // 96..192
  appendBytes(buf, idx);    // 192..216
  appendBytes(buf, times);  // 216..228
  appendBytes(buf, moves);  // 228..264
  std::string json = R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_lights_punctual"],
  "scene": 0,
  "scenes": [{"nodes": [0, 1, 2, 3]}],
  "nodes": [
    {"mesh": 0, "name": "floor"},
    {"mesh": 1, "name": "slider", "translation": [-1.5, 0, 0]},
    {"camera": 0, "translation": [0, 1.6, 5.5], "rotation": [-0.0998, 0, 0, 0.995]},
    {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0.5, 4, 3]}
  ],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05, "zfar": 50, "aspectRatio": 1.333}}],
  "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 80, "color": [1, 1, 1]}]}},
  "meshes": [
    {"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 2}, "indices": 4, "material": 0}]},
    {"primitives": [{"attributes": {"POSITION": 1, "NORMAL": 3}, "indices": 5, "material": 1}]}
  ],
  "materials": [
    {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0, "roughnessFactor": 1}},
    {"name": "red", "doubleSided": true,
     "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.1, 0.05, 1], "metallicFactor": 0, "roughnessFactor": 1}}
  ],
  "animations": [{"name": "slide", "channels": [{"sampler": 0, "target": {"node": 1, "path": "translation"}}],
                  "samplers": [{"input": 6, "output": 7, "interpolation": "LINEAR"}]}],
  "buffers": [{"byteLength": )" +
                     std::to_string(buf.size()) + R"(, "uri": "data:application/octet-stream;base64,)" + base64(buf) +
                     R"("}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 96, "byteStride": 12},
    {"buffer": 0, "byteOffset": 96, "byteLength": 96, "byteStride": 12},
    {"buffer": 0, "byteOffset": 192, "byteLength": 24},
    {"buffer": 0, "byteOffset": 216, "byteLength": 12},
    {"buffer": 0, "byteOffset": 228, "byteLength": 36}
  ],
  "accessors": [
    {"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-3, 0, -3], "max": [3, 0, 3]},
    {"bufferView": 0, "byteOffset": 48, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-0.5, 0, 0], "max": [0.5, 2, 0]},
    {"bufferView": 1, "byteOffset": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 1, "byteOffset": 48, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 2, "byteOffset": 0, "componentType": 5123, "count": 6, "type": "SCALAR"},
    {"bufferView": 2, "byteOffset": 12, "componentType": 5123, "count": 6, "type": "SCALAR"},
    {"bufferView": 3, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "SCALAR", "min": [0], "max": [2]},
    {"bufferView": 4, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3"}
  ]
})";
  auto path = dir / "animated.gltf";
  std::ofstream(path) << json;
  return path;
}

}  // namespace rayster::test
