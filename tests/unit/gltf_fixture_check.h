#pragma once
// Checks that glTF files the tests write are valid glTF: each loads, and the Khronos glTF-Validator
// reports no error in them but the ones the loader deliberately accepts (kLenientValidatorErrors,
// the same as test_gltf_mutations.cpp's exceptions). Used by test_gltf_fixtures*.cpp.
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/log.h"
#include "gltf_validator_util.h"
#include "scene/gltf_loader.h"

namespace rayster::test {

// Validator errors for information the loader does not need: missing declarations and bounds.
inline const std::set<std::string> kLenientValidatorErrors = {"UNDECLARED_EXTENSION",
                                                              "MESH_PRIMITIVE_POSITION_ACCESSOR_WITHOUT_BOUNDS",
                                                              "ANIMATION_SAMPLER_INPUT_ACCESSOR_WITHOUT_BOUNDS"};

inline void expectValidTestFiles(const std::vector<std::string>& files) {
  const log::Level previous = log::level();
  log::setLevel(log::Level::Error);
  for (const std::string& f : files) {
    Result<scene::Scene> s = scene::loadGltf(f);
    EXPECT_TRUE(s.ok()) << f << ": " << (s.ok() ? "" : s.error().message);
  }
  log::setLevel(previous);
  if (const std::string missing = validatorMissing(); !missing.empty()) GTEST_SKIP() << missing;
  const auto reports = runValidator(files);
  ASSERT_EQ(reports.size(), files.size());
  for (const std::string& f : files)
    for (const auto& code : reports.at(f)["codes"])
      EXPECT_TRUE(kLenientValidatorErrors.count(code.get<std::string>())) << f << ": " << reports.at(f)["first"];
}

}  // namespace rayster::test
