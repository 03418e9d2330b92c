// EXT_meshopt_compression: buffer views whose bytes are meshoptimizer streams, decoded with
// Debian's libmeshoptimizer (0.18) into the view's own buffer before anything reads an accessor,
// so that accessors, skins and animations read them like any other view.
//
// The extension's "fallback" buffers have no bytes at all (no uri, or a GLB buffer past the BIN
// chunk). tinygltf 2.7 refuses such a buffer, so the JSON it parses gets a one-byte stand-in
// (stubFallbackBuffers), and the decoded views are written into the buffer at its declared size.
#include <algorithm>
#include <cstring>

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "scene/gltf_internal.h"

namespace rayster::scene::gltf {
namespace {

using Json = nlohmann::json;

constexpr const char* kExt = "EXT_meshopt_compression";

// meshoptimizer's vertex codec spends at least 2 bits per 16 decoded bytes, its index codecs more
// per index, so no valid stream decodes to more than about 64 times its size. A view or fallback
// buffer claiming more than four times that cannot be real and would only make us allocate on the
// file's word.
constexpr uint64_t kMaxExpansion = 256;
constexpr uint64_t kExpansionSlack = uint64_t(1) << 20;

const Json* member(const Json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

const Json* meshoptExtension(const Json& object) {
  const Json* ext = member(object, "extensions");
  return ext ? member(*ext, kExt) : nullptr;
}

// The extension object of a buffer view, read with the types the extension's schema gives.
struct Stream {
  int buffer = -1;
  size_t byteOffset = 0, byteLength = 0, byteStride = 0, count = 0;
  std::string mode, filter = "NONE";
};

Result<Stream> readStream(const tinygltf::Value& ext, const std::string& file, const std::string& path) {
  Stream s;
  auto index = [&](const char* key, bool required, size_t fallback, size_t* out) -> Status {
    if (!ext.Has(key)) {
      if (required) return bad(file, "{}.{} is required", path, key);
      *out = fallback;
      return okStatus();
    }
    const tinygltf::Value& v = ext.Get(key);
    if (!v.IsNumber() || v.GetNumberAsDouble() < 0.0 || v.GetNumberAsDouble() > 9.0e15 ||
        v.GetNumberAsDouble() != double(int64_t(v.GetNumberAsDouble())))
      return bad(file, "{}.{} is not a non-negative integer", path, key);
    *out = size_t(v.GetNumberAsDouble());
    return okStatus();
  };
  size_t buffer = 0;
  RAYSTER_TRY(index("buffer", true, 0, &buffer));
  if (buffer > size_t(INT32_MAX)) return bad(file, "{}.buffer {} does not exist", path, buffer);
  s.buffer = int(buffer);
  RAYSTER_TRY(index("byteOffset", false, 0, &s.byteOffset));
  RAYSTER_TRY(index("byteLength", true, 0, &s.byteLength));
  RAYSTER_TRY(index("byteStride", true, 0, &s.byteStride));
  RAYSTER_TRY(index("count", true, 0, &s.count));
  if (!ext.Has("mode") || !ext.Get("mode").IsString()) return bad(file, "{}.mode is required (a string)", path);
  s.mode = ext.Get("mode").Get<std::string>();
  if (ext.Has("filter")) {
    if (!ext.Get("filter").IsString()) return bad(file, "{}.filter is not a string", path);
    s.filter = ext.Get("filter").Get<std::string>();
  }
  return s;
}

// Every precondition meshoptimizer asserts on, checked first: an assertion would abort the process.
Status checkShape(const Stream& s, const std::string& file, const std::string& path) {
  if (s.mode == "ATTRIBUTES") {
    if (s.byteStride == 0 || s.byteStride % 4 != 0 || s.byteStride > 256)
      return bad(file, "{}: byteStride {} for ATTRIBUTES is not a multiple of 4 in [4, 256]", path, s.byteStride);
  } else if (s.mode == "TRIANGLES" || s.mode == "INDICES") {
    if (s.byteStride != 2 && s.byteStride != 4)
      return bad(file, "{}: byteStride {} for {} is not 2 or 4", path, s.byteStride, s.mode);
    if (s.mode == "TRIANGLES" && s.count % 3 != 0)
      return bad(file, "{}: count {} for TRIANGLES is not a multiple of 3", path, s.count);
  } else {
    return bad(file, "{}.mode '{}' is not ATTRIBUTES, TRIANGLES or INDICES", path, s.mode);
  }
  if (s.filter == "NONE") return okStatus();
  if (s.mode != "ATTRIBUTES") return bad(file, "{}: filter {} needs mode ATTRIBUTES, not {}", path, s.filter, s.mode);
  if (s.filter == "OCTAHEDRAL") {
    if (s.byteStride != 4 && s.byteStride != 8)
      return bad(file, "{}: byteStride {} for the OCTAHEDRAL filter is not 4 or 8", path, s.byteStride);
  } else if (s.filter == "QUATERNION") {
    if (s.byteStride != 8) return bad(file, "{}: byteStride {} for the QUATERNION filter is not 8", path, s.byteStride);
  } else if (s.filter != "EXPONENTIAL") {
    return bad(file, "{}.filter '{}' is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL", path, s.filter);
  }
  return okStatus();
}

std::string codecError(const Stream& s, const uint8_t* src, int rc) {
  // The first byte names the codec and its version: 0xA0 vertex v0, 0xE0/0xE1 index, 0xD1 sequence.
  if (s.mode == "ATTRIBUTES" && s.byteLength > 0 && (src[0] & 0xF0) == 0xA0 && src[0] != 0xA0)
    return fmt::format(
        "uses vertex codec version {}, which EXT_meshopt_compression does not allow (version 0 only; later "
        "versions belong to KHR_meshopt_compression)",
        src[0] & 0x0F);
  return fmt::format("is not a valid meshoptimizer {} stream (decoder error {})", s.mode, rc);
}

Status decodeStream(const Stream& s, const uint8_t* src, uint8_t* dst, const std::string& file,
                    const std::string& path) {
  int rc = 0;
  if (s.mode == "ATTRIBUTES")
    rc = meshopt_decodeVertexBuffer(dst, s.count, s.byteStride, src, s.byteLength);
  else if (s.mode == "TRIANGLES")
    rc = meshopt_decodeIndexBuffer(dst, s.count, s.byteStride, src, s.byteLength);
  else
    rc = meshopt_decodeIndexSequence(dst, s.count, s.byteStride, src, s.byteLength);
  if (rc != 0) return bad(file, "{}: {}", path, codecError(s, src, rc));
  if (s.filter == "OCTAHEDRAL")
    meshopt_decodeFilterOct(dst, s.count, s.byteStride);
  else if (s.filter == "QUATERNION")
    meshopt_decodeFilterQuat(dst, s.count, s.byteStride);
  else if (s.filter == "EXPONENTIAL")
    meshopt_decodeFilterExp(dst, s.count, s.byteStride);
  return okStatus();
}

}  // namespace

Result<bool> stubFallbackBuffers(const std::string& file, nlohmann::json& root, bool binary,
                                 std::vector<FallbackBuffer>& fallbacks) {
  fallbacks.clear();
  Json* buffers = root.contains("buffers") ? &root["buffers"] : nullptr;
  if (!buffers || !buffers->is_array()) return false;
  std::vector<bool> empty(buffers->size(), false);
  for (size_t i = 0; i < buffers->size(); ++i) {
    Json& buffer = (*buffers)[i];
    const Json* ext = meshoptExtension(buffer);
    if (!ext) continue;
    const Json* fallback = member(*ext, "fallback");
    if (fallback && !fallback->is_boolean())
      return bad(file, "buffers[{}].extensions.{}.fallback is not a boolean", i, kExt);
    // A GLB's buffer 0 without a uri is the BIN chunk, whatever the extension says.
    if (!fallback || !fallback->get<bool>() || buffer.contains("uri") || (binary && i == 0)) continue;
    const Json* length = member(buffer, "byteLength");
    if (!length || !length->is_number_unsigned()) return bad(file, "buffers[{}].byteLength is required", i);
    fallbacks.push_back(FallbackBuffer{int(i), length->get<uint64_t>()});
    empty[i] = true;
    // A one-byte data URI that tinygltf accepts; decodeMeshopt() gives the buffer its real size.
    buffer["uri"] = "data:application/octet-stream;base64,AA==";
    buffer["byteLength"] = 1;
  }
  if (fallbacks.empty()) return false;
  // Only compressed views may point into a buffer without data (their bytes come from the decoder);
  // anything else (an image, an uncompressed accessor view) would read bytes the file never had.
  if (const Json* views = member(root, "bufferViews"); views && views->is_array())
    for (size_t v = 0; v < views->size(); ++v) {
      const Json& view = (*views)[v];
      const Json* buffer = member(view, "buffer");
      if (!buffer || !buffer->is_number_unsigned() || buffer->get<uint64_t>() >= empty.size() ||
          !empty[buffer->get<size_t>()])
        continue;
      if (!meshoptExtension(view))
        return bad(file, "bufferViews[{}] is not compressed but uses buffer {}, a {} fallback buffer without data", v,
                   buffer->get<uint64_t>(), kExt);
      const Json* source = member(*meshoptExtension(view), "buffer");
      if (source && source->is_number_unsigned() && source->get<uint64_t>() < empty.size() &&
          empty[source->get<size_t>()])
        return bad(file, "bufferViews[{}].extensions.{}.buffer {} is a fallback buffer without data", v, kExt,
                   source->get<uint64_t>());
    }
  return true;
}

bool detachViewlessIndices(nlohmann::json& root, std::vector<DetachedIndices>& detached) {
  detached.clear();
  const Json* accessors = member(root, "accessors");
  Json* meshes = root.contains("meshes") ? &root["meshes"] : nullptr;
  if (!accessors || !accessors->is_array() || !meshes || !meshes->is_array()) return false;
  for (size_t m = 0; m < meshes->size(); ++m) {
    Json* prims =
        (*meshes)[m].is_object() && (*meshes)[m].contains("primitives") ? &(*meshes)[m]["primitives"] : nullptr;
    if (!prims || !prims->is_array()) continue;
    for (size_t p = 0; p < prims->size(); ++p) {
      Json& prim = (*prims)[p];
      const Json* indices = member(prim, "indices");
      if (!indices || !indices->is_number_unsigned() || indices->get<uint64_t>() >= accessors->size()) continue;
      if (member((*accessors)[indices->get<size_t>()], "bufferView")) continue;
      detached.push_back(DetachedIndices{m, p, indices->get<int>()});
      prim.erase("indices");
    }
  }
  return !detached.empty();
}

Status reattachIndices(tinygltf::Model& model, const std::string& file, const std::vector<DetachedIndices>& detached) {
  for (const DetachedIndices& d : detached) {
    if (d.mesh >= model.meshes.size() || d.primitive >= model.meshes[d.mesh].primitives.size())
      return bad(file, "meshes[{}].primitives[{}] went missing while parsing", d.mesh, d.primitive);
    model.meshes[d.mesh].primitives[d.primitive].indices = d.accessor;
  }
  return okStatus();
}

std::vector<uint8_t> glbWithJson(const std::vector<uint8_t>& glb, std::string_view json) {
  uint32_t oldJsonLength = 0, oldLength = 0;
  std::memcpy(&oldLength, glb.data() + 8, 4);
  std::memcpy(&oldJsonLength, glb.data() + 12, 4);
  std::string padded(json);
  while (padded.size() % 4 != 0) padded += ' ';                // GLB chunks are 4-byte aligned, JSON padded with spaces
  const size_t rest = size_t(oldLength) - 20 - oldJsonLength;  // the chunks after the JSON (glbJsonChunk checked)
  std::vector<uint8_t> out(20 + padded.size() + rest);
  std::memcpy(out.data(), glb.data(), 8);
  const uint32_t length = uint32_t(out.size()), jsonLength = uint32_t(padded.size()), jsonType = 0x4E4F534Au;
  std::memcpy(out.data() + 8, &length, 4);
  std::memcpy(out.data() + 12, &jsonLength, 4);
  std::memcpy(out.data() + 16, &jsonType, 4);
  std::memcpy(out.data() + 20, padded.data(), padded.size());
  if (rest > 0) std::memcpy(out.data() + 20 + padded.size(), glb.data() + 20 + oldJsonLength, rest);
  return out;
}

Status decodeMeshopt(tinygltf::Model& model, const std::string& file, const std::vector<FallbackBuffer>& fallbacks) {
  struct Job {
    size_t view;
    Stream stream;
    std::string path;
  };
  std::vector<Job> jobs;
  uint64_t compressed = 0;
  for (size_t v = 0; v < model.bufferViews.size(); ++v) {
    auto it = model.bufferViews[v].extensions.find(kExt);
    if (it == model.bufferViews[v].extensions.end()) continue;
    const std::string path = fmt::format("bufferViews[{}].extensions.{}", v, kExt);
    Result<Stream> stream = readStream(it->second, file, path);
    if (!stream) return stream.error();
    RAYSTER_TRY(checkShape(*stream, file, path));
    if (size_t(stream->buffer) >= model.buffers.size())
      return bad(file, "{}.buffer {} does not exist", path, stream->buffer);
    const size_t size = model.buffers[size_t(stream->buffer)].data.size();
    if (stream->byteOffset > size || stream->byteLength > size - stream->byteOffset)
      return bad(file, "{}: bytes {}..{} lie outside buffer {} ({} bytes)", path, stream->byteOffset,
                 stream->byteOffset + stream->byteLength, stream->buffer, size);
    compressed += stream->byteLength;
    jobs.push_back(Job{v, std::move(*stream), path});
  }
  const uint64_t budget = kMaxExpansion * compressed + kExpansionSlack;
  for (const FallbackBuffer& f : fallbacks) {
    if (f.byteLength > budget)
      return bad(file, "buffers[{}].byteLength {} is more than its {} compressed bytes can decode to", f.buffer,
                 f.byteLength, compressed);
    model.buffers[size_t(f.buffer)].data.assign(size_t(f.byteLength), 0);
  }
  uint64_t decodedTotal = 0;
  std::vector<uint8_t> decoded;
  for (const Job& job : jobs) {
    const Stream& s = job.stream;
    size_t bytes = 0;
    if (__builtin_mul_overflow(s.count, s.byteStride, &bytes) || bytes > budget - std::min(budget, decodedTotal))
      return bad(file, "{}: {} × {} bytes is more than the compressed data can decode to", job.path, s.count,
                 s.byteStride);
    decodedTotal += bytes;
    tinygltf::BufferView& view = model.bufferViews[job.view];
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
      return bad(file, "bufferViews[{}].buffer {} does not exist", job.view, view.buffer);
    std::vector<unsigned char>& target = model.buffers[size_t(view.buffer)].data;
    if (bytes > view.byteLength || view.byteOffset > target.size() || view.byteLength > target.size() - view.byteOffset)
      return bad(file, "{}: {} decoded bytes do not fit bufferViews[{}] ({} bytes at {} in buffer {} of {} bytes)",
                 job.path, bytes, job.view, view.byteLength, view.byteOffset, view.buffer, target.size());
    // The decoders write whole blocks; decode into a scratch buffer, never past the view.
    decoded.assign(bytes, 0);
    const uint8_t* src = model.buffers[size_t(s.buffer)].data.data() + s.byteOffset;
    RAYSTER_TRY(decodeStream(s, src, decoded.data(), file, job.path));
    std::memcpy(target.data() + view.byteOffset, decoded.data(), bytes);
    // The view now holds plain data; its stride is the stream's (the spec makes them equal).
    if (view.byteStride == 0 && s.mode == "ATTRIBUTES") view.byteStride = s.byteStride;
  }
  return okStatus();
}

}  // namespace rayster::scene::gltf
