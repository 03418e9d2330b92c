#pragma once
// Checks that glTF files the tests write are valid glTF: each loads, and the Khronos glTF-Validator
// reports no error in them but the ones the loader deliberately loads through
// (gltf_validator_exceptions.h). Used by test_gltf_fixtures*.cpp.
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/log.h"
#include "gltf_validator_exceptions.h"
#include "gltf_validator_util.h"
#include "scene/gltf_loader.h"

namespace rayster::test {

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
    EXPECT_FALSE(validatorRefuses(reports.at(f)))
        << f << ": " << reports.at(f)["codes"] << " " << reports.at(f)["first"];
}

}  // namespace rayster::test
