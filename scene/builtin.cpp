#include "scene/builtin.h"

#include <charconv>
#include <optional>

#include <fmt/format.h>

namespace rayster::scene {
namespace {

constexpr std::string_view kPrefix = "builtin:";

// `argument` is what followed "NAME:"; nullopt when there was no colon.
using Maker = Result<Scene> (*)(std::optional<std::string_view> argument);

struct BuiltinEntry {
  std::string_view name;
  std::string_view usage;  // how errors and help show it
  bool takesArgument;
  Maker make;
};

Result<Scene> makeInstancesFromArgument(std::optional<std::string_view> argument) {
  if (!argument) return makeInstancesScene(kDefaultBuiltinInstances);
  uint32_t count = 0;
  const char* end = argument->data() + argument->size();
  const auto [ptr, ec] = std::from_chars(argument->data(), end, count);
  // from_chars takes no sign or spaces, and ec reports overflow, so "", "abc", "-1", "1e3" and
  // "99999999999" all fail here rather than wrapping.
  if (ec != std::errc() || ptr != end || count == 0 || count > kMaxBuiltinInstances)
    return makeError(ExitCode::BadInput, "builtin:instances: count '{}' is not a number in 1..{}", *argument,
                     kMaxBuiltinInstances);
  return makeInstancesScene(count);
}

Result<Scene> makeLightsFromArgument(std::optional<std::string_view> argument) {
  if (!argument) return makeLightsScene(kDefaultBuiltinLights);
  uint32_t count = 0;
  const char* end = argument->data() + argument->size();
  const auto [ptr, ec] = std::from_chars(argument->data(), end, count);
  if (ec != std::errc() || ptr != end || count == 0 || count > kMaxBuiltinLights)
    return makeError(ExitCode::BadInput, "builtin:lights: count '{}' is not a number in 1..{}", *argument,
                     kMaxBuiltinLights);
  return makeLightsScene(count);
}

// The one list of built-in scenes: adding one here makes it loadable and listed in errors/--help.
constexpr BuiltinEntry kBuiltins[] = {
    {"cornell", "cornell", false, [](std::optional<std::string_view>) -> Result<Scene> { return makeCornellBox(); }},
    {"whitted", "whitted", false, [](std::optional<std::string_view>) { return makeWhittedScene(); }},
    {"spheres", "spheres", false, [](std::optional<std::string_view>) -> Result<Scene> { return makeSpheresScene(); }},
    {"instances", "instances[:N]", true, &makeInstancesFromArgument},
    {"lights", "lights[:N]", true, &makeLightsFromArgument},
};

std::string usageList() {
  std::vector<std::string_view> usages;
  for (const BuiltinEntry& entry : kBuiltins) usages.push_back(entry.usage);
  return fmt::format("{}", fmt::join(usages, ", "));
}

}  // namespace

std::vector<std::string> builtinSceneNames() {
  std::vector<std::string> names;
  for (const BuiltinEntry& entry : kBuiltins) names.emplace_back(entry.name);
  return names;
}

Result<Scene> makeBuiltinScene(std::string_view name) {
  std::string_view bare = name;
  if (bare.substr(0, kPrefix.size()) == kPrefix) bare.remove_prefix(kPrefix.size());
  const size_t colon = bare.find(':');
  const std::string_view base = bare.substr(0, colon);
  const bool hasArgument = colon != std::string_view::npos;
  for (const BuiltinEntry& entry : kBuiltins) {
    if (entry.name != base) continue;
    if (hasArgument && !entry.takesArgument)
      return makeError(ExitCode::BadInput, "built-in scene '{}' takes no parameter (got '{}')", entry.name, name);
    Result<Scene> scene =
        entry.make(hasArgument ? std::optional<std::string_view>(bare.substr(colon + 1)) : std::nullopt);
    // The built-in meshes carry no authored sidedness (npm's teapot is open and its winding is not
    // consistent): they render double-sided, as OBJ files do.
    if (scene.ok())
      for (Material& m : scene->materials) m.doubleSided = true;
    return scene;
  }
  return makeError(ExitCode::BadInput, "unknown built-in scene '{}' (available: {})", name, usageList());
}

}  // namespace rayster::scene
