#pragma once
// Building blocks for the analytic render tests (test_analytic.cpp): unit meshes written as glTF
// with one material each, a scene file that places them, the camera's pixel rays (to know which
// world point a pixel shows), and a render that returns the linear HDR image and AOVs.
// Everything goes through the public interfaces only: scene-file syntax, CLI flags, AOV names.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "core/image.h"
#include "core/image_io.h"
#include "core/metrics.h"
#include "tests/render/fixtures.h"
#include "tests/render/run_rayster.h"

namespace rayster::test::analytic {

// glTF metallic-roughness material with the extensions the renderer reads.
struct MaterialSpec {
  glm::vec3 baseColor{0.8f};
  float metallic = 0.0f;
  float roughness = 1.0f;
  glm::vec3 emissive{0.0f};  // linear radiance, any magnitude (split into factor × strength)
  float transmission = 0.0f;
  float ior = 1.5f;
  float thickness = 0.0f;  // > 0: a volume (refracts through its back face); 0: thin-walled
  bool unlit = false;      // KHR_materials_unlit
  float specular = 1.0f;   // KHR_materials_specular
  glm::vec3 specularColor{1.0f};
  std::string specularTexture;       // a PNG in the scene's folder (A: specular), or none
  std::string specularColorTexture;  // a PNG in the scene's folder (RGB, sRGB), or none
  std::string alphaMode = "OPAQUE";
  float alphaCutoff = 0.5f;
  // More material extensions, as JSON members of "extensions" (e.g. a KHR_materials_clearcoat
  // object); "$TEX" in it becomes the index of the texture `layerTexture` (a PNG in the folder).
  std::string layers;
  std::string layerTexture;
};

inline MaterialSpec blackAbsorber() { return {glm::vec3(0.0f), 1.0f, 1.0f}; }  // black rough metal: reflects nothing
inline MaterialSpec emitter(float radiance) {
  MaterialSpec m = blackAbsorber();
  m.emissive = glm::vec3(radiance);
  return m;
}
inline MaterialSpec glass(float ior, float thickness) {
  MaterialSpec m{glm::vec3(1.0f), 0.0f, 0.0f};
  m.transmission = 1.0f;
  m.ior = ior;
  m.thickness = thickness;
  return m;
}

struct Mesh {
  std::vector<float> positions, normals;  // xyz per vertex
  std::vector<uint32_t> indices;          // counter-clockwise seen from the side the normal points to
  std::vector<uint8_t> colors;            // RGBA per vertex (COLOR_0, normalized bytes), or none
};

// The unit square [-0.5, 0.5]² in the plane z = 0, facing +Z.
inline Mesh unitQuad() {
  return {{-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0.5f, 0.5f, 0, -0.5f, 0.5f, 0},
          {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1},
          {0, 1, 2, 0, 2, 3}};
}

// The unit sphere (radius 0.5, like the other unit meshes), `rings` × 2·`rings` quads with smooth
// normals, wound outward.
inline Mesh unitSphere(int rings) {
  Mesh m;
  const int segments = 2 * rings;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const float theta = float(r) / rings * 3.14159265f, phi = float(s) / segments * 6.2831853f;
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
      for (int k = 0; k < 3; ++k) {
        m.positions.push_back(0.5f * n[k]);
        m.normals.push_back(n[k]);
      }
    }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const uint32_t a = uint32_t(r * (segments + 1) + s), b = a + uint32_t(segments + 1);
      m.indices.insert(m.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  return m;
}

// The unit cube [-0.5, 0.5]³, closed, every face wound outward (the bounce loop tells entering
// from leaving a volume by the winding).
inline Mesh unitBox() {
  Mesh m;
  const glm::vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int a = 0; a < 3; ++a)
    for (float sign : {1.0f, -1.0f}) {
      glm::vec3 n = axes[a] * sign, u = axes[(a + 1) % 3], v = glm::cross(n, u);
      uint32_t base = uint32_t(m.positions.size() / 3);
      for (glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
        glm::vec3 p = 0.5f * (n + c.x * u + c.y * v);
        m.positions.insert(m.positions.end(), {p.x, p.y, p.z});
        m.normals.insert(m.normals.end(), {n.x, n.y, n.z});
      }
      m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
  return m;
}

inline std::string vec3Json(glm::vec3 v) { return fmt::format("[{}, {}, {}]", v.x, v.y, v.z); }

// Writes dir/name.gltf: one mesh, one material, the buffer embedded as a data URI.
inline void writeGltf(const std::filesystem::path& dir, const std::string& name, const Mesh& mesh,
                      const MaterialSpec& mat) {
  std::vector<uint8_t> buf;
  appendBytes(buf, mesh.positions);
  appendBytes(buf, mesh.normals);
  appendBytes(buf, mesh.indices);
  const size_t colorOffset = buf.size();  // 4-byte aligned: everything before is 4-byte data
  appendBytes(buf, mesh.colors);
  const size_t vertexBytes = mesh.positions.size() * 4, vertices = mesh.positions.size() / 3;
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (size_t i = 0; i < vertices; ++i) {
    glm::vec3 p(mesh.positions[3 * i], mesh.positions[3 * i + 1], mesh.positions[3 * i + 2]);
    lo = glm::min(lo, p), hi = glm::max(hi, p);
  }
  const float peak = std::max(mat.emissive.x, std::max(mat.emissive.y, mat.emissive.z));
  const glm::vec3 emissiveFactor = peak > 0 ? mat.emissive / peak : glm::vec3(0.0f);
  std::string extensions =
      fmt::format(R"("KHR_materials_emissive_strength": {{"emissiveStrength": {}}})", peak > 0 ? peak : 1.0f);
  if (mat.transmission > 0)
    extensions += fmt::format(R"(, "KHR_materials_transmission": {{"transmissionFactor": {}}})", mat.transmission);
  if (mat.transmission > 0 || mat.ior != 1.5f)
    extensions += fmt::format(R"(, "KHR_materials_ior": {{"ior": {}}})", mat.ior);
  if (mat.thickness > 0)
    extensions += fmt::format(R"(, "KHR_materials_volume": {{"thicknessFactor": {}}})", mat.thickness);
  if (mat.unlit) extensions += R"(, "KHR_materials_unlit": {})";
  // Textures: one image and texture per file, in the order first used.
  std::vector<std::string> images;
  auto textureIndex = [&](const std::string& file) {
    for (size_t i = 0; i < images.size(); ++i)
      if (images[i] == file) return i;
    images.push_back(file);
    return images.size() - 1;
  };
  if (mat.specular != 1.0f || mat.specularColor != glm::vec3(1.0f) || !mat.specularTexture.empty() ||
      !mat.specularColorTexture.empty()) {
    std::string spec =
        fmt::format(R"("specularFactor": {}, "specularColorFactor": {})", mat.specular, vec3Json(mat.specularColor));
    if (!mat.specularTexture.empty())
      spec += fmt::format(R"(, "specularTexture": {{"index": {}}})", textureIndex(mat.specularTexture));
    if (!mat.specularColorTexture.empty())
      spec += fmt::format(R"(, "specularColorTexture": {{"index": {}}})", textureIndex(mat.specularColorTexture));
    extensions += fmt::format(R"(, "KHR_materials_specular": {{{}}})", spec);
  }
  if (!mat.layers.empty()) {
    std::string layers = mat.layers;
    if (const size_t at = layers.find("$TEX"); at != std::string::npos)
      layers.replace(at, 4, std::to_string(textureIndex(mat.layerTexture)));
    extensions += ", " + layers;
  }
  // A textured material needs the UVs its textures read (glTF: MESH_PRIMITIVE_TOO_FEW_TEXCOORDS is an
  // error): planar ones from x and y, appended to the buffer and added to the JSON below.
  size_t uvOffset = 0;
  if (!images.empty()) {
    while (buf.size() % 4) buf.push_back(0);
    uvOffset = buf.size();
    std::vector<float> uvs;
    for (size_t i = 0; i < vertices; ++i)
      uvs.insert(uvs.end(), {mesh.positions[3 * i] + 0.5f, 0.5f - mesh.positions[3 * i + 1]});
    appendBytes(buf, uvs);
  }
  std::string textures;
  if (!images.empty()) {
    std::string imageList, textureList;
    for (size_t i = 0; i < images.size(); ++i) {
      imageList += fmt::format(R"({}{{"uri": "{}"}})", i ? ", " : "", images[i]);
      textureList += fmt::format(R"({}{{"source": {}}})", i ? ", " : "", i);
    }
    textures = fmt::format(R"(,
  "images": [{}], "textures": [{}])",
                           imageList, textureList);
  }
  std::string colorAttribute, colorParts;
  if (!mesh.colors.empty()) {
    colorAttribute = R"(, "COLOR_0": 3)";
    colorParts = fmt::format(
        R"(, {{"bufferView": 3, "componentType": 5121, "normalized": true, "count": {}, "type": "VEC4"}})", vertices);
  }
  const std::string colorView =
      mesh.colors.empty()
          ? ""
          : fmt::format(R"(, {{"buffer": 0, "byteOffset": {}, "byteLength": {}}})", colorOffset, mesh.colors.size());
  const std::string alpha = mat.alphaMode == "OPAQUE" ? ""
                                                      : fmt::format(R"("alphaMode": "{}", "alphaCutoff": {}, )",
                                                                    mat.alphaMode, mat.alphaCutoff);
  std::string json = fmt::format(
      R"({{
  "asset": {{"version": "2.0"}},
  "extensionsUsed": ["KHR_materials_emissive_strength", "KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume",
                     "KHR_materials_unlit", "KHR_materials_specular"],
  "scene": 0, "scenes": [{{"nodes": [0]}}], "nodes": [{{"mesh": 0, "name": "{0}"}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1{17}}}, "indices": 2, "material": 0}}]}}],
  "materials": [{{"name": "{0}", "doubleSided": true, {20}"emissiveFactor": {1},
    "pbrMetallicRoughness": {{"baseColorFactor": [{2}, {3}, {4}, 1], "metallicFactor": {5}, "roughnessFactor": {6}}},
    "extensions": {{{7}}}}}],
  "buffers": [{{"byteLength": {8}, "uri": "data:application/octet-stream;base64,{9}"}}],
  "bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": {10}}}, {{"buffer": 0, "byteOffset": {10}, "byteLength": {10}}},
                  {{"buffer": 0, "byteOffset": {11}, "byteLength": {12}}}{19}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": {13}, "type": "VEC3", "min": {14}, "max": {15}}},
    {{"bufferView": 1, "componentType": 5126, "count": {13}, "type": "VEC3"}},
    {{"bufferView": 2, "componentType": 5125, "count": {16}, "type": "SCALAR"}}{18}]{21}
}})",
      name, vec3Json(emissiveFactor), mat.baseColor.x, mat.baseColor.y, mat.baseColor.z, mat.metallic, mat.roughness,
      extensions, buf.size(), base64(buf), vertexBytes, 2 * vertexBytes, mesh.indices.size() * 4, vertices,
      vec3Json(lo), vec3Json(hi), mesh.indices.size(), colorAttribute, colorParts, colorView, alpha, textures);
  if (!images.empty()) {
    nlohmann::json j = nlohmann::json::parse(json);
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", uvOffset}, {"byteLength", vertices * 8}});
    j["accessors"].push_back(
        {{"bufferView", j["bufferViews"].size() - 1}, {"componentType", 5126}, {"count", vertices}, {"type", "VEC2"}});
    j["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = j["accessors"].size() - 1;
    json = j.dump(1);
  }
  std::ofstream(dir / (name + ".gltf")) << json;
}

// One model of a scene file: a unit mesh scaled, rotated (degrees, R = Rz·Ry·Rx), translated.
struct Placed {
  std::string name;
  Mesh mesh;
  MaterialSpec material;
  glm::vec3 scale{1.0f}, rotate{0.0f}, translate{0.0f};
};

struct CameraSpec {
  glm::vec3 position{0, 0, 5}, target{0, 0, 0};
  float yfovDeg = 40.0f;
};

struct SceneSpec {
  std::vector<Placed> models;
  std::vector<std::string> lights;  // scene-file light objects, as JSON
  CameraSpec camera;
  std::string environment = R"("black")";
};

// A light that is there only so the loader adds no default sun: it emits nothing.
inline std::string darkLight() { return R"({"type": "point", "position": [0, 100, 0], "intensity": 0})"; }
// A uniform environment of radiance `L` in every direction (the procedural sky, one colour).
inline std::string uniformEnvironment(float L) {
  return fmt::format(
      R"({{"sky": {{"zenith": [1, 1, 1], "horizon": [1, 1, 1], "ground": [1, 1, 1]}}, "intensity": {}}})", L);
}

inline std::filesystem::path writeScene(const std::filesystem::path& dir, const std::string& name, const SceneSpec& s) {
  std::string models, lights;
  for (const Placed& m : s.models) {
    writeGltf(dir, m.name, m.mesh, m.material);
    models +=
        fmt::format(R"({}{{"path": "{}.gltf", "scale": {}, "rotate": {}, "translate": {}}})",
                    models.empty() ? "" : ", ", m.name, vec3Json(m.scale), vec3Json(m.rotate), vec3Json(m.translate));
  }
  for (const std::string& l : s.lights) lights += (lights.empty() ? "" : ", ") + l;
  auto path = dir / (name + ".json");
  std::ofstream(path) << fmt::format(
      R"({{"models": [{}], "lights": [{}], "environment": {},
  "cameras": [{{"name": "test", "position": {}, "target": {}, "yfov": {}, "znear": 0.05, "zfar": 200}}]}})",
      models, lights, s.environment, vec3Json(s.camera.position), vec3Json(s.camera.target), s.camera.yfovDeg);
  return path;
}

// The world-space ray through the centre of pixel (x, y) (top row first), for the camera model of
// the scene format: look-at with +Y up, vertical field of view, square pixels.
struct Ray {
  glm::vec3 origin, dir;
};
inline Ray pixelRay(const CameraSpec& c, int width, int height, double x, double y) {
  const glm::vec3 forward = glm::normalize(c.target - c.position);
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  const glm::vec3 up = glm::cross(right, forward);
  const float t = std::tan(glm::radians(c.yfovDeg) * 0.5f), aspect = float(width) / float(height);
  const float ndcX = float((x + 0.5) / width * 2 - 1), ndcY = float((y + 0.5) / height * 2 - 1);
  return {c.position, glm::normalize(forward + right * (ndcX * t * aspect) - up * (ndcY * t))};
}

// Where a pixel's ray meets the plane y = height (false if it does not, going forward).
inline bool hitHorizontal(const Ray& r, float height, glm::vec3& p) {
  if (std::abs(r.dir.y) < 1e-6f) return false;
  float s = (height - r.origin.y) / r.dir.y;
  p = r.origin + s * r.dir;
  return s > 0;
}

struct Rendered {
  ImageF hdr;
  std::map<std::string, ImageF> aovs;
};

// Renders `scene` with the real binary (validation on), reads the linear HDR image (EXR) and the
// AOVs' EXRs, and fails the test on any error or an empty (non-finite, uniform, wrong-size) HDR.
inline Rendered renderHdr(const std::filesystem::path& dir, const std::string& name, const std::filesystem::path& scene,
                          int w, int h, int frames, const std::string& aovs = "", const std::string& extra = "") {
  Rendered out;
  auto png = dir / (name + ".png");
  auto exr = dir / (name + ".exr");
  // No TAA unless `extra` asks for it: its sub-pixel jitter would move the pixel centres the closed
  // forms are evaluated at. Seed 7 unless `extra` names one.
  const std::string seed = extra.find("--seed") == std::string::npos ? "--seed 7" : "";
  const std::string taa = extra.find("--taa") == std::string::npos ? "--taa off" : "";
  std::string args = fmt::format("render {} --size {}x{} --frames {} {} {} --hdr {} -o {} {}", scene.string(), w, h,
                                 frames, seed, taa, exr.string(), png.string(), extra);
  if (!aovs.empty()) args += " --aov " + aovs;
  RunResult r = runRayster(args);
  EXPECT_EQ(r.exitCode, 0) << r.output;
  auto hdr = readExr(exr);
  EXPECT_TRUE(hdr.ok()) << (hdr.ok() ? "" : hdr.error().message);
  if (!hdr.ok()) return out;
  auto empty = rejectEmpty(*hdr, w, h);
  EXPECT_FALSE(empty.has_value()) << name << ": " << empty.value_or("");
  out.hdr = std::move(hdr).value();
  size_t start = 0;
  while (!aovs.empty() && start <= aovs.size()) {
    size_t comma = aovs.find(',', start);
    std::string aov = aovs.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    auto img = readExr(dir / (name + "." + aov + ".exr"));
    EXPECT_TRUE(img.ok()) << aov << ": " << (img.ok() ? "" : img.error().message);
    if (img.ok()) {
      EXPECT_EQ(img->width, w);
      EXPECT_EQ(img->height, h);
      size_t nonFinite = 0;
      for (float v : img->rgba) nonFinite += !std::isfinite(v);
      EXPECT_EQ(nonFinite, 0u) << aov << " has non-finite values";
      out.aovs[aov] = std::move(img).value();
    }
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

}  // namespace rayster::test::analytic
