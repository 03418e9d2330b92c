// tests/support/test_dirs.h: per-process test folders, removed when their test passes.
#include "tests/support/test_dirs.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <random>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

namespace rayster::test {
namespace fs = std::filesystem;

namespace {

// The folders made so far, by the test that made them ("" outside any test).
struct Registry {
  std::mutex mutex;
  std::map<std::string, std::vector<fs::path>> byTest;
  bool anyFailed = false;
  fs::path root;  // empty until processDir() made it
};
Registry& registry() {
  static Registry r;
  return r;
}

std::string currentTestName() {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return info ? std::string(info->test_suite_name()) + "." + info->name() : std::string();
}

fs::path makeFresh(const fs::path& dir) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  std::vector<fs::path>& mine = r.byTest[currentTestName()];
  if (std::find(mine.begin(), mine.end(), dir) == mine.end()) mine.push_back(dir);
  return dir;
}

void removeQuietly(const fs::path& dir) {
  std::error_code ec;
  fs::remove_all(dir, ec);
}

// Removes a passed test's folders, keeps a failed one's; at the end removes the root unless
// something failed.
class Cleanup : public ::testing::EmptyTestEventListener {
  // The pipeline cache of every Vulkan context of this run, in the test process and in the rayster
  // processes it starts, goes to the root too, not to the user's ~/.cache/rayster (unless the
  // caller chose a cache folder). Not before the tests run: listing them creates nothing.
  void OnTestProgramStart(const ::testing::UnitTest&) override {
    if (!std::getenv("RAYSTER_CACHE_DIR")) setenv("RAYSTER_CACHE_DIR", (processDir() / "pipeline-cache").c_str(), 1);
  }
  void OnTestEnd(const ::testing::TestInfo& info) override {
    Registry& r = registry();
    std::lock_guard lock(r.mutex);
    auto it = r.byTest.find(std::string(info.test_suite_name()) + "." + info.name());
    if (it == r.byTest.end()) return;
    const bool failed = info.result()->Failed();
    r.anyFailed = r.anyFailed || failed;
    for (const fs::path& dir : it->second) {
      if (failed)
        std::printf("[ kept     ] %s (its test failed)\n", dir.c_str());
      else
        removeQuietly(dir);
    }
    r.byTest.erase(it);
  }
  void OnTestProgramEnd(const ::testing::UnitTest& unit) override {
    Registry& r = registry();
    std::lock_guard lock(r.mutex);
    if (r.root.empty()) return;  // no test wrote anything
    if (!r.anyFailed && !unit.Failed()) {
      removeQuietly(r.root);
      return;
    }
    std::printf("[ kept     ] the test files of this run: %s\n", r.root.c_str());
    std::fflush(stdout);
  }
};

[[maybe_unused]] const bool kCleanupRegistered = [] {
  ::testing::UnitTest::GetInstance()->listeners().Append(new Cleanup);
  return true;
}();

}  // namespace

const fs::path& processDir() {
  static const fs::path root = [] {
    std::random_device random;
    for (int attempt = 0;; ++attempt) {
      const fs::path dir =
          fs::temp_directory_path() / fmt::format("rayster-tests-{}-{:08x}", ::getpid(), uint32_t(random()));
      std::error_code ec;
      if (fs::create_directory(dir, ec)) {  // false when it exists: a folder is never shared
        Registry& r = registry();
        std::lock_guard lock(r.mutex);
        r.root = dir;
        return dir;
      }
      if (attempt == 100) throw fs::filesystem_error("cannot create a test folder", dir, ec);
    }
  }();
  return root;
}

fs::path testDir() {
  const std::string name = currentTestName();
  return makeFresh(processDir() / (name.empty() ? std::string("shared") : name));
}

fs::path uniqueTestDir(const std::string& tag) {
  static std::atomic<int> counter{0};
  const std::string name = currentTestName();
  return makeFresh(processDir() / fmt::format("{}-{}-{}", name.empty() ? "shared" : name, tag, counter++));
}

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace rayster::test
