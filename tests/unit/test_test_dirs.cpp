// tests/support/test_dirs.h, through this very binary started as two more processes at once: each
// process writes under its own root folder, a passing test's folder is gone when its process ends,
// and a failing test's folder stays and is named in the output. What makes two `ctest` runs on one
// machine safe from each other.
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/test_dirs.h"

namespace rayster::test {
namespace {
namespace fs = std::filesystem;

constexpr const char* kFailOnPurpose = "RAYSTER_TEST_DIRS_FAIL";

// The helper the other tests start: prints its folder; fails on purpose when asked to.
TEST(TestDirs, HelperPrintsItsFolder) {
  const fs::path dir = testDir();
  std::ofstream(dir / "marker") << "written by TestDirs.HelperPrintsItsFolder\n";
  std::printf("test-dir: %s\n", dir.c_str());
  if (std::getenv(kFailOnPurpose)) ADD_FAILURE() << "failing on purpose (" << kFailOnPurpose << " is set)";
}

struct Helper {
  FILE* pipe = nullptr;
  std::string output;
  int status = -1;
  fs::path dir;  // what it printed
};

Helper startHelper(const std::string& env) {
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  Helper h;
  h.pipe = popen((env + " '" + self + "' --gtest_filter=TestDirs.HelperPrintsItsFolder 2>&1").c_str(), "r");
  return h;
}

void finish(Helper& h) {
  ASSERT_NE(h.pipe, nullptr);
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, h.pipe)) h.output.append(buf, n);
  h.status = pclose(h.pipe);
  const size_t at = h.output.find("test-dir: ");
  ASSERT_NE(at, std::string::npos) << h.output;
  const size_t end = h.output.find('\n', at);
  h.dir = h.output.substr(at + 10, end - at - 10);
}

TEST(TestDirs, ConcurrentProcessesHaveTheirOwnFoldersAndLeaveNothing) {
  Helper a = startHelper(""), b = startHelper("");  // both running at once
  finish(a);
  finish(b);
  ASSERT_TRUE(WIFEXITED(a.status) && WEXITSTATUS(a.status) == 0) << a.output;
  ASSERT_TRUE(WIFEXITED(b.status) && WEXITSTATUS(b.status) == 0) << b.output;
  EXPECT_EQ(a.dir.filename(), b.dir.filename());  // the same test...
  EXPECT_NE(a.dir.parent_path(), b.dir.parent_path()) << "two processes shared " << a.dir.parent_path();
  for (const Helper* h : {&a, &b}) {
    EXPECT_NE(h->dir.parent_path(), processDir());
    EXPECT_EQ(h->dir.parent_path().parent_path(), processDir().parent_path());  // the temp folder
    EXPECT_FALSE(fs::exists(h->dir.parent_path())) << "left behind by a passing run: " << h->dir.parent_path();
  }
}

TEST(TestDirs, FailedTestKeepsItsFolder) {
  Helper h = startHelper(std::string("env ") + kFailOnPurpose + "=1");
  finish(h);
  EXPECT_TRUE(WIFEXITED(h.status) && WEXITSTATUS(h.status) != 0) << h.output;
  EXPECT_TRUE(fs::exists(h.dir / "marker")) << h.output;
  EXPECT_NE(h.output.find("[ kept     ] " + h.dir.string()), std::string::npos) << h.output;
  std::error_code ec;
  fs::remove_all(h.dir.parent_path(), ec);  // the helper's root: kept for debugging, not needed here
}

}  // namespace
}  // namespace rayster::test
