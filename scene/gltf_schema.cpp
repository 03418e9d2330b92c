// The glTF 2.0 schema on the raw JSON: the checker's readers, then the asset, the extension lists,
// buffers, buffer views and accessors (gltf_schema.h says what is checked and why here).
#include "scene/gltf_schema.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

namespace rayster::scene::gltf::schema {

std::string Range::describe() const {
  const bool hasLo = std::isfinite(lo), hasHi = std::isfinite(hi);
  if (hasLo && hasHi) return fmt::format("{}{}, {}{}", loOpen ? "(" : "[", lo, hi, hiOpen ? ")" : "]");
  if (hasLo) return fmt::format("{} {}", loOpen ? "above" : "at least", lo);
  if (hasHi) return fmt::format("{} {}", hiOpen ? "below" : "at most", hi);
  return "any number";
}

const Json* Checker::find(const Json& o, const char* key) {
  if (!o.is_object()) return nullptr;
  auto it = o.find(key);
  return it == o.end() ? nullptr : &*it;
}

size_t Checker::count(const char* name) const {
  const Json* a = find(root_, name);
  return a && a->is_array() ? a->size() : 0;
}

namespace {
bool isIndex(const Json& v) { return v.is_number_integer() && (v.is_number_unsigned() || v.get<int64_t>() >= 0); }

// "node" for "nodes", "mesh" for "meshes".
std::string singular(const std::string& plural) {
  if (plural == "meshes") return "mesh";
  return !plural.empty() && plural.back() == 's' ? plural.substr(0, plural.size() - 1) : plural;
}
}  // namespace

Status Checker::indexInto(const Json& o, const char* key, const std::string& path, size_t size, const char* what,
                          bool required) const {
  const Json* v = find(o, key);
  const std::string p = at(path, key);
  if (!v) return required ? Status(fail(path, "{} is required", key)) : okStatus();
  if (!isIndex(*v)) return fail(p, "{} is not a non-negative integer index", v->dump());
  if (v->get<uint64_t>() >= size)
    return fail(p, "{} {} does not exist ({} {})", singular(what), v->get<uint64_t>(), size, what);
  return okStatus();
}

Status Checker::ref(const Json& o, const char* key, const std::string& path, const char* array, bool required) const {
  return indexInto(o, key, path, count(array), array, required);
}

Status Checker::number(const Json& o, const char* key, const std::string& path, Range range, bool required) const {
  const Json* v = find(o, key);
  if (!v) return required ? Status(fail(path, "{} is required", key)) : okStatus();
  if (!v->is_number()) return fail(at(path, key), "{} is not a number", v->dump());
  const double x = v->get<double>();
  if (!range.contains(x)) return fail(at(path, key), "{} is not {}", x, range.describe());
  return okStatus();
}

Status Checker::integer(const Json& o, const char* key, const std::string& path, Range range, bool required) const {
  const Json* v = find(o, key);
  if (!v) return required ? Status(fail(path, "{} is required", key)) : okStatus();
  if (!v->is_number_integer()) return fail(at(path, key), "{} is not an integer", v->dump());
  const double x = v->is_number_unsigned() ? double(v->get<uint64_t>()) : double(v->get<int64_t>());
  if (!range.contains(x)) return fail(at(path, key), "{} is not {}", x, range.describe());
  return okStatus();
}

Status Checker::numbers(const Json& o, const char* key, const std::string& path, std::initializer_list<size_t> lengths,
                        Range range) const {
  const Json* v = find(o, key);
  if (!v) return okStatus();
  const std::string p = at(path, key);
  if (!v->is_array()) return fail(p, "is not an array of numbers");
  if (std::find(lengths.begin(), lengths.end(), v->size()) == lengths.end()) {
    std::string need;
    for (size_t n : lengths) need += (need.empty() ? "" : " or ") + std::to_string(n);
    return fail(p, "{} numbers, need {}", v->size(), need);
  }
  for (size_t i = 0; i < v->size(); ++i) {
    if (!(*v)[i].is_number()) return fail(at(p, i), "{} is not a number", (*v)[i].dump());
    const double x = (*v)[i].get<double>();
    if (!range.contains(x)) return fail(at(p, i), "{} is not {}", x, range.describe());
  }
  return okStatus();
}

Status Checker::refs(const Json& o, const char* key, const std::string& path, const char* array) const {
  const Json* v = find(o, key);
  if (!v) return okStatus();
  const std::string p = at(path, key);
  if (!v->is_array()) return fail(p, "is not an array of indices");
  if (v->empty()) return fail(p, "is empty (leave it out instead)");
  std::set<uint64_t> seen;
  for (size_t i = 0; i < v->size(); ++i) {
    const Json& e = (*v)[i];
    if (!isIndex(e)) return fail(at(p, i), "{} is not a non-negative integer index", e.dump());
    if (e.get<uint64_t>() >= count(array))
      return fail(at(p, i), "{} {} does not exist ({} {})", singular(array), e.get<uint64_t>(), count(array), array);
    if (!seen.insert(e.get<uint64_t>()).second) return fail(at(p, i), "{} is listed twice", e.get<uint64_t>());
  }
  return okStatus();
}

Status Checker::string(const Json& o, const char* key, const std::string& path, bool required) const {
  const Json* v = find(o, key);
  if (!v) return required ? Status(fail(path, "{} is required", key)) : okStatus();
  if (!v->is_string()) return fail(at(path, key), "{} is not a string", v->dump());
  return okStatus();
}

Status Checker::boolean(const Json& o, const char* key, const std::string& path) const {
  const Json* v = find(o, key);
  if (v && !v->is_boolean()) return fail(at(path, key), "{} is not true or false", v->dump());
  return okStatus();
}

Status Checker::textureInfo(const Json& o, const char* key, const std::string& path, const char* extra,
                            Range extraRange, std::vector<std::pair<std::string, int64_t>>* texCoords) const {
  const Json* info = find(o, key);
  if (!info) return okStatus();
  const std::string p = at(path, key);
  if (!info->is_object()) return fail(p, "is not an object");
  RAYSTER_TRY(ref(*info, "index", p, "textures", true));
  RAYSTER_TRY(integer(*info, "texCoord", p, kNonNegative));
  if (extra) RAYSTER_TRY(number(*info, extra, p, extraRange));
  int64_t texCoord = info->value("texCoord", int64_t(0));
  if (const Json* ext = find(*info, "extensions"))
    if (const Json* transform = find(*ext, "KHR_texture_transform")) {
      const std::string tp = at(at(p, "extensions"), "KHR_texture_transform");
      RAYSTER_TRY(numbers(*transform, "offset", tp, {2}));
      RAYSTER_TRY(numbers(*transform, "scale", tp, {2}));
      RAYSTER_TRY(number(*transform, "rotation", tp, kAny));
      RAYSTER_TRY(integer(*transform, "texCoord", tp, kNonNegative));
      texCoord = transform->value("texCoord", texCoord);
    }
  if (texCoords) texCoords->emplace_back(p, texCoord);
  return okStatus();
}

double Checker::numberOr(const Json& o, const char* key, double fallback) const {
  const Json* v = find(o, key);
  return v && v->is_number() ? v->get<double>() : fallback;
}

size_t componentCount(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

size_t componentBytes(int64_t componentType) {
  switch (componentType) {
    case 5120:
    case 5121:
      return 1;
    case 5122:
    case 5123:
      return 2;
    case 5125:
    case 5126:
      return 4;
    default:
      return 0;
  }
}

namespace {

// "major.minor", digits only (the schema's pattern ^[0-9]+\.[0-9]+$); {-1, -1} when it is not.
std::pair<long, long> version(const std::string& v) {
  const size_t dot = v.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 >= v.size() || v.size() > 12) return {-1, -1};
  for (size_t i = 0; i < v.size(); ++i)
    if (i != dot && (v[i] < '0' || v[i] > '9')) return {-1, -1};
  return {std::stol(v.substr(0, dot)), std::stol(v.substr(dot + 1))};
}

Status checkAsset(const Checker& c) {
  const Json* asset = Checker::find(c.root(), "asset");
  if (!asset) return c.fail("glTF", "asset is required");
  RAYSTER_TRY(c.string(*asset, "version", "asset", true));
  for (const char* key : {"generator", "copyright", "minVersion"}) RAYSTER_TRY(c.string(*asset, key, "asset"));
  const std::string v = (*asset)["version"].get<std::string>();
  const auto [major, minor] = version(v);
  if (major < 0) return c.fail("asset.version", "'{}' is not 'major.minor'", v);
  if (major != 2) return c.fail("asset.version", "'{}' is not a glTF 2.x version (this loader reads glTF 2.0)", v);
  if (const Json* mv = Checker::find(*asset, "minVersion")) {
    const std::string m = mv->get<std::string>();
    const auto [minMajor, minMinor] = version(m);
    if (minMajor < 0) return c.fail("asset.minVersion", "'{}' is not 'major.minor'", m);
    if (std::pair(minMajor, minMinor) > std::pair(major, minor))
      return c.fail("asset.minVersion", "'{}' is greater than version '{}'", m, v);
    // A 2.0 loader cannot promise what a later minor version asks for.
    if (std::pair(minMajor, minMinor) > std::pair(2L, 0L))
      return c.fail("asset.minVersion", "'{}' asks for more than glTF 2.0", m);
  }
  return okStatus();
}

Status stringSet(const Checker& c, const char* key, std::set<std::string>& out) {
  const Json* list = Checker::find(c.root(), key);
  if (!list) return okStatus();
  if (!list->is_array()) return c.fail(key, "is not an array of strings");
  if (list->empty()) return c.fail(key, "is empty (leave it out instead)");
  for (size_t i = 0; i < list->size(); ++i) {
    if (!(*list)[i].is_string()) return c.fail(Checker::at(key, i), "{} is not a string", (*list)[i].dump());
    if (!out.insert((*list)[i].get<std::string>()).second)
      return c.fail(Checker::at(key, i), "'{}' is listed twice", (*list)[i].get<std::string>());
  }
  return okStatus();
}

Status checkExtensionLists(const Checker& c) {
  std::set<std::string> used, required;
  RAYSTER_TRY(stringSet(c, "extensionsUsed", used));
  RAYSTER_TRY(stringSet(c, "extensionsRequired", required));
  size_t i = 0;
  for (const Json& name : c.root().value("extensionsRequired", Json::array())) {
    if (!used.count(name.get<std::string>()))
      return c.fail(Checker::at("extensionsRequired", i), "'{}' is not in extensionsUsed", name.get<std::string>());
    ++i;
  }
  return okStatus();
}

Status checkBuffers(const Checker& c) {
  for (size_t i = 0; i < c.count("buffers"); ++i) {
    const Json& b = c.element("buffers", i);
    const std::string p = Checker::at("buffers", i);
    RAYSTER_TRY(c.integer(b, "byteLength", p, {1.0, kAny.hi}, true));
    RAYSTER_TRY(c.string(b, "uri", p));
    if (const Json* uri = Checker::find(b, "uri"); uri && uri->get<std::string>().rfind("data:", 0) == 0) {
      const std::string u = uri->get<std::string>();
      const std::string mime = u.substr(5, u.find_first_of(";,") - 5);
      if (mime != "application/octet-stream" && mime != "application/gltf-buffer")
        return c.fail(Checker::at(p, "uri"),
                      "data URI media type '{}' is not application/octet-stream or application/gltf-buffer", mime);
      // The bytes the URI holds, from its base64 length (a URI that is not base64 at all is
      // refused by vetJson, with its own message).
      const size_t comma = u.find(',');
      const size_t chars = comma == std::string::npos ? 0 : u.size() - comma - 1;
      size_t padding = 0;
      while (padding < 2 && padding < chars && u[u.size() - 1 - padding] == '=') ++padding;
      bool base64 = chars % 4 == 0 && u.find(";base64,") != std::string::npos;
      for (size_t k = comma + 1; base64 && k < u.size() - padding; ++k)
        base64 = std::isalnum(static_cast<unsigned char>(u[k])) || u[k] == '+' || u[k] == '/';
      const uint64_t holds = chars / 4 * 3 - padding;
      if (base64 && holds < b["byteLength"].get<uint64_t>())
        return c.fail(Checker::at(p, "byteLength"), "{}, but the data URI holds {} bytes",
                      b["byteLength"].get<uint64_t>(), holds);
    }
  }
  return okStatus();
}

Status checkBufferViews(const Checker& c) {
  for (size_t i = 0; i < c.count("bufferViews"); ++i) {
    const Json& v = c.element("bufferViews", i);
    const std::string p = Checker::at("bufferViews", i);
    RAYSTER_TRY(c.ref(v, "buffer", p, "buffers", true));
    RAYSTER_TRY(c.integer(v, "byteOffset", p, kNonNegative));
    RAYSTER_TRY(c.integer(v, "byteLength", p, {1.0, kAny.hi}, true));
    RAYSTER_TRY(c.integer(v, "byteStride", p, {4.0, 252.0}));
    RAYSTER_TRY(c.integer(v, "target", p, kAny));  // an unknown target is only a warning
    const uint64_t offset = v.value("byteOffset", uint64_t(0)), length = v["byteLength"].get<uint64_t>();
    if (const Json* stride = Checker::find(v, "byteStride")) {
      if (stride->get<uint64_t>() % 4 != 0)
        return c.fail(Checker::at(p, "byteStride"), "{} is not a multiple of 4", stride->get<uint64_t>());
      if (stride->get<uint64_t>() > length)
        return c.fail(Checker::at(p, "byteStride"), "{} is more than byteLength {}", stride->get<uint64_t>(), length);
    }
    const Json& buffer = c.element("buffers", v["buffer"].get<size_t>());
    const uint64_t bufferLength = buffer["byteLength"].get<uint64_t>();
    if (offset > bufferLength || length > bufferLength - offset)
      return c.fail(p, "byteOffset {} + byteLength {} runs past buffer {} (byteLength {})", offset, length,
                    v["buffer"].get<uint64_t>(), bufferLength);
  }
  return okStatus();
}

// Bytes of one element: matrix columns of 1- and 2-byte components start on 4-byte boundaries
// (glTF 2.0 §3.6.2.4).
uint64_t elementBytes(const std::string& type, size_t component) {
  if (type == "MAT2" && component == 1) return 8;
  if (type == "MAT3" && component == 1) return 12;
  if (type == "MAT3" && component == 2) return 24;
  return componentCount(type) * component;
}

// `count` elements of `element` bytes every `stride` from `offset` lie within `length`.
bool fits(uint64_t offset, uint64_t stride, uint64_t count, uint64_t element, uint64_t length) {
  if (count == 0) return offset <= length;
  const long double end = (long double)offset + (long double)stride * (long double)(count - 1) + element;
  return end <= (long double)length;
}

Status checkSparse(const Checker& c, const Json& sparse, const std::string& p, uint64_t count, uint64_t element) {
  if (!sparse.is_object()) return c.fail(p, "is not an object");
  RAYSTER_TRY(c.integer(sparse, "count", p, {1.0, kAny.hi}, true));
  const uint64_t n = sparse["count"].get<uint64_t>();
  if (n > count) return c.fail(Checker::at(p, "count"), "{} is more than the accessor's count {}", n, count);
  for (const char* part : {"indices", "values"}) {
    const Json* o = Checker::find(sparse, part);
    if (!o) return c.fail(p, "{} is required", part);
    const std::string pp = Checker::at(p, part);
    if (!o->is_object()) return c.fail(pp, "is not an object");
    RAYSTER_TRY(c.ref(*o, "bufferView", pp, "bufferViews", true));
    RAYSTER_TRY(c.integer(*o, "byteOffset", pp, kNonNegative));
    uint64_t size = element;
    if (std::string(part) == "indices") {
      RAYSTER_TRY(c.integer(*o, "componentType", pp, kAny, true));
      const int64_t type = (*o)["componentType"].get<int64_t>();
      if (type != 5121 && type != 5123 && type != 5125)
        return c.fail(Checker::at(pp, "componentType"), "{} is not 5121, 5123 or 5125 (unsigned byte, short or int)",
                      type);
      size = componentBytes(type);
    }
    const Json& view = c.element("bufferViews", (*o)["bufferView"].get<size_t>());
    if (Checker::find(view, "byteStride"))
      return c.fail(Checker::at(pp, "bufferView"), "buffer view {} has a byteStride, which sparse data must not",
                    (*o)["bufferView"].get<uint64_t>());
    const uint64_t offset = o->value("byteOffset", uint64_t(0));
    if (!fits(offset, size, n, size, view["byteLength"].get<uint64_t>()))
      return c.fail(pp, "{} elements of {} bytes from byteOffset {} run past buffer view {} (byteLength {})", n, size,
                    offset, (*o)["bufferView"].get<uint64_t>(), view["byteLength"].get<uint64_t>());
  }
  return okStatus();
}

Status checkAccessors(const Checker& c) {
  for (size_t i = 0; i < c.count("accessors"); ++i) {
    const Json& a = c.element("accessors", i);
    const std::string p = Checker::at("accessors", i);
    RAYSTER_TRY(c.ref(a, "bufferView", p, "bufferViews"));
    RAYSTER_TRY(c.integer(a, "byteOffset", p, kNonNegative));
    RAYSTER_TRY(c.integer(a, "componentType", p, kAny, true));  // an unknown type is only a warning
    RAYSTER_TRY(c.boolean(a, "normalized", p));
    RAYSTER_TRY(c.integer(a, "count", p, {1.0, kAny.hi}, true));
    RAYSTER_TRY(c.string(a, "type", p, true));
    const int64_t componentType = a["componentType"].get<int64_t>();
    const std::string type = a["type"].get<std::string>();
    const size_t components = componentCount(type), bytes = componentBytes(componentType);
    const uint64_t count = a["count"].get<uint64_t>();
    if (a.value("normalized", false) && (componentType == 5125 || componentType == 5126))
      return c.fail(Checker::at(p, "normalized"), "only byte and short component types can be normalized, not {}",
                    componentType);
    for (const char* bound : {"min", "max"})
      if (components) RAYSTER_TRY(c.numbers(a, bound, p, {components}));
    const Json* viewIndex = Checker::find(a, "bufferView");
    const uint64_t offset = a.value("byteOffset", uint64_t(0));
    if (!viewIndex && Checker::find(a, "byteOffset"))
      return c.fail(Checker::at(p, "byteOffset"), "is set but bufferView is not");
    if (bytes && offset % bytes != 0)
      return c.fail(Checker::at(p, "byteOffset"), "{} is not a multiple of the component size {}", offset, bytes);
    if (viewIndex && bytes && components) {
      const Json& view = c.element("bufferViews", viewIndex->get<size_t>());
      const uint64_t viewOffset = view.value("byteOffset", uint64_t(0)),
                     viewLength = view["byteLength"].get<uint64_t>();
      if ((viewOffset + offset) % bytes != 0)
        return c.fail(p, "buffer view {} byteOffset {} + byteOffset {} is not a multiple of the component size {}",
                      viewIndex->get<uint64_t>(), viewOffset, offset, bytes);
      const uint64_t element = elementBytes(type, bytes);
      const uint64_t stride = view.value("byteStride", uint64_t(0));
      if (stride && stride < element)
        return c.fail(p, "buffer view {} byteStride {} is less than an element ({} bytes)", viewIndex->get<uint64_t>(),
                      stride, element);
      if (!fits(offset, stride ? stride : element, count, element, viewLength))
        return c.fail(p, "{} elements of {} bytes from byteOffset {} run past buffer view {} (byteLength {})", count,
                      element, offset, viewIndex->get<uint64_t>(), viewLength);
    }
    if (const Json* sparse = Checker::find(a, "sparse"))
      RAYSTER_TRY(checkSparse(c, *sparse, Checker::at(p, "sparse"), count, elementBytes(type, bytes)));
  }
  return okStatus();
}

// Top-level arrays, when present, hold at least one object.
Status checkTopLevelArrays(const Checker& c) {
  for (const char* key : {"accessors", "animations", "buffers", "bufferViews", "cameras", "images", "materials",
                          "meshes", "nodes", "samplers", "scenes", "skins", "textures"})
    if (const Json* a = Checker::find(c.root(), key); a && a->is_array() && a->empty())
      return c.fail(key, "is empty (leave it out instead)");
  return okStatus();
}

}  // namespace

Status checkBuffersAndAccessors(const Checker& c) {
  RAYSTER_TRY(checkAsset(c));
  RAYSTER_TRY(checkExtensionLists(c));
  RAYSTER_TRY(checkTopLevelArrays(c));
  RAYSTER_TRY(c.ref(c.root(), "scene", "", "scenes"));
  RAYSTER_TRY(checkBuffers(c));
  RAYSTER_TRY(checkBufferViews(c));
  return checkAccessors(c);
}

}  // namespace rayster::scene::gltf::schema

namespace rayster::scene::gltf {

Status checkSchema(const std::string& file, const nlohmann::json& root) {
  const schema::Checker c(file, root);
  RAYSTER_TRY(schema::checkBuffersAndAccessors(c));
  RAYSTER_TRY(schema::checkImagesAndTextures(c));
  RAYSTER_TRY(schema::checkMaterials(c));
  RAYSTER_TRY(schema::checkMeshes(c));
  RAYSTER_TRY(schema::checkNodesAndScenes(c));
  RAYSTER_TRY(schema::checkSkinsAndAnimations(c));
  RAYSTER_TRY(schema::checkCameras(c));
  return schema::checkLights(c);
}

}  // namespace rayster::scene::gltf
