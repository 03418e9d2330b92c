#include "rhi/spirv_reflect.h"

#include <algorithm>
#include <unordered_map>

namespace rayster::rhi {
namespace {

// Opcodes, decorations and storage classes used here (SPIR-V specification, §3).
enum Op : uint32_t {
  OpName = 5,
  OpTypeBool = 20,
  OpTypeInt = 21,
  OpTypeFloat = 22,
  OpTypeVector = 23,
  OpTypeMatrix = 24,
  OpTypeImage = 25,
  OpTypeSampler = 26,
  OpTypeSampledImage = 27,
  OpTypeArray = 28,
  OpTypeRuntimeArray = 29,
  OpTypeStruct = 30,
  OpTypePointer = 32,
  OpConstant = 43,
  OpVariable = 59,
  OpDecorate = 71,
  OpMemberDecorate = 72,
  OpTypeAccelerationStructureKHR = 5341,
};
enum Decoration : uint32_t {
  Block = 2,
  BufferBlock = 3,
  ArrayStride = 6,
  MatrixStride = 7,
  NonWritable = 24,
  NonReadable = 25,
  Binding = 33,
  DescriptorSet = 34,
  Offset = 35,
};
enum StorageClass : uint32_t { UniformConstant = 0, Uniform = 2, PushConstant = 9, StorageBuffer = 12 };
constexpr uint32_t kMagic = 0x07230203;
constexpr uint32_t kDimBuffer = 5;

struct Type {
  uint32_t op = 0;
  std::vector<uint32_t> operands;  // the instruction's words after the result id
};
struct Member {
  uint32_t offset = 0, matrixStride = 0;
};
struct Ids {
  std::unordered_map<uint32_t, std::string> names;
  std::unordered_map<uint32_t, Type> types;
  std::unordered_map<uint32_t, uint32_t> constants;                 // 32-bit integer constants (array lengths)
  std::unordered_map<uint32_t, std::vector<uint32_t>> decorations;  // id -> decoration words (pairs flattened)
  std::unordered_map<uint32_t, uint32_t> set, binding, arrayStride;
  std::unordered_map<uint32_t, std::vector<Member>> members;
  struct Variable {
    uint32_t id, pointerType, storage;
  };
  std::vector<Variable> variables;

  bool has(uint32_t id, uint32_t decoration) const {
    auto it = decorations.find(id);
    return it != decorations.end() && std::find(it->second.begin(), it->second.end(), decoration) != it->second.end();
  }
};

std::string literalString(std::span<const uint32_t> words) {
  std::string s;
  for (uint32_t w : words)
    for (int i = 0; i < 4; ++i) {
      const char c = char((w >> (8 * i)) & 0xFF);
      if (c == 0) return s;
      s += c;
    }
  return s;
}

// Bytes a value of type `id` occupies in a push-constant block (explicit layout: offsets and strides
// are decorations). `matrixStride` comes from the member that holds the matrix.
uint32_t typeSize(const Ids& ids, uint32_t id, uint32_t matrixStride = 0) {
  auto it = ids.types.find(id);
  if (it == ids.types.end()) return 0;
  const Type& t = it->second;
  switch (t.op) {
    case OpTypeBool:
      return 4;
    case OpTypeInt:
    case OpTypeFloat:
      return t.operands[0] / 8;
    case OpTypeVector:
      return t.operands[1] * typeSize(ids, t.operands[0]);
    case OpTypeMatrix:
      return t.operands[1] * (matrixStride ? matrixStride : typeSize(ids, t.operands[0]));
    case OpTypeArray: {
      auto len = ids.constants.find(t.operands[1]);
      auto stride = ids.arrayStride.find(id);
      const uint32_t n = len == ids.constants.end() ? 0 : len->second;
      return n * (stride == ids.arrayStride.end() ? typeSize(ids, t.operands[0]) : stride->second);
    }
    case OpTypeStruct: {
      uint32_t size = 0;
      auto mem = ids.members.find(id);
      for (size_t m = 0; m < t.operands.size(); ++m) {
        const Member info = mem != ids.members.end() && m < mem->second.size() ? mem->second[m] : Member{};
        size = std::max(size, info.offset + typeSize(ids, t.operands[m], info.matrixStride));
      }
      return size;
    }
    default:
      return 0;
  }
}

bool fail(std::string* error, std::string message) {
  if (error) *error = std::move(message);
  return false;
}

}  // namespace

const ShaderBinding* ShaderInterface::find(std::string_view name, uint32_t set) const {
  for (const ShaderBinding& b : bindings)
    if (b.set == set && b.name == name) return &b;
  return nullptr;
}

const ShaderBinding* ShaderInterface::at(uint32_t set, uint32_t binding) const {
  for (const ShaderBinding& b : bindings)
    if (b.set == set && b.binding == binding) return &b;
  return nullptr;
}

bool ShaderInterface::usesSet(uint32_t set) const {
  return std::any_of(bindings.begin(), bindings.end(), [set](const ShaderBinding& b) { return b.set == set; });
}

std::optional<ShaderInterface> reflectSpirv(std::span<const uint32_t> words, VkShaderStageFlagBits stage,
                                            std::string* error) {
  if (words.size() < 5 || words[0] != kMagic) {
    fail(error, "not a SPIR-V module");
    return std::nullopt;
  }
  Ids ids;
  for (size_t at = 5; at < words.size();) {
    const uint32_t count = words[at] >> 16, op = words[at] & 0xFFFF;
    if (count == 0 || at + count > words.size()) {
      fail(error, "truncated SPIR-V instruction");
      return std::nullopt;
    }
    const std::span<const uint32_t> w = words.subspan(at + 1, count - 1);  // operands
    switch (op) {
      case OpName:
        ids.names[w[0]] = literalString(w.subspan(1));
        break;
      case OpDecorate:
        ids.decorations[w[0]].push_back(w[1]);
        if (w[1] == DescriptorSet) ids.set[w[0]] = w[2];
        if (w[1] == Binding) ids.binding[w[0]] = w[2];
        if (w[1] == ArrayStride) ids.arrayStride[w[0]] = w[2];
        break;
      case OpMemberDecorate: {
        auto& members = ids.members[w[0]];
        if (members.size() <= w[1]) members.resize(w[1] + 1);
        if (w[2] == Offset) members[w[1]].offset = w[3];
        if (w[2] == MatrixStride) members[w[1]].matrixStride = w[3];
        break;
      }
      case OpConstant:
        ids.constants[w[1]] = w[2];  // (result type, id, value): only the low word matters for lengths
        break;
      case OpVariable:
        ids.variables.push_back({w[1], w[0], w[2]});
        break;
      default:
        if ((op >= OpTypeBool && op <= OpTypePointer) || op == OpTypeAccelerationStructureKHR)
          ids.types[w[0]] = {op, std::vector<uint32_t>(w.begin() + 1, w.end())};
        break;
    }
    at += count;
  }

  ShaderInterface out;
  out.stages = stage;
  for (const auto& v : ids.variables) {
    const Type& pointer = ids.types[v.pointerType];
    if (pointer.op != OpTypePointer) continue;
    uint32_t type = pointer.operands[1];
    if (v.storage == PushConstant) {
      out.pushConstantBytes = std::max(out.pushConstantBytes, typeSize(ids, type));
      continue;
    }
    if (v.storage != UniformConstant && v.storage != Uniform && v.storage != StorageBuffer) continue;
    if (!ids.set.count(v.id) || !ids.binding.count(v.id)) continue;
    ShaderBinding b;
    b.set = ids.set[v.id];
    b.binding = ids.binding[v.id];
    b.stages = stage;
    b.name = ids.names[v.id];
    b.nonWritable = ids.has(v.id, NonWritable);
    b.nonReadable = ids.has(v.id, NonReadable);
    // Arrays of descriptors (one level: Rayster's bindless set).
    if (ids.types[type].op == OpTypeArray) {
      auto len = ids.constants.find(ids.types[type].operands[1]);
      b.count = len == ids.constants.end() ? 1 : len->second;
      type = ids.types[type].operands[0];
    } else if (ids.types[type].op == OpTypeRuntimeArray) {
      b.count = 0;
      type = ids.types[type].operands[0];
    }
    const Type& t = ids.types[type];
    if (b.name.empty()) b.name = ids.names[type];  // an anonymous block: its type's name
    switch (t.op) {
      case OpTypeSampledImage:
        b.type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        break;
      case OpTypeSampler:
        b.type = VK_DESCRIPTOR_TYPE_SAMPLER;
        break;
      case OpTypeAccelerationStructureKHR:
        b.type = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
        break;
      case OpTypeImage: {
        const uint32_t dim = t.operands[1], sampled = t.operands[5];
        if (dim == kDimBuffer)
          b.type = sampled == 2 ? VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER : VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
        else
          b.type = sampled == 2 ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
        break;
      }
      case OpTypeStruct:
        if (v.storage == StorageBuffer || ids.has(type, BufferBlock))
          b.type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        else if (ids.has(type, Block))
          b.type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        break;
      default:
        break;
    }
    if (b.type == VK_DESCRIPTOR_TYPE_MAX_ENUM) {
      fail(error, "descriptor '" + b.name + "' (set " + std::to_string(b.set) + ", binding " +
                      std::to_string(b.binding) + ") has a type Rayster does not bind");
      return std::nullopt;
    }
    out.bindings.push_back(std::move(b));
  }
  std::sort(out.bindings.begin(), out.bindings.end(), [](const ShaderBinding& a, const ShaderBinding& b) {
    return a.set != b.set ? a.set < b.set : a.binding < b.binding;
  });
  return out;
}

bool mergeInterface(ShaderInterface& into, const ShaderInterface& stage, std::string* error) {
  into.stages |= stage.stages;
  into.pushConstantBytes = std::max(into.pushConstantBytes, stage.pushConstantBytes);
  for (const ShaderBinding& b : stage.bindings) {
    auto it = std::find_if(into.bindings.begin(), into.bindings.end(),
                           [&](const ShaderBinding& x) { return x.set == b.set && x.binding == b.binding; });
    if (it == into.bindings.end()) {
      into.bindings.push_back(b);
      continue;
    }
    if (it->type != b.type || it->count != b.count)
      return fail(error, "set " + std::to_string(b.set) + " binding " + std::to_string(b.binding) + " is '" + it->name +
                             "' in one stage and '" + b.name + "' of another type or size in another");
    it->stages |= b.stages;
    it->nonWritable = it->nonWritable && b.nonWritable;  // written by any stage: written
    it->nonReadable = it->nonReadable && b.nonReadable;
    if (it->name.empty()) it->name = b.name;
  }
  std::sort(into.bindings.begin(), into.bindings.end(), [](const ShaderBinding& a, const ShaderBinding& b) {
    return a.set != b.set ? a.set < b.set : a.binding < b.binding;
  });
  return true;
}

}  // namespace rayster::rhi
