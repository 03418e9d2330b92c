// Accessor reads for the glTF loader. Nothing tinygltf parsed is trusted: every index, offset,
// stride and count is checked here, with overflow-checked arithmetic, before a byte is read or a
// vector allocated.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "scene/gltf_internal.h"

namespace rayster::scene::gltf {
namespace {

// Accessors without a buffer view (sparse on zeros) allocate memory the file does not pay for in
// bytes, so their count is capped well below what a real asset would need.
constexpr size_t kMaxZeroBasedCount = size_t(1) << 24;

size_t componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

const char* typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
    default:
      return "unknown";
  }
}

template <class T>
T load(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));  // glTF data need not be aligned in memory
  return v;
}

// One component as a float, normalized integers mapped as the glTF spec says (signed: max(c/MAX, -1)).
float decodeFloat(const uint8_t* p, int componentType, bool normalized) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      float c = load<int8_t>(p);
      return normalized ? std::max(c / 127.0f, -1.0f) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      float c = load<uint8_t>(p);
      return normalized ? c / 255.0f : c;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      float c = load<int16_t>(p);
      return normalized ? std::max(c / 32767.0f, -1.0f) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      float c = load<uint16_t>(p);
      return normalized ? c / 65535.0f : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return float(load<uint32_t>(p));
    default:
      return 0.0f;
  }
}

uint32_t decodeUint(const uint8_t* p, int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return load<uint8_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return load<uint16_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return load<uint32_t>(p);
    default:
      return 0;
  }
}

// A validated byte range of a buffer view.
struct ViewBytes {
  const uint8_t* data = nullptr;
  size_t length = 0;
};

Result<ViewBytes> viewBytes(const tinygltf::Model& model, int view, const std::string& file, int accessor) {
  if (view < 0 || size_t(view) >= model.bufferViews.size())
    return bad(file, "accessor {} uses buffer view {}, which does not exist", accessor, view);
  const tinygltf::BufferView& bv = model.bufferViews[size_t(view)];
  if (bv.buffer < 0 || size_t(bv.buffer) >= model.buffers.size())
    return bad(file, "buffer view {} uses buffer {}, which does not exist", view, bv.buffer);
  const std::vector<unsigned char>& data = model.buffers[size_t(bv.buffer)].data;
  size_t end = 0;
  if (__builtin_add_overflow(bv.byteOffset, bv.byteLength, &end) || end > data.size())
    return bad(file, "buffer view {} reaches past the end of buffer {}", view, bv.buffer);
  return ViewBytes{data.data() + bv.byteOffset, bv.byteLength};
}

// Checks that `count` elements of `elementSize` bytes, `stride` apart from `offset`, fit in `length`.
bool fits(size_t offset, size_t stride, size_t count, size_t elementSize, size_t length) {
  if (count == 0) return offset <= length;
  size_t span = 0, end = 0;
  return !__builtin_mul_overflow(stride, count - 1, &span) && !__builtin_add_overflow(span, elementSize, &end) &&
         !__builtin_add_overflow(end, offset, &end) && end <= length;
}

// Everything about an accessor needed to read it, after validation.
struct Layout {
  const uint8_t* data = nullptr;  // nullptr: all zeros (sparse accessor without a buffer view)
  size_t stride = 0, count = 0, elementSize = 0, componentSize = 0;
  int componentType = 0;
  bool normalized = false;
};

Result<Layout> resolve(const tinygltf::Model& model, int index, int wantType, bool integerOnly,
                       const std::string& file) {
  if (index < 0 || size_t(index) >= model.accessors.size()) return bad(file, "accessor {} does not exist", index);
  const tinygltf::Accessor& acc = model.accessors[size_t(index)];
  if (acc.type != wantType)
    return bad(file, "accessor {} has type {}, expected {}", index, typeName(acc.type), typeName(wantType));
  Layout layout;
  layout.componentType = acc.componentType;
  layout.componentSize = componentSize(acc.componentType);
  if (layout.componentSize == 0)
    return bad(file, "accessor {} has invalid component type {}", index, acc.componentType);
  const bool isFloat = acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  if (integerOnly && (isFloat || acc.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
                      acc.componentType == TINYGLTF_COMPONENT_TYPE_SHORT))
    return bad(file, "accessor {} holds indices but its component type {} is not unsigned", index, acc.componentType);
  if (acc.normalized && (isFloat || acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    return bad(file, "accessor {} is normalized but its component type {} cannot be", index, acc.componentType);
  layout.normalized = acc.normalized;
  layout.elementSize = layout.componentSize * size_t(tinygltf::GetNumComponentsInType(uint32_t(wantType)));
  layout.count = acc.count;

  if (acc.bufferView < 0) {
    // No data: zeros, possibly with sparse values on top. Cap before anything allocates.
    if (acc.count > kMaxZeroBasedCount)
      return bad(file, "accessor {} count {} is too large for an accessor without a buffer view", index, acc.count);
    return layout;
  }
  Result<ViewBytes> view = viewBytes(model, acc.bufferView, file, index);
  if (!view) return view.error();
  const tinygltf::BufferView& bv = model.bufferViews[size_t(acc.bufferView)];
  layout.stride = bv.byteStride != 0 ? bv.byteStride : layout.elementSize;
  if (layout.stride < layout.elementSize)
    return bad(file, "accessor {}: byteStride {} of buffer view {} is smaller than an element ({} bytes)", index,
               bv.byteStride, acc.bufferView, layout.elementSize);
  // This check also bounds the count by the file's size, so the allocation that follows is paid for.
  if (!fits(acc.byteOffset, layout.stride, acc.count, layout.elementSize, view->length))
    return bad(file, "accessor {} reads past the end of buffer view {}", index, acc.bufferView);
  layout.data = view->data + acc.byteOffset;
  return layout;
}

// Calls apply(element, valueBytes) for each sparse entry, after bounds-checking both arrays.
template <class F>
Status forEachSparse(const tinygltf::Model& model, int index, const Layout& layout, const std::string& file,
                     F&& apply) {
  const tinygltf::Accessor& acc = model.accessors[size_t(index)];
  if (!acc.sparse.isSparse) return okStatus();
  const auto& sp = acc.sparse;
  if (sp.count < 1 || size_t(sp.count) > layout.count)
    return bad(file, "accessor {} has sparse count {} for {} elements", index, sp.count, layout.count);
  const size_t indexSize = componentSize(sp.indices.componentType);
  if (indexSize == 0 || sp.indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
      sp.indices.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
      sp.indices.componentType == TINYGLTF_COMPONENT_TYPE_SHORT)
    return bad(file, "accessor {} has sparse indices of invalid component type {}", index, sp.indices.componentType);
  if (sp.indices.byteOffset < 0 || sp.values.byteOffset < 0)
    return bad(file, "accessor {} has a negative sparse byteOffset", index);
  Result<ViewBytes> indexView = viewBytes(model, sp.indices.bufferView, file, index);
  if (!indexView) return indexView.error();
  Result<ViewBytes> valueView = viewBytes(model, sp.values.bufferView, file, index);
  if (!valueView) return valueView.error();
  const size_t count = size_t(sp.count);
  if (!fits(size_t(sp.indices.byteOffset), indexSize, count, indexSize, indexView->length))
    return bad(file, "accessor {} sparse indices read past the end of buffer view {}", index, sp.indices.bufferView);
  if (!fits(size_t(sp.values.byteOffset), layout.elementSize, count, layout.elementSize, valueView->length))
    return bad(file, "accessor {} sparse values read past the end of buffer view {}", index, sp.values.bufferView);
  const uint8_t* indices = indexView->data + sp.indices.byteOffset;
  const uint8_t* values = valueView->data + sp.values.byteOffset;
  for (size_t i = 0; i < count; ++i) {
    const uint32_t element = decodeUint(indices + i * indexSize, sp.indices.componentType);
    if (element >= layout.count)
      return bad(file, "accessor {} sparse index {} is {}, past the count {}", index, i, element, layout.count);
    apply(element, values + i * layout.elementSize);
  }
  return okStatus();
}

template <int N>
Result<std::vector<glm::vec<N, float>>> readVectors(const tinygltf::Model& model, int index, int type,
                                                    const std::string& file) {
  Result<Layout> layout = resolve(model, index, type, false, file);
  if (!layout) return layout.error();
  const Layout& l = *layout;
  auto decode = [&](const uint8_t* p) {
    glm::vec<N, float> v;
    for (int c = 0; c < N; ++c) v[c] = decodeFloat(p + size_t(c) * l.componentSize, l.componentType, l.normalized);
    return v;
  };
  std::vector<glm::vec<N, float>> out(l.count, glm::vec<N, float>(0.0f));
  if (l.data)
    for (size_t i = 0; i < l.count; ++i) out[i] = decode(l.data + i * l.stride);
  RAYSTER_TRY(forEachSparse(model, index, l, file, [&](uint32_t e, const uint8_t* p) { out[e] = decode(p); }));
  return out;
}

}  // namespace

Result<std::vector<float>> readScalars(const tinygltf::Model& model, int accessor, const std::string& file) {
  Result<std::vector<glm::vec<1, float>>> values = readVectors<1>(model, accessor, TINYGLTF_TYPE_SCALAR, file);
  if (!values) return values.error();
  std::vector<float> out;
  out.reserve(values->size());
  for (const glm::vec<1, float>& v : *values) out.push_back(v.x);
  return out;
}

Result<std::vector<glm::vec2>> readVec2(const tinygltf::Model& model, int accessor, const std::string& file) {
  return readVectors<2>(model, accessor, TINYGLTF_TYPE_VEC2, file);
}

Result<std::vector<glm::vec3>> readVec3(const tinygltf::Model& model, int accessor, const std::string& file) {
  return readVectors<3>(model, accessor, TINYGLTF_TYPE_VEC3, file);
}

Result<std::vector<glm::vec4>> readVec4(const tinygltf::Model& model, int accessor, const std::string& file) {
  return readVectors<4>(model, accessor, TINYGLTF_TYPE_VEC4, file);
}

Result<std::vector<glm::mat4>> readMat4(const tinygltf::Model& model, int accessor, const std::string& file) {
  Result<Layout> layout = resolve(model, accessor, TINYGLTF_TYPE_MAT4, false, file);
  if (!layout) return layout.error();
  const Layout& l = *layout;
  // Float matrices have no column padding (glTF 2.0 §3.6.2.4); the other component types are not
  // allowed where Rayster reads matrices (inverse bind matrices).
  if (l.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
    return bad(file, "accessor {} holds MAT4 of component type {}, need float (5126)", accessor, l.componentType);
  auto decode = [&](const uint8_t* p) {
    glm::mat4 m;
    for (int c = 0; c < 16; ++c) m[c / 4][c % 4] = load<float>(p + size_t(c) * 4);  // column-major, as glm
    return m;
  };
  std::vector<glm::mat4> out(l.count, glm::mat4(0.0f));
  if (l.data)
    for (size_t i = 0; i < l.count; ++i) out[i] = decode(l.data + i * l.stride);
  RAYSTER_TRY(forEachSparse(model, accessor, l, file, [&](uint32_t e, const uint8_t* p) { out[e] = decode(p); }));
  return out;
}

Result<std::vector<uint32_t>> readIndices(const tinygltf::Model& model, int accessor, const std::string& file) {
  Result<Layout> layout = resolve(model, accessor, TINYGLTF_TYPE_SCALAR, true, file);
  if (!layout) return layout.error();
  const Layout& l = *layout;
  std::vector<uint32_t> out(l.count, 0u);
  if (l.data)
    for (size_t i = 0; i < l.count; ++i) out[i] = decodeUint(l.data + i * l.stride, l.componentType);
  RAYSTER_TRY(forEachSparse(model, accessor, l, file,
                            [&](uint32_t e, const uint8_t* p) { out[e] = decodeUint(p, l.componentType); }));
  return out;
}

}  // namespace rayster::scene::gltf
