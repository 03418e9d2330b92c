// What the glTF-Validator checks in the data rather than the JSON, over every accessor (not only the
// ones the displayed scene reads): min and max equal the values' extremes (ACCESSOR_MIN_MISMATCH /
// MAX_MISMATCH), floats are finite, sparse indices increase strictly and stay below the count,
// animation key times are >= 0 and increase strictly, vertex indices stay below the vertex count and
// are not the primitive restart value.
//
// Data that is not in the buffers yet is left to the readers: compressed buffer views
// (EXT_meshopt_compression) and accessors without a buffer view (zeros, Draco-decoded data).
#include <cmath>
#include <cstring>
#include <limits>
#include <set>

#include "scene/gltf_schema.h"

namespace rayster::scene::gltf {
namespace {

// The bytes of buffer view `view` from `offset`, or an empty span when they are not available.
struct Bytes {
  const uint8_t* data = nullptr;
  size_t size = 0;
};

Bytes viewBytes(const tinygltf::Model& model, int view, size_t offset) {
  if (view < 0 || size_t(view) >= model.bufferViews.size()) return {};
  const tinygltf::BufferView& bv = model.bufferViews[size_t(view)];
  if (bv.extensions.count("EXT_meshopt_compression") || bv.buffer < 0 || size_t(bv.buffer) >= model.buffers.size())
    return {};
  const std::vector<unsigned char>& data = model.buffers[size_t(bv.buffer)].data;
  if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset || offset > bv.byteLength) return {};
  return {data.data() + bv.byteOffset + offset, bv.byteLength - offset};
}

double component(const uint8_t* p, int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return double(int8_t(*p));
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return double(*p);
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    default: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

// One accessor's elements in order, sparse substitution applied: calls f(i, components).
// Returns false when its data is not available here (see the file comment).
class AccessorData {
 public:
  AccessorData(const tinygltf::Model& model, const tinygltf::Accessor& a) : a_(a) {
    bytes_ = schema::componentBytes(a.componentType);
    components_ = size_t(tinygltf::GetNumComponentsInType(uint32_t(a.type)));
    // Matrices of 1- and 2-byte components have padded columns; too rare to read here.
    if (a.type == TINYGLTF_TYPE_MAT2 || a.type == TINYGLTF_TYPE_MAT3) {
      if (bytes_ < 4) bytes_ = 0;
    }
    if (!bytes_ || components_ == 0 || a.bufferView < 0) return;
    element_ = bytes_ * components_;
    const int stride = a.ByteStride(model.bufferViews[size_t(a.bufferView)]);
    stride_ = stride > 0 ? size_t(stride) : element_;
    base_ = viewBytes(model, a.bufferView, a.byteOffset);
    if (!base_.data || a.count == 0 || stride_ * (a.count - 1) + element_ > base_.size) base_ = {};
    if (a.sparse.isSparse) {
      sparseValues_ = viewBytes(model, a.sparse.values.bufferView, size_t(a.sparse.values.byteOffset));
      if (size_t(a.sparse.count) * element_ > sparseValues_.size) base_ = {};
    }
  }
  bool available() const { return base_.data != nullptr; }

  // `sparseIndices` are already checked to increase strictly and stay below the count.
  template <class F>
  void forEach(const std::vector<uint32_t>& sparseIndices, F&& f) const {
    double v[16];
    size_t next = 0;
    for (size_t i = 0; i < a_.count; ++i) {
      const uint8_t* p = base_.data + i * stride_;
      if (next < sparseIndices.size() && sparseIndices[next] == i) p = sparseValues_.data + element_ * next++;
      for (size_t c = 0; c < components_; ++c) v[c] = component(p + c * bytes_, a_.componentType);
      if (!f(i, v)) return;
    }
  }
  size_t components() const { return components_; }

 private:
  const tinygltf::Accessor& a_;
  size_t bytes_ = 0, components_ = 0, element_ = 0, stride_ = 0;
  Bytes base_, sparseValues_;
};

Status readSparseIndices(const tinygltf::Model& model, size_t index, const std::string& file,
                         std::vector<uint32_t>& out) {
  const tinygltf::Accessor& a = model.accessors[index];
  out.clear();
  if (!a.sparse.isSparse) return okStatus();
  const size_t bytes = schema::componentBytes(a.sparse.indices.componentType);
  const Bytes b = viewBytes(model, a.sparse.indices.bufferView, size_t(a.sparse.indices.byteOffset));
  if (!b.data || !bytes || size_t(a.sparse.count) * bytes > b.size) return okStatus();
  for (size_t i = 0; i < size_t(a.sparse.count); ++i) {
    const uint32_t v = uint32_t(component(b.data + i * bytes, a.sparse.indices.componentType));
    if (v >= a.count)
      return bad(file, "accessors[{}].sparse.indices: element {} is {}, not below the accessor's count {}", index, i, v,
                 a.count);
    if (!out.empty() && v <= out.back())
      return bad(file, "accessors[{}].sparse.indices: element {} is {}, not above the one before ({})", index, i, v,
                 out.back());
    out.push_back(v);
  }
  return okStatus();
}

// Declared bounds equal the data's: the validator compares them as floats for float accessors.
Status checkBoundsAndValues(const tinygltf::Model& model, size_t index, const std::vector<uint32_t>& sparse,
                            const std::string& file) {
  const tinygltf::Accessor& a = model.accessors[index];
  const AccessorData data(model, a);
  if (!data.available()) return okStatus();
  const size_t n = data.components();
  const bool isFloat = a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  double lo[16], hi[16];
  for (size_t c = 0; c < n; ++c) lo[c] = std::numeric_limits<double>::infinity(), hi[c] = -lo[c];
  Status status = okStatus();
  data.forEach(sparse, [&](size_t i, const double* v) {
    for (size_t c = 0; c < n; ++c) {
      if (isFloat && !std::isfinite(v[c])) {
        status = bad(file, "accessors[{}]: element {} component {} is {}, not a finite number", index, i, c, v[c]);
        return false;
      }
      lo[c] = std::min(lo[c], v[c]);
      hi[c] = std::max(hi[c], v[c]);
    }
    return true;
  });
  if (!status) return status;
  auto declared = [&](double d) { return isFloat ? double(float(d)) : d; };
  if (a.minValues.size() == n)
    for (size_t c = 0; c < n; ++c)
      if (declared(a.minValues[c]) != lo[c])
        return bad(file, "accessors[{}].min[{}]: {}, but the smallest value is {}", index, c, a.minValues[c], lo[c]);
  if (a.maxValues.size() == n)
    for (size_t c = 0; c < n; ++c)
      if (declared(a.maxValues[c]) != hi[c])
        return bad(file, "accessors[{}].max[{}]: {}, but the largest value is {}", index, c, a.maxValues[c], hi[c]);
  return okStatus();
}

Status checkKeyTimes(const tinygltf::Model& model, size_t anim, size_t s, const std::vector<uint32_t>& sparse,
                     const std::string& file) {
  const int input = model.animations[anim].samplers[s].input;
  if (input < 0 || size_t(input) >= model.accessors.size()) return okStatus();
  const AccessorData data(model, model.accessors[size_t(input)]);
  if (!data.available() || data.components() != 1) return okStatus();
  Status status = okStatus();
  double previous = 0.0;
  data.forEach(sparse, [&](size_t i, const double* v) {
    if (v[0] < 0.0)
      status = bad(file, "animations[{}].samplers[{}].input: key {} is at {}, before 0", anim, s, i, v[0]);
    else if (i > 0 && !(v[0] > previous))
      status = bad(file, "animations[{}].samplers[{}].input: key {} at {} is not after key {} at {}", anim, s, i, v[0],
                   i - 1, previous);
    previous = v[0];
    return bool(status);
  });
  return status;
}

// Rotation keys are unit quaternions (the validator's tolerance, as for node rotations); for
// CUBICSPLINE only the values, not the tangents.
Status checkRotationKeys(const tinygltf::Model& model, size_t anim, size_t ch, const std::vector<uint32_t>& sparse,
                         const std::string& file) {
  const tinygltf::AnimationChannel& channel = model.animations[anim].channels[ch];
  const std::vector<tinygltf::AnimationSampler>& samplers = model.animations[anim].samplers;
  if (channel.target_path != "rotation" || channel.sampler < 0 || size_t(channel.sampler) >= samplers.size())
    return okStatus();
  const tinygltf::AnimationSampler& sampler = samplers[size_t(channel.sampler)];
  if (sampler.output < 0 || size_t(sampler.output) >= model.accessors.size()) return okStatus();
  const tinygltf::Accessor& a = model.accessors[size_t(sampler.output)];
  const AccessorData data(model, a);
  if (!data.available() || data.components() != 4 || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
    return okStatus();
  const bool cubic = sampler.interpolation == "CUBICSPLINE";
  Status status = okStatus();
  data.forEach(sparse, [&](size_t i, const double* v) {
    if (cubic && i % 3 != 1) return true;
    const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
    if (std::abs(1.0 - length) > 0.00769)
      status = bad(file, "animations[{}].samplers[{}].output: rotation key {} has length {}, not a unit quaternion",
                   anim, channel.sampler, cubic ? i / 3 : i, length);
    return bool(status);
  });
  return status;
}

Status checkVertexIndices(const tinygltf::Model& model, size_t m, size_t p, const std::string& file,
                          const std::vector<std::vector<uint32_t>>& sparse) {
  const tinygltf::Primitive& prim = model.meshes[m].primitives[p];
  if (prim.indices < 0 || size_t(prim.indices) >= model.accessors.size() || prim.attributes.empty() ||
      prim.extensions.count("KHR_draco_mesh_compression"))
    return okStatus();
  size_t vertices = std::numeric_limits<size_t>::max();
  for (const auto& [name, accessor] : prim.attributes)
    if (accessor >= 0 && size_t(accessor) < model.accessors.size())
      vertices = std::min(vertices, model.accessors[size_t(accessor)].count);
  const tinygltf::Accessor& a = model.accessors[size_t(prim.indices)];
  const AccessorData data(model, a);
  if (!data.available()) return okStatus();
  const double restart = a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 255.0
                         : a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 65535.0
                                                                                     : 4294967295.0;
  Status status = okStatus();
  data.forEach(sparse[size_t(prim.indices)], [&](size_t i, const double* v) {
    if (v[0] == restart)
      status =
          bad(file, "meshes[{}].primitives[{}].indices: index {} is {}, the primitive restart value", m, p, i, v[0]);
    else if (v[0] >= double(vertices))
      status = bad(file, "meshes[{}].primitives[{}].indices: index {} is {}, not below the vertex count {}", m, p, i,
                   v[0], vertices);
    return bool(status);
  });
  return status;
}

}  // namespace

Status checkAccessorData(const tinygltf::Model& model, const std::string& file) {
  std::vector<std::vector<uint32_t>> sparse(model.accessors.size());
  for (size_t i = 0; i < model.accessors.size(); ++i) {
    RAYSTER_TRY(readSparseIndices(model, i, file, sparse[i]));
    RAYSTER_TRY(checkBoundsAndValues(model, i, sparse[i], file));
  }
  for (size_t a = 0; a < model.animations.size(); ++a)
    for (size_t s = 0; s < model.animations[a].samplers.size(); ++s) {
      const int input = model.animations[a].samplers[s].input;
      if (input >= 0 && size_t(input) < sparse.size())
        RAYSTER_TRY(checkKeyTimes(model, a, s, sparse[size_t(input)], file));
    }
  for (size_t a = 0; a < model.animations.size(); ++a)
    for (size_t c = 0; c < model.animations[a].channels.size(); ++c) {
      const int sampler = model.animations[a].channels[c].sampler;
      if (sampler < 0 || size_t(sampler) >= model.animations[a].samplers.size()) continue;
      const int output = model.animations[a].samplers[size_t(sampler)].output;
      if (output >= 0 && size_t(output) < sparse.size())
        RAYSTER_TRY(checkRotationKeys(model, a, c, sparse[size_t(output)], file));
    }
  for (size_t m = 0; m < model.meshes.size(); ++m)
    for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p)
      RAYSTER_TRY(checkVertexIndices(model, m, p, file, sparse));
  return okStatus();
}

}  // namespace rayster::scene::gltf
