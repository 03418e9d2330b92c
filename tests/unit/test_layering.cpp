// docs/architecture.md §1: dependencies point down only. Libraries link only the layers below them, but a
// header-only include would slip past the linker, so this test reads every #include.
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>

#include <gtest/gtest.h>

namespace {

// Each layer and the layers it may include (its own included).
const std::map<std::string, std::set<std::string>> kAllowed = {
    {"core", {"core"}},
    {"rhi", {"rhi", "core", "shaders"}},  // shaders/embedded.h: SPIR-V by name
    {"graph", {"graph", "rhi", "core"}},
    {"scene", {"scene", "core"}},
    {"render", {"render", "graph", "rhi", "scene", "core", "shaders"}},
    {"app", {"app", "render", "graph", "rhi", "scene", "core", "shaders"}},
};

TEST(Layering, IncludesPointDownOnly) {
  const std::filesystem::path root = RAYSTER_SOURCE_DIR;
  const std::regex include(R"re(^\s*#\s*include\s*"([a-z_]+)/)re");
  int checked = 0;
  for (const auto& [layer, allowed] : kAllowed) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root / layer)) {
      if (!entry.is_regular_file()) continue;
      std::ifstream file(entry.path());
      std::string line;
      int lineNo = 0;
      while (std::getline(file, line)) {
        ++lineNo;
        std::smatch m;
        if (!std::regex_search(line, m, include)) continue;
        ++checked;
        EXPECT_TRUE(allowed.count(m[1].str()))
            << entry.path().lexically_relative(root).string() << ":" << lineNo << ": layer '" << layer << "' includes '"
            << m[1].str() << "/', which is not below it";
      }
    }
  }
  EXPECT_GT(checked, 50) << "the scan found too few includes to be meaningful";
}

}  // namespace
