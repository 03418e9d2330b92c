// tests/costs.txt, the COST ctest gives the long tests on a clean clone (tests/costs.cmake): every
// line reads as "SECONDS NAME", and every name is a test ctest runs — a test of this binary, a
// shared-run suite (ctest runs a suite as one test) or a test tests/CMakeLists.txt adds — so a
// renamed test cannot silently lose its place at the front of the schedule.
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/test_dirs.h"

namespace {

using rayster::test::readText;

// "Suite.Test" of every test of this binary, and every suite name. A parameterised test is
// "Prefix/Suite.Test/N"; ctest names it with the parameter's printed value instead of N, so it is
// known here by what precedes its last '/'.
struct Registered {
  std::set<std::string> tests, parameterised, suites;
};
Registered registeredTests() {
  Registered r;
  const ::testing::UnitTest& unit = *::testing::UnitTest::GetInstance();
  for (int i = 0; i < unit.total_test_suite_count(); ++i) {
    const ::testing::TestSuite& suite = *unit.GetTestSuite(i);
    r.suites.insert(suite.name());
    for (int j = 0; j < suite.total_test_count(); ++j) {
      const std::string name = std::string(suite.name()) + "." + suite.GetTestInfo(j)->name();
      if (suite.GetTestInfo(j)->value_param()) {
        r.parameterised.insert(name.substr(0, name.rfind('/')));
      } else {
        r.tests.insert(name);
      }
    }
  }
  return r;
}

TEST(TestCosts, EveryListedTestExists) {
  const std::filesystem::path root = RAYSTER_SOURCE_DIR;
  const Registered known = registeredTests();
  std::set<std::string> added;  // add_test(NAME x ...) in tests/CMakeLists.txt
  const std::string cmake = readText(root / "tests/CMakeLists.txt");
  static const std::regex addTest(R"(add_test\(NAME ([A-Za-z0-9_.]+))");
  for (auto it = std::sregex_iterator(cmake.begin(), cmake.end(), addTest); it != std::sregex_iterator(); ++it)
    added.insert((*it)[1]);
  static const std::regex sharedSuites(R"(set\(shared_run_suites ([A-Za-z0-9_ ]+)\))");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(cmake, m, sharedSuites)) << "tests/CMakeLists.txt names no shared-run suites";
  std::istringstream suites(m[1].str());
  for (std::string suite; suites >> suite;) {
    EXPECT_TRUE(known.suites.count(suite)) << "shared-run suite " << suite << " has no tests";
    added.insert(suite);
  }

  std::ifstream costs(root / "tests/costs.txt");
  ASSERT_TRUE(costs.good());
  static const std::regex entry(R"(([0-9]+(\.[0-9]+)?) (.+))");
  int listed = 0;
  for (std::string line; std::getline(costs, line);) {
    if (line.empty() || line[0] == '#') continue;
    ASSERT_TRUE(std::regex_match(line, m, entry)) << "not 'SECONDS NAME': " << line;
    const std::string name = m[3];
    const std::string stem = name.substr(0, name.rfind('/'));
    const bool inSharedSuite = added.count(name.substr(0, name.find('.'))) > 0;  // ctest runs the suite instead
    const bool runs = added.count(name) ||
                      (!inSharedSuite && (known.tests.count(name) ||
                                          (name.find('/') != std::string::npos && known.parameterised.count(stem))));
    EXPECT_TRUE(runs) << "tests/costs.txt lists " << name
                      << ", which ctest does not run (renamed? run scripts/test-costs.sh)";
    ++listed;
  }
  EXPECT_GT(listed, 10);
}

}  // namespace
