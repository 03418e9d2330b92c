#include "scene/obj_loader.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

// Debian ships tinyobjloader and stb compiled (core/image_io.cpp holds stb's implementation), so
// neither IMPLEMENTATION macro is defined here.
#include <stb/stb_image.h>
#include <tiny_obj_loader.h>

#include "core/image_io.h"
#include "core/log.h"
#include "scene/loader.h"

namespace rayster::scene {
namespace fs = std::filesystem;
namespace {

// Larger than any GPU's 2D image limit that Rayster targets; also stops a hostile PNG header
// from asking for gigabytes.
constexpr int kMaxTextureSide = 16384;

bool isSpace(char c) { return c == ' ' || c == '\t'; }

// Splits like tinyobjloader's safeGetline ("\n", "\r\n" or a lone "\r") so line numbers agree.
template <class Fn>
void forEachLine(std::string_view text, Fn&& fn) {
  size_t pos = 0, lineNumber = 0;
  while (pos < text.size()) {
    const size_t end = text.find_first_of("\r\n", pos);
    fn(++lineNumber, text.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos));
    if (end == std::string_view::npos) break;
    pos = end + 1;
    if (text[end] == '\r' && pos < text.size() && text[pos] == '\n') ++pos;
  }
}

// The keyword of an OBJ line ("v", "vt", "f", ...) and the rest after it.
std::string_view keyword(std::string_view line, std::string_view* rest) {
  size_t start = 0;
  while (start < line.size() && isSpace(line[start])) ++start;
  size_t end = start;
  while (end < line.size() && !isSpace(line[end])) ++end;
  *rest = line.substr(end);
  return line.substr(start, end - start);
}

struct AttributeCounts {
  int64_t v = 0, vt = 0, vn = 0;
};

// Checks one index field of a face corner: 1-based, or negative relative to what precedes it.
Status checkIndex(std::string_view field, const char* kind, int64_t soFar, int64_t total, const std::string& where) {
  int64_t value = 0;
  const char* first = field.data();
  if (!field.empty() && field[0] == '+') ++first;
  auto [ptr, ec] = std::from_chars(first, field.data() + field.size(), value);
  if (ec == std::errc::result_out_of_range || value > INT_MAX || value < INT_MIN)
    return makeError(ExitCode::BadInput, "{}: face {} index '{}' is out of range", where, kind, field);
  if (ec != std::errc() || ptr == first)
    return makeError(ExitCode::BadInput, "{}: face {} index '{}' is not a number", where, kind, field);
  if (value == 0) return makeError(ExitCode::BadInput, "{}: face {} index 0 (OBJ indices start at 1)", where, kind);
  if (value > total)
    return makeError(ExitCode::BadInput, "{}: face {} index {} is past the {} {}s in the file", where, kind, value,
                     total, kind);
  if (value < 0 && soFar + value < 0)
    return makeError(ExitCode::BadInput, "{}: relative face {} index {} points before the first {} ({} so far)", where,
                     kind, value, kind, soFar);
  return okStatus();
}

// Faces are triangulated (ear clipping, quadratic in the corners); a polygon of thousands of corners
// is a broken or hostile file, not a model.
constexpr size_t kMaxFaceVertices = 1024;

// The numbers of a "v", "vt" or "vn" line must be finite: a NaN or an overflow poisons every
// bounding box and acceleration structure built from it.
Status checkFiniteNumbers(std::string_view rest, const std::string& where, std::string_view key) {
  size_t pos = 0;
  while (pos < rest.size()) {
    while (pos < rest.size() && isSpace(rest[pos])) ++pos;
    size_t end = pos;
    while (end < rest.size() && !isSpace(rest[end])) ++end;
    if (end == pos) break;
    const std::string token(rest.substr(pos, end - pos));
    pos = end;
    char* stop = nullptr;
    const double v = std::strtod(token.c_str(), &stop);
    if (stop == token.c_str()) continue;  // not a number: tinyobjloader's parse decides
    if (!std::isfinite(v) || std::abs(v) > double(std::numeric_limits<float>::max()))
      return makeError(ExitCode::BadInput, "{}: {} coordinate '{}' is not a finite number", where, key, token);
  }
  return okStatus();
}

// Validates every face index before tinyobjloader sees the file, so errors name their line
// (tinyobjloader names only some, and drops quads with bad indices with just a warning).
Status checkFaceIndices(std::string_view text, const std::string& file) {
  AttributeCounts total;
  forEachLine(text, [&](size_t, std::string_view line) {
    std::string_view rest;
    std::string_view key = keyword(line, &rest);
    if (key == "v")
      ++total.v;
    else if (key == "vt")
      ++total.vt;
    else if (key == "vn")
      ++total.vn;
  });
  AttributeCounts soFar;
  Status status = okStatus();
  forEachLine(text, [&](size_t lineNumber, std::string_view line) {
    if (!status.ok()) return;
    std::string_view rest;
    std::string_view key = keyword(line, &rest);
    if (key == "v")
      ++soFar.v;
    else if (key == "vt")
      ++soFar.vt;
    else if (key == "vn")
      ++soFar.vn;
    if (key == "v" || key == "vt" || key == "vn") {
      status = checkFiniteNumbers(rest, fmt::format("{}:{}", file, lineNumber), key);
      return;
    }
    if (key != "f") return;
    const std::string where = fmt::format("{}:{}", file, lineNumber);
    size_t corners = 0;
    size_t pos = 0;
    while (pos < rest.size() && status.ok()) {
      while (pos < rest.size() && isSpace(rest[pos])) ++pos;
      size_t end = pos;
      while (end < rest.size() && !isSpace(rest[end])) ++end;
      if (end == pos) break;
      std::string_view corner = rest.substr(pos, end - pos);
      pos = end;
      if (++corners > kMaxFaceVertices) {
        status = makeError(ExitCode::BadInput,
                           "{}: a face of more than {} vertices (Rayster triangulates faces of "
                           "up to {})",
                           where, kMaxFaceVertices, kMaxFaceVertices);
        break;
      }
      // v, v/vt, v//vn or v/vt/vn: an empty field means "not given".
      const char* kinds[3] = {"vertex", "texcoord", "normal"};
      const int64_t counts[3] = {soFar.v, soFar.vt, soFar.vn};
      const int64_t totals[3] = {total.v, total.vt, total.vn};
      for (int field = 0; field < 3 && status.ok(); ++field) {
        size_t slash = corner.find('/');
        std::string_view value = corner.substr(0, slash);
        if (field == 0 || !value.empty()) status = checkIndex(value, kinds[field], counts[field], totals[field], where);
        if (slash == std::string_view::npos) break;
        corner.remove_prefix(slash + 1);
      }
    }
  });
  return status;
}

// Opens mtllib files for tinyobjloader, but only inside the OBJ's folder.
class ConfinedMtlReader : public tinyobj::MaterialReader {
 public:
  ConfinedMtlReader(fs::path dir, std::string file) : dir_(std::move(dir)), file_(std::move(file)) {}

  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* materialMap, std::string* warn, std::string* err) override {
    if (error) return false;
    Result<fs::path> path = resolveRelativePath(dir_, name, fmt::format("{}: mtllib", file_));
    if (!path) {
      error = path.error();
      return false;
    }
    std::ifstream in(*path);
    if (!in || fs::is_directory(*path)) {
      *warn += fmt::format("material library '{}' not found, using a default material\n", name);
      missing = true;
      return false;
    }
    tinyobj::LoadMtl(materialMap, materials, &in, warn, err);
    return true;
  }

  std::optional<Error> error;
  bool missing = false;

 private:
  fs::path dir_;
  std::string file_;
};

// Decodes textures once per file into Scene::images/textures.
class TextureLoader {
 public:
  TextureLoader(Scene& scene, fs::path dir, std::string file)
      : scene_(scene), dir_(std::move(dir)), file_(std::move(file)) {}

  // -1 when the file is missing or undecodable (a warning: the model still renders).
  Result<int32_t> load(const std::string& ref, const std::string& what) {
    Result<fs::path> resolved = resolveRelativePath(dir_, ref, fmt::format("{}: {}", file_, what));
    if (!resolved) return resolved.error();
    const fs::path path = *resolved;
    if (auto it = cache_.find(path); it != cache_.end()) return it->second;
    Result<int32_t> index = decode(path, ref, what);
    if (index) cache_[path] = *index;
    return index;
  }

 private:
  Result<int32_t> decode(const fs::path& path, const std::string& ref, const std::string& what) {
    std::ifstream in(path, std::ios::binary);
    std::vector<uint8_t> bytes;
    if (in && !fs::is_directory(path)) bytes.assign(std::istreambuf_iterator<char>(in), {});
    if (bytes.empty() || bytes.size() > INT_MAX) {
      log::warn("{}: {} '{}' not found or unreadable, rendering without it", file_, what, ref);
      return -1;
    }
    // The hazard check comes first: stb's header parse (stbi_info) already reads the Huffman tables.
    if (const std::string hazard = stbDecodeHazard(bytes.data(), bytes.size()); !hazard.empty()) {
      log::warn("{}: {} '{}' cannot be decoded ({}), rendering without it", file_, what, ref, hazard);
      return -1;
    }
    int w = 0, h = 0, channels = 0;
    const int size = static_cast<int>(bytes.size());
    if (!stbi_info_from_memory(bytes.data(), size, &w, &h, &channels)) {
      log::warn("{}: {} '{}' cannot be decoded ({}), rendering without it", file_, what, ref,
                stbi_failure_reason() ? stbi_failure_reason() : "unknown format");
      return -1;
    }
    if (w <= 0 || h <= 0 || w > kMaxTextureSide || h > kMaxTextureSide)
      return makeError(ExitCode::BadInput, "{}: {} '{}' is {}x{}, more than the {} pixels per side Rayster accepts",
                       file_, what, ref, w, h, kMaxTextureSide);
    uint8_t* pixels = stbi_load_from_memory(bytes.data(), size, &w, &h, &channels, 4);
    if (!pixels) {
      log::warn("{}: {} '{}' cannot be decoded ({}), rendering without it", file_, what, ref,
                stbi_failure_reason() ? stbi_failure_reason() : "unknown error");
      return -1;
    }
    ImageData image;
    image.name = ref;
    image.width = w;
    image.height = h;
    image.rgba.assign(pixels, pixels + static_cast<size_t>(w) * h * 4);
    stbi_image_free(pixels);
    if (scene_.samplers.empty()) scene_.samplers.push_back(Sampler{});  // OBJ has no sampler state: repeat
    scene_.images.push_back(std::move(image));
    scene_.textures.push_back(Texture{static_cast<uint32_t>(scene_.images.size() - 1), 0});
    return static_cast<int32_t>(scene_.textures.size() - 1);
  }

  Scene& scene_;
  fs::path dir_;
  std::string file_;
  std::map<fs::path, int32_t> cache_;
};

glm::vec3 toVec3(const tinyobj::real_t* v) { return {v[0], v[1], v[2]}; }
bool isBlack(glm::vec3 c) { return c.x <= 0.0f && c.y <= 0.0f && c.z <= 0.0f; }

bool hasTransparentPixels(const ImageData& image) {
  for (size_t i = 3; i < image.rgba.size(); i += 4)
    if (image.rgba[i] < 255) return true;
  return false;
}

Result<Material> convertMaterial(const tinyobj::material_t& m, TextureLoader& textures, Scene& scene) {
  Material out;
  out.name = m.name;
  out.doubleSided = true;
  out.baseColor = glm::vec4(toVec3(m.diffuse), std::clamp(static_cast<float>(m.dissolve), 0.0f, 1.0f));
  if (!std::isfinite(out.baseColor.w)) out.baseColor.w = 1.0f;
  if (out.baseColor.w < 1.0f) out.alphaMode = AlphaMode::Blend;
  out.emissive = glm::max(toVec3(m.emission), glm::vec3(0.0f));
  // Blinn-Phong exponent to GGX roughness: the usual alpha = sqrt(2 / (Ns + 2)) match.
  const float ns = std::max(static_cast<float>(m.shininess), 0.0f);
  out.roughness = std::clamp(std::sqrt(2.0f / (ns + 2.0f)), 0.0f, 1.0f);
  const glm::vec3 kd = toVec3(m.diffuse), ks = toVec3(m.specular), tf = toVec3(m.transmittance);
  switch (m.illum) {
    case 3:
    case 5:  // "reflection on, ray trace on" (5: with Fresnel): a mirror
      out.metallic = 1.0f;
      out.roughness = 0.0f;
      out.baseColor = glm::vec4(isBlack(ks) ? kd : ks, out.baseColor.w);
      break;
    case 4:
    case 6:
    case 7:
    case 9:  // the glass / refraction models
      out.transmission = 1.0f;
      out.metallic = 0.0f;
      out.roughness = 0.0f;
      // tinyobjloader's Ni default is 1.0, which would make glass invisible: read it as "unset".
      out.ior = (m.ior > 0.0f && m.ior != 1.0f && std::isfinite(m.ior)) ? m.ior : 1.5f;
      out.baseColor = glm::vec4(!isBlack(tf) ? tf : !isBlack(kd) ? kd : glm::vec3(1.0f), out.baseColor.w);
      break;
    default:
      break;
  }
  out.baseColor = glm::clamp(out.baseColor, glm::vec4(0.0f), glm::vec4(FLT_MAX));
  if (!m.diffuse_texname.empty()) {
    Result<int32_t> texture = textures.load(m.diffuse_texname, fmt::format("material '{}' map_Kd", m.name));
    if (!texture) return texture.error();
    out.baseColorTexture.texture = *texture;
    // map_Kd usually comes with a placeholder Kd; black would hide the texture entirely.
    if (*texture >= 0 && isBlack(glm::vec3(out.baseColor)))
      out.baseColor = glm::vec4(1.0f, 1.0f, 1.0f, out.baseColor.w);
    // map_d next to a texture with an alpha channel means cut-outs (foliage), not blending.
    if (*texture >= 0 && !m.alpha_texname.empty() && out.alphaMode == AlphaMode::Opaque &&
        hasTransparentPixels(scene.images[scene.textures[*texture].image]))
      out.alphaMode = AlphaMode::Mask;
  }
  if (!m.normal_texname.empty()) {
    Result<int32_t> texture = textures.load(m.normal_texname, fmt::format("material '{}' norm", m.name));
    if (!texture) return texture.error();
    out.normalTexture.texture = *texture;
  }
  return out;
}

struct CornerKey {
  int v, vt, vn;
  bool operator==(const CornerKey&) const = default;
};
struct CornerHash {
  size_t operator()(const CornerKey& k) const {
    return std::hash<uint64_t>()((static_cast<uint64_t>(static_cast<uint32_t>(k.v)) << 32) ^
                                 (static_cast<uint64_t>(static_cast<uint32_t>(k.vt)) << 16) ^
                                 static_cast<uint32_t>(k.vn));
  }
};

// Collects one primitive's deduplicated vertices; normals missing in the file are generated last.
struct PrimitiveBuilder {
  Primitive prim;
  std::unordered_map<CornerKey, uint32_t, CornerHash> lookup;
  std::vector<int> positionIndex;  // OBJ vertex per primitive vertex, to smooth across UV seams
  std::vector<bool> hasNormal;
  bool anyUv = false;

  void add(const tinyobj::attrib_t& a, const tinyobj::index_t& idx) {
    const CornerKey key{idx.vertex_index, idx.texcoord_index, idx.normal_index};
    auto [it, inserted] = lookup.try_emplace(key, static_cast<uint32_t>(prim.positions.size()));
    prim.indices.push_back(it->second);
    if (!inserted) return;
    prim.positions.push_back(toVec3(&a.vertices[3 * static_cast<size_t>(idx.vertex_index)]));
    positionIndex.push_back(idx.vertex_index);
    glm::vec3 n(0.0f);
    if (idx.normal_index >= 0) n = toVec3(&a.normals[3 * static_cast<size_t>(idx.normal_index)]);
    const float len = glm::length(n);
    const bool usable = std::isfinite(len) && len > 1e-20f;
    prim.normals.push_back(usable ? n / len : glm::vec3(0.0f));
    hasNormal.push_back(usable);
    glm::vec2 uv(0.0f);
    if (idx.texcoord_index >= 0) {
      anyUv = true;
      const tinyobj::real_t* t = &a.texcoords[2 * static_cast<size_t>(idx.texcoord_index)];
      uv = glm::vec2(t[0], 1.0f - t[1]);  // OBJ's v grows upwards, glTF's downwards
      if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = glm::vec2(0.0f);
    }
    prim.uvs.push_back(uv);
    // `v x y z r g b`: tinyobjloader keeps colours only when every vertex line has them (we ask
    // for no white fallback). Read as linear, like glTF's COLOR_0, clamped to [0, 1].
    if (a.colors.size() == a.vertices.size()) {
      glm::vec3 c = glm::clamp(toVec3(&a.colors[3 * static_cast<size_t>(idx.vertex_index)]), 0.0f, 1.0f);
      if (!std::isfinite(c.x + c.y + c.z)) c = glm::vec3(1.0f);
      prim.colors.emplace_back(c, 1.0f);
    }
  }

  // Area-weighted smooth normals, accumulated per OBJ vertex; scratch is all zero on entry and exit.
  Primitive finish(std::vector<glm::vec3>& scratch) {
    if (!anyUv) prim.uvs.clear();
    bool missing = false;
    for (bool has : hasNormal) missing |= !has;
    if (!missing) return std::move(prim);
    for (size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
      const uint32_t a = prim.indices[t], b = prim.indices[t + 1], c = prim.indices[t + 2];
      const glm::vec3 area = glm::cross(prim.positions[b] - prim.positions[a], prim.positions[c] - prim.positions[a]);
      if (!std::isfinite(area.x + area.y + area.z)) continue;
      for (uint32_t v : {a, b, c}) scratch[positionIndex[v]] += area;
    }
    for (size_t v = 0; v < prim.normals.size(); ++v) {
      if (hasNormal[v]) continue;
      const glm::vec3 sum = scratch[positionIndex[v]];
      const float len = glm::length(sum);
      prim.normals[v] = (std::isfinite(len) && len > 0.0f) ? sum / len : glm::vec3(0, 1, 0);
    }
    for (int p : positionIndex) scratch[p] = glm::vec3(0.0f);
    return std::move(prim);
  }
};

// Every index is re-checked against what tinyobjloader actually parsed: the line-based pre-check
// and tinyobjloader may disagree on odd input (NUL bytes, stray '\r'), and this is what the copies
// below rely on. The message is only formatted on failure: this runs once per face corner.
Status checkCorner(const tinyobj::attrib_t& a, const tinyobj::index_t& idx, const std::string& file,
                   const std::string& object, size_t face) {
  const int64_t nv = static_cast<int64_t>(a.vertices.size() / 3), nvt = static_cast<int64_t>(a.texcoords.size() / 2),
                nvn = static_cast<int64_t>(a.normals.size() / 3);
  auto outOfRange = [&](const char* kind, int64_t index, int64_t count) {
    return makeError(ExitCode::BadInput, "{}: object '{}' face {}: {} index {} out of range ({} in the file)", file,
                     object, face, kind, index + 1, count);
  };
  if (idx.vertex_index < 0 || idx.vertex_index >= nv) return outOfRange("vertex", idx.vertex_index, nv);
  if (idx.texcoord_index < -1 || idx.texcoord_index >= nvt) return outOfRange("texcoord", idx.texcoord_index, nvt);
  if (idx.normal_index < -1 || idx.normal_index >= nvn) return outOfRange("normal", idx.normal_index, nvn);
  return okStatus();
}

// One Mesh per tinyobjloader shape (object/group), one Primitive per material in first-use order.
Status buildMeshes(Scene& scene, const tinyobj::attrib_t& attrib, const std::vector<tinyobj::shape_t>& shapes,
                   size_t mtlCount, const std::string& file) {
  std::optional<uint32_t> defaultMaterial;
  auto materialFor = [&](int id) -> uint32_t {
    if (id >= 0 && static_cast<size_t>(id) < mtlCount) return static_cast<uint32_t>(id);
    if (!defaultMaterial) {
      Material m;
      m.name = "default";
      m.baseColor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
      m.doubleSided = true;
      scene.materials.push_back(m);
      defaultMaterial = static_cast<uint32_t>(scene.materials.size() - 1);
    }
    return *defaultMaterial;
  };
  std::vector<glm::vec3> scratch(attrib.vertices.size() / 3, glm::vec3(0.0f));
  for (size_t s = 0; s < shapes.size(); ++s) {
    const tinyobj::mesh_t& mesh = shapes[s].mesh;
    const std::string name = shapes[s].name.empty() ? fmt::format("object {}", s) : shapes[s].name;
    std::vector<PrimitiveBuilder> builders;
    std::map<uint32_t, size_t> builderOf;
    size_t offset = 0;
    for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      const size_t n = mesh.num_face_vertices[f];
      if (offset + n > mesh.indices.size())
        return makeError(ExitCode::BadInput, "{}: object '{}' face {} has missing indices", file, name, f);
      for (size_t k = 0; k < n; ++k) RAYSTER_TRY(checkCorner(attrib, mesh.indices[offset + k], file, name, f));
      const uint32_t material = materialFor(f < mesh.material_ids.size() ? mesh.material_ids[f] : -1);
      auto [it, inserted] = builderOf.try_emplace(material, builders.size());
      if (inserted) builders.emplace_back().prim.material = material;
      PrimitiveBuilder& builder = builders[it->second];
      // tinyobjloader already triangulated; a fan covers anything it left as a polygon.
      for (size_t k = 1; k + 1 < n; ++k)
        for (size_t corner : {size_t{0}, k, k + 1}) builder.add(attrib, mesh.indices[offset + corner]);
      offset += n;
    }
    Mesh out;
    out.name = name;
    for (PrimitiveBuilder& builder : builders)
      if (!builder.prim.indices.empty()) out.primitives.push_back(builder.finish(scratch));
    if (out.primitives.empty()) continue;  // lines or points only
    scene.meshes.push_back(std::move(out));
    Instance instance;
    instance.name = name;
    instance.mesh = static_cast<uint32_t>(scene.meshes.size() - 1);
    scene.instances.push_back(instance);
  }
  return okStatus();
}

// tinyobjloader's messages are newline-separated; log each distinct one once. Once a material
// library is missing, its follow-up messages (every usemtl it names) only repeat that.
void logWarnings(const std::string& text, const std::string& file, bool mtlMissing) {
  std::set<std::string> seen;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.size() < 2 || !seen.insert(line).second) continue;
    if (mtlMissing && (line.rfind("Failed to load material file", 0) == 0 || line.rfind("material [", 0) == 0))
      continue;
    log::warn("{}: {}", file, line);
  }
}

std::string firstLine(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  return line.empty() ? "parse error" : line;
}

}  // namespace

Result<Scene> loadObj(const fs::path& path) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in || fs::is_directory(path)) return makeError(ExitCode::BadInput, "cannot read scene '{}': no such file", file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  RAYSTER_TRY(checkFaceIndices(text, file));

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  ConfinedMtlReader mtlReader(dir, file);
  std::istringstream stream(text);
  const bool parsed = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &stream, &mtlReader,
                                       /*triangulate=*/true, /*default_vcols_fallback=*/false);
  if (mtlReader.error) return *mtlReader.error;
  if (!parsed) return makeError(ExitCode::BadInput, "{}: {}", file, firstLine(err));
  // tinyobjloader drops such faces with only a warning; a model with holes is an error here.
  if (warn.find("invalid vertex index") != std::string::npos)
    return makeError(ExitCode::BadInput, "{}: a face uses an invalid vertex index", file);
  logWarnings(warn, file, mtlReader.missing);
  logWarnings(err, file, mtlReader.missing);

  for (size_t i = 0; i < attrib.vertices.size(); ++i)
    if (!std::isfinite(attrib.vertices[i]))
      return makeError(ExitCode::BadInput, "{}: vertex {} is not finite", file, i / 3 + 1);

  Scene scene;
  scene.name = path.stem().string();
  TextureLoader textures(scene, dir, file);
  for (const tinyobj::material_t& m : materials) {
    Result<Material> material = convertMaterial(m, textures, scene);
    if (!material) return material.error();
    scene.materials.push_back(std::move(*material));
  }
  RAYSTER_TRY(buildMeshes(scene, attrib, shapes, materials.size(), file));
  if (scene.triangleCount() == 0) return makeError(ExitCode::BadInput, "{}: no triangles", file);
  return scene;
}

}  // namespace rayster::scene
