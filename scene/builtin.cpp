#include "scene/builtin.h"

#include <fmt/format.h>

namespace rayster::scene {
namespace {

struct BuiltinEntry {
  std::string_view name;
  Scene (*make)();
};

// The one list of built-in scenes: adding one here makes it loadable and listed in errors/--help.
constexpr BuiltinEntry kBuiltins[] = {
    {"cornell", &makeCornellBox},
};

constexpr std::string_view kPrefix = "builtin:";

} // namespace

std::vector<std::string> builtinSceneNames() {
  std::vector<std::string> names;
  for (const BuiltinEntry& entry : kBuiltins) names.emplace_back(entry.name);
  return names;
}

Result<Scene> makeBuiltinScene(std::string_view name) {
  std::string_view bare = name;
  if (bare.substr(0, kPrefix.size()) == kPrefix) bare.remove_prefix(kPrefix.size());
  for (const BuiltinEntry& entry : kBuiltins)
    if (entry.name == bare) return entry.make();
  return makeError(ExitCode::BadInput, "unknown built-in scene '{}' (available: {})", name,
                   fmt::join(builtinSceneNames(), ", "));
}

} // namespace rayster::scene
