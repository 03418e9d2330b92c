#pragma once
// A SPIR-V reader for what a pipeline layout needs (docs/architecture.md §4): the descriptors a shader
// declares (set, binding, type, array size, GLSL name, readonly/writeonly) and the size of its
// push-constant block. Binding numbers are written once, in GLSL; the C++ side binds by name.
// Rayster's own reader of the SPIR-V binary (the SPIR-V specification, §2.3 physical layout and
// §3 binary form): only the instructions that describe the shader's interface are decoded.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <vulkan/vulkan_core.h>

namespace rayster::rhi {

struct ShaderBinding {
  uint32_t set = 0, binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
  uint32_t count = 1;        // array size; 0 for a runtime-sized array (bindless)
  std::string name;          // the GLSL variable (a block's instance name, else its type name)
  bool nonWritable = false;  // `readonly`
  bool nonReadable = false;  // `writeonly`
  VkShaderStageFlags stages = 0;
};

struct ShaderInterface {
  std::vector<ShaderBinding> bindings;  // sorted by (set, binding)
  uint32_t pushConstantBytes = 0;       // 0: no push-constant block
  VkShaderStageFlags stages = 0;

  const ShaderBinding* find(std::string_view name, uint32_t set = 0) const;
  const ShaderBinding* at(uint32_t set, uint32_t binding) const;
  bool usesSet(uint32_t set) const;
};

// Reads one module. Returns std::nullopt and sets `error` when the words are not SPIR-V or the
// interface is one Rayster cannot express (a descriptor kind it does not know).
std::optional<ShaderInterface> reflectSpirv(std::span<const uint32_t> words, VkShaderStageFlagBits stage,
                                            std::string* error = nullptr);

// Merges the interface of another stage of the same pipeline into `into`. Two stages that declare
// one (set, binding) with different types or sizes are an error (returns false, sets `error`).
bool mergeInterface(ShaderInterface& into, const ShaderInterface& stage, std::string* error = nullptr);

}  // namespace rayster::rhi
