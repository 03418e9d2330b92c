#!/usr/bin/env bash
# cmake/build_info.cmake on a throwaway project and git repository, configured once: every build
# stamps HEAD as it is then (a commit made after configuring shows on the next build), "-dirty"
# follows uncommitted changes to tracked files (untracked ones do not count), a tree without git
# says "unknown", and a build with nothing changed compiles and links nothing.
# Run by ctest (build_info_stamp): test_build_info.sh REPO_ROOT [CMAKE] [GENERATOR]
set -euo pipefail
repo=$1
cmake=${2:-cmake}
generator=${3:-Ninja}

failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT
src=$root/src
build=$root/build
mkdir -p "$src"

cat >"$src/CMakeLists.txt" <<CMAKE
cmake_minimum_required(VERSION 3.25)
project(stamp_test LANGUAGES CXX)
include($repo/cmake/build_info.cmake)
rayster_build_info(info \${CMAKE_SOURCE_DIR} 1.2.3)
add_executable(show main.cpp)
target_link_libraries(show PRIVATE info)
CMAKE
cat >"$src/main.cpp" <<'CPP'
#include <cstdio>
namespace rayster::app {
const char* buildCommit();
const char* buildVersion();
}  // namespace rayster::app
int main() { std::printf("%s %s\n", rayster::app::buildVersion(), rayster::app::buildCommit()); }
CPP
echo "first" >"$src/notes.txt"

g() { git -C "$src" -c user.name=test -c user.email=test@example.invalid -c commit.gpgsign=false "$@"; }
g init -q
g add -A
g commit -qm first

"$cmake" -S "$src" -B "$build" -G "$generator" >"$root/configure.log" 2>&1 || { cat "$root/configure.log"; exit 1; }
build() { "$cmake" --build "$build" >"$root/build.log" 2>&1 || { cat "$root/build.log" >&2; exit 1; }; }
expect() { # what the binary should report, what for
  local got
  got=$("$build/show")
  [ "$got" = "1.2.3 $1" ] || fail "$2: the binary reports '$got', expected '1.2.3 $1'"
}

build
first=$(g rev-parse --short HEAD)
expect "$first" "first build"

# Nothing changed: the stamp step runs, but rewrites nothing, so nothing is compiled or linked.
sleep 1  # file systems with coarse time stamps
touch "$root/marker"
build
[ "$build/show" -nt "$root/marker" ] && fail "a build with nothing changed relinked the binary"
expect "$first" "second build"

echo "edited" >>"$src/notes.txt"
build
expect "$first-dirty" "uncommitted change to a tracked file"

g commit -qam second
second=$(g rev-parse --short HEAD)
[ "$second" != "$first" ] || fail "the test's two commits have the same hash"
build
expect "$second" "a commit made after configuring"

echo "scratch" >"$src/untracked.txt"
build
expect "$second" "an untracked file"

rm -rf "$src/.git"
build
expect "unknown" "no git work tree"

if [ "$failures" -gt 0 ]; then
  echo "$failures check(s) failed" >&2
  exit 1
fi
echo "build info stamp: all checks passed"
