// What the binary says it was built from: `rayster --version`, `rayster info` and `render --json`
// name the build's stamp (app/build_info.h; bench JSON: test_bench.cpp), which this test binary
// links from the same build. That the stamp follows the tree at build time rather than at
// configure time is checked on a throwaway repository by tests/scripts/test_build_info.sh
// (ctest: build_info_stamp). Comparing with `git rev-parse HEAD` here would test the checkout,
// not the code: it fails whenever someone commits between building and testing.
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/build_info.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

TEST(BuildInfo, StampIsACommitOfThisTree) {
  const std::string commit = app::buildCommit();
  if (std::filesystem::exists(std::filesystem::path(RAYSTER_SOURCE_DIR) / ".git"))
    EXPECT_TRUE(std::regex_match(commit, std::regex("[0-9a-f]{7,40}(-dirty)?"))) << commit;
  else
    EXPECT_EQ(commit, "unknown");
}

TEST(BuildInfo, VersionNamesTheStampedCommit) {
  RunResult r = runRayster("--version");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output, fmt::format("rayster {} (commit {})\n", app::buildVersion(), app::buildCommit()));
}

TEST(BuildInfo, InfoAndRenderJsonNameTheStampedCommit) {
  RunResult info = runRayster("info");
  ASSERT_EQ(info.exitCode, 0) << info.output;
  EXPECT_NE(info.output.find(fmt::format("(commit {})", app::buildCommit())), std::string::npos) << info.output;

  const auto dir = testDir();
  RunResult r = runRayster("render builtin:cornell --size 32x24 --frames 1 --json " + (dir / "t.json").string() +
                           " -o " + (dir / "out.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream f(dir / "t.json");
  std::stringstream text;
  text << f.rdbuf();
  const nlohmann::json j = nlohmann::json::parse(text.str());
  EXPECT_EQ(j.value("commit", ""), app::buildCommit());
}

}  // namespace
}  // namespace rayster::test
