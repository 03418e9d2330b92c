// KHR_draco_mesh_compression: a primitive whose attributes and indices are one Draco mesh in a
// buffer view, decoded with Debian's libdraco. The decoded values are written, in the component
// types the primitive's accessors declare, into a new buffer, and the primitive is pointed at
// copies of its accessors that read it; from there on it is an ordinary primitive (bounds checks,
// normalized attributes, flat normals). Quantized Draco attributes come out dequantized.
#include <algorithm>
#include <cstring>
#include <memory>

#include <draco/compression/decode.h>

#include "scene/gltf_internal.h"

namespace rayster::scene::gltf {
namespace {

constexpr const char* kExt = "KHR_draco_mesh_compression";

// Appends `bytes` to `out` (4-byte aligned, as accessors need) and returns where they start.
size_t appendAligned(std::vector<unsigned char>& out, size_t bytes) {
  const size_t start = (out.size() + 3) & ~size_t(3);
  out.resize(start + bytes);
  return start;
}

template <class T>
bool convertPoints(const draco::PointAttribute& attr, size_t points, int components, unsigned char* out) {
  std::vector<T> value(static_cast<size_t>(components));
  for (size_t i = 0; i < points; ++i) {
    const draco::AttributeValueIndex avi = attr.mapped_index(draco::PointIndex(uint32_t(i)));
    if (avi.value() >= attr.size()) return false;
    if (!attr.ConvertValue<T>(avi, int8_t(components), value.data())) return false;
    std::memcpy(out + i * components * sizeof(T), value.data(), components * sizeof(T));
  }
  return true;
}

bool convertAttribute(const draco::PointAttribute& attr, size_t points, int components, int componentType,
                      unsigned char* out) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return convertPoints<float>(attr, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return convertPoints<int8_t>(attr, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return convertPoints<uint8_t>(attr, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return convertPoints<int16_t>(attr, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return convertPoints<uint16_t>(attr, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return convertPoints<uint32_t>(attr, points, components, out);
    default:
      return false;
  }
}

size_t componentBytes(int componentType) {
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

// Exporters write an attribute's bounds from the data before Draco quantized it, and dequantized
// values can land up to one quantization step outside them (gltf-transform's 14-bit positions on a
// 0.8 m box: 0.40005 for a bound of 0.4). Such bounds are widened to the decoded data, as long as
// the overshoot is within 1/128 of the extent (a 7-bit quantization step, coarser than any
// exporter uses); a larger one is a real contradiction that checkBounds reports.
void widenBounds(tinygltf::Accessor& accessor, const float* values, size_t points, int components) {
  if (accessor.minValues.size() != size_t(components) || accessor.maxValues.size() != size_t(components)) return;
  for (int c = 0; c < components; ++c) {
    double lo = accessor.minValues[size_t(c)], hi = accessor.maxValues[size_t(c)];
    const double slack = std::max(hi - lo, 0.0) / 128.0;
    for (size_t i = 0; i < points; ++i) {
      const double v = values[i * size_t(components) + size_t(c)];
      if (v < lo && v >= accessor.minValues[size_t(c)] - slack) lo = v;
      if (v > hi && v <= accessor.maxValues[size_t(c)] + slack) hi = v;
    }
    accessor.minValues[size_t(c)] = lo;
    accessor.maxValues[size_t(c)] = hi;
  }
}

// A new view over `buffer` bytes [offset, offset + length) and a copy of `accessor` that reads it.
int addAccessor(tinygltf::Model& model, int buffer, size_t offset, size_t length, tinygltf::Accessor accessor) {
  tinygltf::BufferView view;
  view.buffer = buffer;
  view.byteOffset = offset;
  view.byteLength = length;
  model.bufferViews.push_back(view);
  accessor.bufferView = int(model.bufferViews.size() - 1);
  accessor.byteOffset = 0;
  accessor.sparse.isSparse = false;  // Draco data replaces everything the accessor had
  model.accessors.push_back(std::move(accessor));
  return int(model.accessors.size() - 1);
}

Status decodePrimitive(tinygltf::Model& model, const std::string& file, size_t meshIndex, size_t primIndex,
                       int outBuffer) {
  tinygltf::Primitive& prim = model.meshes[meshIndex].primitives[primIndex];
  const std::string path = fmt::format("meshes[{}].primitives[{}].extensions.{}", meshIndex, primIndex, kExt);
  const tinygltf::Value& ext = prim.extensions.at(kExt);
  if (!ext.IsObject()) return bad(file, "{} is not an object", path);
  if (!ext.Has("bufferView") || !ext.Get("bufferView").IsInt() || ext.Get("bufferView").GetNumberAsInt() < 0 ||
      size_t(ext.Get("bufferView").GetNumberAsInt()) >= model.bufferViews.size())
    return bad(file, "{}.bufferView is missing or names no buffer view", path);
  if (!ext.Has("attributes") || !ext.Get("attributes").IsObject())
    return bad(file, "{}.attributes is required (an object)", path);
  // Draco encodes triangle meshes and point clouds; a point primitive is skipped later anyway.
  if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) return okStatus();

  const int viewIndex = ext.Get("bufferView").GetNumberAsInt();
  const tinygltf::BufferView& view = model.bufferViews[size_t(viewIndex)];
  if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
    return bad(file, "bufferViews[{}].buffer {} does not exist", viewIndex, view.buffer);
  const std::vector<unsigned char>& src = model.buffers[size_t(view.buffer)].data;
  if (view.byteOffset > src.size() || view.byteLength > src.size() - view.byteOffset)
    return bad(file, "{}: bufferViews[{}] lies outside buffer {}", path, viewIndex, view.buffer);

  draco::DecoderBuffer input;
  input.Init(reinterpret_cast<const char*>(src.data() + view.byteOffset), view.byteLength);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&input);
  if (!decoded.ok())
    return bad(file, "{}: Draco cannot decode bufferViews[{}]: {}", path, viewIndex,
               oneLine(decoded.status().error_msg_string()));
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  if (!mesh) return bad(file, "{}: Draco decoded no mesh from bufferViews[{}]", path, viewIndex);
  const size_t points = mesh->num_points();

  // Attributes: the extension maps glTF semantics to Draco attribute ids.
  const tinygltf::Value& attributes = ext.Get("attributes");
  for (const std::string& name : attributes.Keys()) {
    const tinygltf::Value& id = attributes.Get(name);
    if (!id.IsInt() || id.GetNumberAsInt() < 0)
      return bad(file, "{}.attributes.{} is not a Draco attribute id", path, name);
    auto it = prim.attributes.find(name);
    if (it == prim.attributes.end())
      return bad(file, "{}.attributes.{}: the primitive has no {} attribute", path, name, name);
    if (it->second < 0 || size_t(it->second) >= model.accessors.size())
      return bad(file, "{}: accessor {} of {} does not exist", path, it->second, name);
    const tinygltf::Accessor& accessor = model.accessors[size_t(it->second)];
    const draco::PointAttribute* attr = mesh->GetAttributeByUniqueId(uint32_t(id.GetNumberAsInt()));
    if (!attr)
      return bad(file, "{}.attributes.{}: the Draco mesh has no attribute {}", path, name, id.GetNumberAsInt());
    const int components = tinygltf::GetNumComponentsInType(uint32_t(accessor.type));
    const size_t size = componentBytes(accessor.componentType);
    if (components <= 0 || components > 4 || size == 0)
      return bad(file, "{}: accessor {} of {} has an unusable type", path, it->second, name);
    if (attr->num_components() != components)
      return bad(file, "{}.attributes.{}: Draco has {} components, accessor {} has {}", path, name,
                 attr->num_components(), it->second, components);
    if (accessor.count != points)
      return bad(file, "{}.attributes.{}: accessor {} count {} is not the {} decoded points", path, name, it->second,
                 accessor.count, points);
    const size_t bytes = points * size_t(components) * size;
    std::vector<unsigned char>& out = model.buffers[size_t(outBuffer)].data;
    const size_t offset = appendAligned(out, bytes);
    if (!convertAttribute(*attr, points, components, accessor.componentType, out.data() + offset))
      return bad(file, "{}.attributes.{}: Draco values do not convert to accessor {}'s component type", path, name,
                 it->second);
    tinygltf::Accessor decodedAccessor = accessor;
    if (accessor.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
      widenBounds(decodedAccessor, reinterpret_cast<const float*>(out.data() + offset), points, components);
    it->second = addAccessor(model, outBuffer, offset, bytes, std::move(decodedAccessor));
  }

  // Indices, in the indices accessor's component type (a new UNSIGNED_INT accessor where it has none).
  const size_t faces = mesh->num_faces();
  tinygltf::Accessor indices;
  if (prim.indices >= 0) {
    if (size_t(prim.indices) >= model.accessors.size())
      return bad(file, "{}: indices accessor {} does not exist", path, prim.indices);
    indices = model.accessors[size_t(prim.indices)];
    if (indices.count != faces * 3)
      return bad(file, "{}: indices accessor {} count {} is not the {} decoded indices", path, prim.indices,
                 indices.count, faces * 3);
  } else {
    indices.type = TINYGLTF_TYPE_SCALAR;
    indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    indices.count = faces * 3;
  }
  const size_t size = componentBytes(indices.componentType);
  if (indices.type != TINYGLTF_TYPE_SCALAR ||
      (size != 4 && indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
       indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) ||
      indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
    return bad(file, "{}: indices accessor {} is not an unsigned integer scalar", path, prim.indices);
  const uint64_t limit = size == 4 ? UINT32_MAX : (uint64_t(1) << (8 * size)) - 1;
  std::vector<unsigned char>& out = model.buffers[size_t(outBuffer)].data;
  const size_t offset = appendAligned(out, faces * 3 * size);
  for (size_t f = 0; f < faces; ++f) {
    const draco::Mesh::Face& face = mesh->face(draco::FaceIndex(uint32_t(f)));
    for (int k = 0; k < 3; ++k) {
      const uint64_t v = face[k].value();
      if (v >= points || v > limit)
        return bad(file, "{}: decoded index {} is {}, past the {} points or its component type", path, f * 3 + k, v,
                   points);
      std::memcpy(out.data() + offset + (f * 3 + size_t(k)) * size, &v, size);  // little-endian
    }
  }
  prim.indices = addAccessor(model, outBuffer, offset, faces * 3 * size, indices);
  return okStatus();
}

}  // namespace

Status decodeDraco(tinygltf::Model& model, const std::string& file) {
  int outBuffer = -1;
  for (size_t m = 0; m < model.meshes.size(); ++m)
    for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      if (!model.meshes[m].primitives[p].extensions.count(kExt)) continue;
      if (outBuffer < 0) {
        model.buffers.emplace_back();
        model.buffers.back().name = "draco-decoded";
        outBuffer = int(model.buffers.size() - 1);
      }
      RAYSTER_TRY(decodePrimitive(model, file, m, p, outBuffer));
    }
  return okStatus();
}

}  // namespace rayster::scene::gltf
