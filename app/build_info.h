#pragma once
// What the binary was built from, stamped by every build (cmake/build_info.cmake), so `--version`,
// `render --json` and bench JSON name the tree that was compiled, not the one last configured.

namespace rayster::app {

// `git rev-parse --short HEAD` of the source tree at build time, with "-dirty" when tracked files
// had uncommitted changes; "unknown" when the tree is not a git work tree or git is missing.
const char* buildCommit();
// The project version (CMakeLists.txt's project()).
const char* buildVersion();

}  // namespace rayster::app
