// Runtime SPIR-V overrides of the embedded shaders (shader hot reload in development builds).
#include <map>
#include <string>

#include "shaders/embedded.h"

namespace rayster::shaders {
namespace {
std::map<std::string, std::vector<uint32_t>, std::less<>>& overrides() {
  static std::map<std::string, std::vector<uint32_t>, std::less<>> table;
  return table;
}
}  // namespace

void setOverride(std::string_view name, std::vector<uint32_t> words) {
  overrides()[std::string(name)] = std::move(words);
}

std::span<const uint32_t> overrideOf(std::string_view name) {
  const auto it = overrides().find(name);
  return it == overrides().end() ? std::span<const uint32_t>{} : std::span<const uint32_t>(it->second);
}
}  // namespace rayster::shaders
