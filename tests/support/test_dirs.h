#pragma once
// Where tests write files. Every test process has its own root folder under the system temp
// folder, rayster-tests-<pid>-<random>, so two test runs on one machine (two `ctest` runs, or the
// test binary started twice) never share or delete each other's files. A test's folders are
// removed when it passes; a failed test's folders stay (their images are what one debugs with)
// and their paths are printed; the root goes at exit when every test passed. Vulkan pipeline caches
// (RAYSTER_CACHE_DIR, unless already set) go to the root as well. Mesa's and the validation
// layer's own caches stay in ~/.cache: they are built for concurrent processes, and a cold Mesa
// shader cache makes a lavapipe run minutes slower.
#include <filesystem>
#include <string>

namespace rayster::test {

// This process's root folder, created on first use.
const std::filesystem::path& processDir();

// A fresh, empty folder for the running test: processDir()/<Suite.Name>. Calling it again in the
// same test empties it again. Outside a test (a suite-wide fixture), processDir()/shared, kept
// when any test of the process failed.
std::filesystem::path testDir();

// Another fresh folder for the running test, processDir()/<Suite.Name>-<tag>-<n>, for tests that
// need several; cleaned up (or kept) like testDir().
std::filesystem::path uniqueTestDir(const std::string& tag);

// The whole file as text ("" when it cannot be read): logs, scripts, JSON a test checks.
std::string readText(const std::filesystem::path& path);

}  // namespace rayster::test
