// Vetting a glTF document before tinygltf parses it, and confining tinygltf's file access.
// tinygltf 2.7 trusts much of its input (image buffer views, GLB chunk ends, recursion depth of
// extras) and resolves URIs against both the file's folder and the working directory, so the
// checks that make loading untrusted files safe live here.
#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/log.h"
#include "scene/gltf_internal.h"

namespace rayster::scene::gltf {
namespace {

using Json = nlohmann::json;

// tinygltf converts extras and extensions to its Value type recursively; real files nest a few
// levels, hostile ones thousands (a stack overflow).
constexpr int kMaxJsonDepth = 64;

// Extensions whose meaning Rayster implements (or, for KHR_mesh_quantization, that only widen
// the accessor types the reader already handles). The compression ones: docs/gltf-compression.md;
// the material layers: docs/materials.md.
constexpr std::array<std::string_view, 19> kSupportedExtensions = {
    "KHR_lights_punctual",        "KHR_texture_transform",    "KHR_materials_emissive_strength",
    "KHR_materials_transmission", "KHR_materials_ior",        "KHR_materials_volume",
    "KHR_materials_specular",     "KHR_mesh_quantization",    "KHR_materials_unlit",
    "KHR_materials_clearcoat",    "KHR_materials_sheen",      "KHR_materials_iridescence",
    "KHR_materials_anisotropy",   "KHR_materials_dispersion", "KHR_materials_variants",
    "KHR_draco_mesh_compression", "EXT_meshopt_compression",  "KHR_texture_basisu",
    "EXT_mesh_gpu_instancing"};

bool supported(std::string_view name) {
  return std::find(kSupportedExtensions.begin(), kSupportedExtensions.end(), name) != kSupportedExtensions.end();
}

uint32_t readU32(const uint8_t* p) {
  // GLB is little-endian, like every platform Rayster runs on.
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

// Long data URIs would swamp a message; the start says enough.
std::string shortUri(std::string_view uri) {
  constexpr size_t kMax = 64;
  return uri.size() <= kMax ? std::string(uri) : std::string(uri.substr(0, kMax)) + "...";
}

std::string percentDecode(std::string_view s) {
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && hex(s[i + 1]) >= 0 && hex(s[i + 2]) >= 0) {
      out += char(hex(s[i + 1]) * 16 + hex(s[i + 2]));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

bool validBase64(std::string_view s) {
  if (s.empty() || s.size() % 4 != 0) return false;
  size_t padding = 0;
  while (padding < 2 && padding < s.size() && s[s.size() - 1 - padding] == '=') ++padding;
  for (size_t i = 0; i < s.size() - padding; ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (!std::isalnum(c) && c != '+' && c != '/') return false;
  }
  return true;
}

// The path policy for a decoded relative reference: no absolute paths, no "..", no drive
// letters or schemes, no NULs. Returns the reason it fails, or an empty string.
std::string pathProblem(std::string_view decoded) {
  if (decoded.empty()) return "is empty";
  if (decoded.find('\0') != std::string_view::npos) return "contains a NUL character";
  if (decoded.front() == '/' || decoded.front() == '\\') return "is an absolute path";
  if (decoded.find(':') != std::string_view::npos) return "names a drive or scheme";
  size_t start = 0;
  while (start <= decoded.size()) {
    size_t end = decoded.find_first_of("/\\", start);
    if (end == std::string_view::npos) end = decoded.size();
    if (decoded.substr(start, end - start) == "..") return "leaves the glTF's folder";
    start = end + 1;
  }
  return {};
}

Status checkUri(const std::string& file, std::string_view what, std::string_view uri) {
  if (uri.rfind("data:", 0) == 0) {
    const size_t comma = uri.find(',');
    const std::string_view header = uri.substr(0, comma);
    if (comma == std::string_view::npos || header.size() < 7 || header.substr(header.size() - 7) != ";base64")
      return bad(file, "{} data URI is not base64 ('{}')", what, shortUri(uri));
    if (!validBase64(uri.substr(comma + 1))) return bad(file, "{} data URI has invalid base64", what);
    return okStatus();
  }
  // A scheme is letters before the first ':' that precedes any '/'.
  const size_t colon = uri.find(':');
  if (colon != std::string_view::npos && colon < uri.find('/') && colon > 1)
    return bad(file, "{} URI '{}' uses the scheme '{}'; only relative paths and data: URIs are allowed", what,
               shortUri(uri), uri.substr(0, colon));
  const std::string problem = pathProblem(percentDecode(uri));
  if (!problem.empty())
    return bad(file, "{} URI '{}' {}; only paths inside the glTF's folder are allowed", what, shortUri(uri), problem);
  return okStatus();
}

int jsonDepth(std::string_view text) {
  int depth = 0, maxDepth = 0;
  bool inString = false, escaped = false;
  for (char c : text) {
    if (inString) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      maxDepth = std::max(maxDepth, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return maxDepth;
}

const Json* member(const Json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

std::optional<uint64_t> unsignedMember(const Json& object, const char* key, uint64_t fallback) {
  const Json* v = member(object, key);
  if (!v) return fallback;
  if (!v->is_number_unsigned()) return std::nullopt;
  return v->get<uint64_t>();
}

// tinygltf hands an image's buffer view to the decoder without checking it lies in its buffer.
Status checkImageView(const std::string& file, const Json& root, size_t image, const Json& viewIndex) {
  const Json* views = member(root, "bufferViews");
  const Json* buffers = member(root, "buffers");
  if (!viewIndex.is_number_unsigned() || !views || !views->is_array() || viewIndex.get<uint64_t>() >= views->size())
    return bad(file, "image {} uses a buffer view that does not exist", image);
  const Json& view = (*views)[viewIndex.get<size_t>()];
  const Json* buffer = member(view, "buffer");
  if (!buffer || !buffer->is_number_unsigned() || !buffers || !buffers->is_array() ||
      buffer->get<uint64_t>() >= buffers->size())
    return bad(file, "image {} uses a buffer view whose buffer does not exist", image);
  std::optional<uint64_t> offset = unsignedMember(view, "byteOffset", 0);
  std::optional<uint64_t> length = unsignedMember(view, "byteLength", 0);
  std::optional<uint64_t> bufferLength = unsignedMember((*buffers)[buffer->get<size_t>()], "byteLength", 0);
  if (!offset || !length || !bufferLength || *length == 0 || *offset > *bufferLength ||
      *length > *bufferLength - *offset)
    return bad(file, "image {} buffer view {} lies outside its buffer", image, viewIndex.get<uint64_t>());
  return okStatus();
}

Status checkExtensions(const std::string& file, const Json& root) {
  if (const Json* required = member(root, "extensionsRequired"); required && required->is_array())
    for (const Json& name : *required)
      if (name.is_string() && !supported(name.get<std::string>()))
        return bad(file, "requires extension {}, which Rayster does not support", name.get<std::string>());
  if (const Json* used = member(root, "extensionsUsed"); used && used->is_array())
    for (const Json& name : *used)
      if (name.is_string() && !supported(name.get<std::string>()))
        log::warn("{}: uses extension {}, which Rayster ignores", file, name.get<std::string>());
  return okStatus();
}

bool allowedPath(const ConfinedFs& fs, const std::string& path) {
  const std::string prefix = fs.baseDir.empty() || fs.baseDir.back() == '/' ? fs.baseDir : fs.baseDir + "/";
  return path.size() > prefix.size() && path.compare(0, prefix.size(), prefix) == 0 &&
         pathProblem(std::string_view(path).substr(prefix.size())).empty();
}

bool confinedFileExists(const std::string& path, void* user) {
  auto* fs = static_cast<ConfinedFs*>(user);
  // tinygltf also tries the working directory ("./name"); that is never allowed, silently.
  if (!allowedPath(*fs, path)) return false;
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

std::string identityExpand(const std::string& path, void*) {
  return path;  // tinygltf's default runs wordexp() on the path: no shell expansion of file contents
}

bool confinedRead(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  auto* fs = static_cast<ConfinedFs*>(user);
  if (!allowedPath(*fs, path)) {
    if (fs->violation.empty()) fs->violation = fmt::format("refused to read '{}' outside the glTF's folder", path);
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (err) *err = "cannot open";
    return false;
  }
  out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return true;
}

bool refuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err = "writing is disabled";
  return false;
}

// Per image, the first material that shows it through one of the texture slots Rayster reads.
// Broken references are left to the material conversion, which warns about them.
std::vector<int> imageMaterials(const Json& root) {
  const Json* images = member(root, "images");
  std::vector<int> out(images && images->is_array() ? images->size() : 0, -1);
  const Json* textures = member(root, "textures");
  const Json* materials = member(root, "materials");
  if (!textures || !textures->is_array() || !materials || !materials->is_array()) return out;
  auto mark = [&](const Json* slot, size_t material) {
    const Json* index = slot ? member(*slot, "index") : nullptr;
    if (!index || !index->is_number_unsigned() || index->get<uint64_t>() >= textures->size()) return;
    const Json& texture = (*textures)[index->get<size_t>()];
    // The texture's image and, with KHR_texture_basisu, its KTX2 image (the other is the fallback).
    const Json* extensions = member(texture, "extensions");
    const Json* basisu = extensions ? member(*extensions, "KHR_texture_basisu") : nullptr;
    for (const Json* source : {member(texture, "source"), basisu ? member(*basisu, "source") : nullptr}) {
      if (!source || !source->is_number_unsigned() || source->get<uint64_t>() >= out.size()) continue;
      int& first = out[source->get<size_t>()];
      if (first < 0) first = int(material);
    }
  };
  for (size_t m = 0; m < materials->size(); ++m) {
    const Json& material = (*materials)[m];
    if (const Json* pbr = member(material, "pbrMetallicRoughness")) {
      mark(member(*pbr, "baseColorTexture"), m);
      mark(member(*pbr, "metallicRoughnessTexture"), m);
    }
    for (const char* slot : {"normalTexture", "occlusionTexture", "emissiveTexture"}) mark(member(material, slot), m);
    // The extensions' texture slots that gltf_material_layers.cpp reads.
    if (const Json* extensions = member(material, "extensions"))
      for (const ExtensionTextureSlot& s : kExtensionTextureSlots)
        if (const Json* ext = member(*extensions, s.extension)) mark(member(*ext, s.slot), m);
  }
  return out;
}

}  // namespace

std::string oneLine(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (c == '\n' || c == '\r') {
      if (!out.empty() && out.back() != ' ') out += "; ";
    } else {
      out += c;
    }
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == ';')) out.pop_back();
  return out;
}

Result<std::string_view> glbJsonChunk(const std::string& file, const std::vector<uint8_t>& bytes) {
  if (bytes.size() < 20) return bad(file, "GLB file is truncated ({} bytes)", bytes.size());
  const uint8_t* p = bytes.data();
  if (readU32(p + 4) != 2) return bad(file, "GLB version {} is not supported (only 2)", readU32(p + 4));
  const uint64_t length = readU32(p + 8);
  if (length > bytes.size() || length < 20)
    return bad(file, "GLB header says {} bytes but the file has {}", length, bytes.size());
  const uint64_t jsonLength = readU32(p + 12);
  if (readU32(p + 16) != 0x4E4F534Au) return bad(file, "GLB first chunk is not JSON");
  const uint64_t jsonEnd = 20 + jsonLength;
  if (jsonEnd > length) return bad(file, "GLB JSON chunk ({} bytes) runs past the end of the file", jsonLength);
  if (jsonEnd < length) {
    if (length - jsonEnd < 8) return bad(file, "GLB has a truncated chunk after the JSON");
    const uint64_t binLength = readU32(p + jsonEnd);
    if (jsonEnd + 8 + binLength > length)
      return bad(file, "GLB BIN chunk ({} bytes) runs past the end of the file", binLength);
  }
  return std::string_view(reinterpret_cast<const char*>(p) + 20, size_t(jsonLength));
}

Result<VettedJson> vetJson(const std::string& file, std::string_view text, bool binary) {
  if (jsonDepth(text) > kMaxJsonDepth) return bad(file, "JSON nests deeper than {} levels", kMaxJsonDepth);
  Json root;
  try {
    root = Json::parse(text.begin(), text.end());
  } catch (const std::exception& e) {
    return bad(file, "invalid JSON: {}", oneLine(e.what()));
  }
  if (!root.is_object()) return bad(file, "invalid glTF: the JSON root is not an object");
  // glTF 1.0 is a different format (techniques, shaders); tinygltf's complaint would be cryptic.
  if (const Json* asset = member(root, "asset")) {
    const Json* version = member(*asset, "version");
    if (version && version->is_string() && version->get<std::string>().rfind("1", 0) == 0)
      return bad(file, "is glTF {}; Rayster reads glTF 2.0", version->get<std::string>());
  }
  RAYSTER_TRY(checkExtensions(file, root));
  RAYSTER_TRY(checkJsonTypes(file, root));
  if (const Json* buffers = member(root, "buffers"); buffers && buffers->is_array())
    for (size_t i = 0; i < buffers->size(); ++i)
      if (const Json* uri = member((*buffers)[i], "uri"); uri && uri->is_string())
        RAYSTER_TRY(checkUri(file, fmt::format("buffer {}", i), uri->get<std::string>()));
  if (const Json* images = member(root, "images"); images && images->is_array())
    for (size_t i = 0; i < images->size(); ++i) {
      if (const Json* uri = member((*images)[i], "uri"); uri && uri->is_string())
        RAYSTER_TRY(checkUri(file, fmt::format("image {}", i), uri->get<std::string>()));
      if (const Json* view = member((*images)[i], "bufferView")) RAYSTER_TRY(checkImageView(file, root, i, *view));
    }
  VettedJson vetted{imageMaterials(root), {}, {}, {}};
  // What tinygltf 2.7 cannot parse although it is valid (compressed glTF needs both).
  Result<bool> stubbed = stubFallbackBuffers(file, root, binary, vetted.fallbackBuffers);
  if (!stubbed) return stubbed.error();
  const bool detached = detachViewlessIndices(root, vetted.detachedIndices);
  if (*stubbed || detached) vetted.rewrittenJson = root.dump();
  return vetted;
}

tinygltf::FsCallbacks makeConfinedFsCallbacks(ConfinedFs* fs) {
  tinygltf::FsCallbacks callbacks{};
  callbacks.FileExists = &confinedFileExists;
  callbacks.ExpandFilePath = &identityExpand;
  callbacks.ReadWholeFile = &confinedRead;
  callbacks.WriteWholeFile = &refuseWrite;
  callbacks.user_data = fs;
  return callbacks;
}

}  // namespace rayster::scene::gltf
