#pragma once
// Runs the Khronos glTF-Validator (npm: gltf-validator, installed by scripts/setup.sh into
// tools/npm) over many files in one node call: tools/gltf-validate.js prints one JSON line per file.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rayster::test {

inline std::filesystem::path validatorModule() {
  return std::filesystem::path(RAYSTER_SOURCE_DIR) / "tools" / "npm" / "node_modules" / "gltf-validator";
}

// Why the validator cannot run here, or an empty string when it can.
inline std::string validatorMissing() {
  if (std::system("command -v node >/dev/null 2>&1") != 0 || !std::filesystem::exists(validatorModule()))
    return "node or tools/npm/node_modules/gltf-validator is missing (scripts/setup.sh installs both)";
  return {};
}

// file -> {"file", "errors", "first"}; files the validator did not report on are absent.
inline std::map<std::string, nlohmann::json> runValidator(const std::vector<std::string>& files) {
  auto quoted = [](const std::string& s) { return "'" + s + "'"; };
  std::string cmd = "GLTF_VALIDATOR_MODULE=" + quoted(validatorModule().string()) + " node " +
                    quoted((std::filesystem::path(RAYSTER_SOURCE_DIR) / "tools" / "gltf-validate.js").string());
  for (const std::string& f : files) cmd += " " + quoted(f);
  std::map<std::string, nlohmann::json> reports;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return reports;
  std::string line;
  char chunk[4096];
  while (std::fgets(chunk, sizeof chunk, pipe)) {
    line += chunk;
    if (line.empty() || line.back() != '\n') continue;
    const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
    if (!j.is_discarded() && j.contains("file")) reports[j["file"].get<std::string>()] = j;
    line.clear();
  }
  pclose(pipe);
  return reports;
}

}  // namespace rayster::test
