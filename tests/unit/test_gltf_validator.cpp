// Rayster's glTF loader against the Khronos glTF-Validator (npm: gltf-validator, installed by
// scripts/setup.sh into tools/npm): over every glTF and GLB of Debian's assimp-testmodels and of the
// repository's own corpus (assets/, tests/), a file the validator reports errors in must be refused,
// and a file without errors must load — except for the files listed below, each with the reason it
// differs (gltf_validator_exceptions.h). test_gltf_mutations.cpp does the same for one broken file
// per schema check.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include "core/log.h"
#include "gltf_validator_exceptions.h"
#include "gltf_validator_util.h"
#include "scene/gltf_loader.h"

namespace fs = std::filesystem;
using namespace rayster;

namespace {

const fs::path kModels = "/usr/share/assimp/models/glTF2";

// "assimp:<path under kModels>" or "repo:<path under the source folder>".
std::vector<std::pair<std::string, std::string>> corpus() {
  std::vector<std::pair<std::string, std::string>> files;  // (name, path)
  auto add = [&](const fs::path& root, const std::string& prefix) {
    if (!fs::exists(root)) return;
    for (const auto& e : fs::recursive_directory_iterator(root))
      if (e.path().extension() == ".gltf" || e.path().extension() == ".glb")
        files.emplace_back(prefix + fs::relative(e.path(), root).string(), e.path().string());
  };
  add(kModels, "assimp:");
  const fs::path source = RAYSTER_SOURCE_DIR;
  add(source / "assets", "repo:assets/");
  add(source / "tests", "repo:tests/");
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

TEST(GltfValidator, RaysterRefusesWhatTheValidatorReportsAndLoadsTheRest) {
  if (!fs::exists(kModels)) GTEST_SKIP() << "assimp-testmodels is not installed";
  if (const std::string missing = test::validatorMissing(); !missing.empty()) GTEST_SKIP() << missing;
  const auto files = corpus();
  ASSERT_GE(files.size(), 44u);
  std::vector<std::string> paths;
  for (const auto& [name, path] : files) paths.push_back(path);
  std::map<std::string, nlohmann::json> reports = test::runValidator(paths);
  ASSERT_EQ(reports.size(), files.size()) << "the validator reported on every file";

  const log::Level previous = log::level();
  log::setLevel(log::Level::Error);
  std::set<std::string> seenExceptions;
  for (const auto& [rel, f] : files) {
    const nlohmann::json& r = reports[f];
    ASSERT_GE(r["errors"].get<int>(), 0) << rel << ": " << r["first"];
    const bool invalid = test::validatorRefuses(r);
    Result<scene::Scene> loaded = scene::loadGltf(f);
    const bool refused = !loaded.ok();
    if (invalid == refused) {
      EXPECT_EQ(test::kRefusedValidFiles.count(rel), 0u) << rel << " agrees with the validator now: drop its exception";
      continue;
    }
    if (test::kRefusedValidFiles.count(rel) && refused) {
      seenExceptions.insert(rel);
      continue;
    }
    ADD_FAILURE() << rel << ": validator " << (invalid ? "reports " + r["first"].get<std::string>() : "finds no error")
                  << ", Rayster " << (refused ? "refuses it: " + loaded.error().message : "loads it");
  }
  log::setLevel(previous);
  for (const auto& [rel, why] : test::kRefusedValidFiles)
    if (rel.rfind("mutation:", 0) != 0)
      EXPECT_TRUE(seenExceptions.count(rel))
          << rel << " is listed as an exception but no longer differs (" << why << ")";
}
