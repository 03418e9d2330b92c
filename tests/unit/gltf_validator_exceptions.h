#pragma once
// The one list of known, justified differences between Rayster's glTF loader and the Khronos
// glTF-Validator, used by every cross-check (test_gltf_validator.cpp over the corpora,
// test_gltf_mutations.cpp over one broken file per check, test_gltf_fixtures*.cpp over the files
// the tests write). Each entry says why; a test fails when an entry no longer makes a difference.
#include <map>
#include <string>

#include <nlohmann/json.hpp>

namespace rayster::test {

// Validator errors Rayster loads through: information the loader does not need, whose absence
// changes nothing it draws.
inline const std::map<std::string, std::string> kLoadedValidatorErrors = {
    {"UNDECLARED_EXTENSION",
     "an extension's objects say what they mean without extensionsUsed listing them; refusing them helps no one, and "
     "the list is often forgotten by hand-written files"},
    {"MESH_PRIMITIVE_POSITION_ACCESSOR_WITHOUT_BOUNDS",
     "Rayster computes bounds itself; absent bounds cannot contradict the data (bounds that are given must be exact)"},
    {"ANIMATION_SAMPLER_INPUT_ACCESSOR_WITHOUT_BOUNDS",
     "as for POSITION: absent bounds cannot contradict the key times, which are checked themselves"},
};

// Files the validator finds no error in (or only warnings) that Rayster refuses, by corpus name
// ("assimp:…", "repo:…") or mutation name ("mutation:…").
inline const std::map<std::string, std::string> kRefusedValidFiles = {
    {"assimp:BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf",
     "requires KHR_technique_webgl (glTF 1.0 shaders), which no 2.0 renderer supports; the validator only warns"},
    {"mutation:requires an unknown extension",
     "the validator cannot check an extension it does not know; Rayster cannot draw what it does not implement"},
    {"mutation:sparse indices of float type",
     "the validator only warns (VALUE_NOT_IN_LIST: the schema allows any integer); floats cannot index elements, so "
     "the accessor's values are undefined"},
    {"mutation:an unknown camera type",
     "the validator only warns (VALUE_NOT_IN_LIST); tinygltf 2.7 refuses the file while parsing it"},
};

// Whether the validator's report has an error Rayster must refuse the file for.
inline bool validatorRefuses(const nlohmann::json& report) {
  if (report.value("errors", 0) <= 0) return false;
  for (const nlohmann::json& code : report.value("codes", nlohmann::json::array()))
    if (!kLoadedValidatorErrors.count(code.get<std::string>())) return true;
  return false;
}

}  // namespace rayster::test
