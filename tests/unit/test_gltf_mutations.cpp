// The mutation cross-check against the Khronos glTF-Validator: small valid files, each broken one
// way per schema check the loader makes (and bent into valid edge cases the spec allows), written
// as .gltf and validated in one node call. Rayster must refuse exactly the files the validator
// reports errors in, with a message naming the JSON path, and load the rest, except for the
// differences gltf_validator_exceptions.h lists, each with its reason.
#include <cmath>
#include <functional>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "core/log.h"
#include "gltf_mutations.h"
#include "gltf_test_util.h"
#include "gltf_validator_exceptions.h"
#include "gltf_validator_util.h"

using namespace rayster;
using namespace rayster::test;
using namespace rayster::test::mutation;

namespace {

std::vector<Mutation> mutations() {
  std::vector<Mutation> list = dataMutations();
  for (Mutation& m : sceneMutations()) list.push_back(std::move(m));
  return list;
}

}  // namespace

TEST(GltfMutations, RaysterRefusesExactlyWhatTheValidatorReports) {
  if (const std::string missing = validatorMissing(); !missing.empty()) GTEST_SKIP() << missing;
  TempDir dir;
  const std::vector<Mutation> list = mutations();
  std::vector<std::string> files;
  for (size_t i = 0; i < list.size(); ++i) {
    Doc d = boundedQuad();
    list[i].edit(d);
    std::string json = d.gltf();
    Json j = Json::parse(json);
    if (list[i].written) list[i].written(j);
    if (list[i].glb) {
      j["buffers"][0].erase("uri");
      std::vector<uint8_t> bin = d.bin;
      if (list[i].bin) list[i].bin(bin);
      files.push_back(dir.write(fmt::format("m{:03}.glb", i), glbBytes(j, bin)).string());
      continue;
    }
    files.push_back(dir.write(fmt::format("m{:03}.gltf", i), j.dump()).string());
  }
  const std::map<std::string, Json> reports = runValidator(files);
  ASSERT_EQ(reports.size(), files.size()) << "the validator reported on every file";

  const log::Level previous = log::level();
  log::setLevel(log::Level::Error);
  std::set<std::string> seenExceptions, seenLoadedCodes;
  for (size_t i = 0; i < list.size(); ++i) {
    const Mutation& m = list[i];
    const Json& r = reports.at(files[i]);
    ASSERT_GE(r["errors"].get<int>(), 0) << m.name << ": " << r["first"];
    const bool invalid = validatorRefuses(r);
    if (!invalid)
      for (const Json& code : r["codes"]) seenLoadedCodes.insert(code.get<std::string>());
    const Result<scene::Scene> loaded = scene::loadGltf(files[i]);
    const bool refused = !loaded.ok();
    const std::string rayster = refused ? "refuses it: " + loaded.error().message : "loads it";
    const std::string validator = r["errors"].get<int>() > 0
                                      ? "reports " + r["codes"].dump() + " " + r["first"].get<std::string>()
                                      : "finds no error";
    if (kRefusedValidFiles.count("mutation:" + m.name)) {
      if (!invalid && refused) seenExceptions.insert("mutation:" + m.name);
      continue;
    }
    // The list says what each mutation is; the validator must agree, or the mutation tests nothing.
    EXPECT_EQ(invalid, m.refusal != nullptr) << m.name << " (" << files[i] << "): validator " << validator;
    if (invalid != refused) {
      ADD_FAILURE() << m.name << " (" << files[i] << "): validator " << validator << ", Rayster " << rayster;
      continue;
    }
    if (refused && m.refusal) {
      EXPECT_EQ(loaded.error().code, ExitCode::BadInput) << m.name;
      EXPECT_NE(loaded.error().message.find(m.refusal), std::string::npos)
          << m.name << ": the message should name " << m.refusal << ": " << loaded.error().message;
      EXPECT_EQ(loaded.error().message.find('\n'), std::string::npos) << m.name << ": " << loaded.error().message;
    }
  }
  log::setLevel(previous);
  for (const auto& [name, why] : kRefusedValidFiles)
    if (name.rfind("mutation:", 0) == 0)
      EXPECT_TRUE(seenExceptions.count(name))
          << name << " is listed as an exception but no longer differs (" << why << ")";
  // Every validator error Rayster loads through is exercised by a mutation here.
  for (const auto& [code, why] : kLoadedValidatorErrors)
    EXPECT_TRUE(seenLoadedCodes.count(code)) << "no mutation makes the validator report " << code;
}
