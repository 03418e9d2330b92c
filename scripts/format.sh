#!/usr/bin/env bash
# Formats the project's C++ (*.cpp, *.h, *.hpp, *.cc) with Debian's clang-format 14 and the
# committed .clang-format; `--check` changes nothing, lists the files that would change and exits
# 1 if there are any (for CI). Files given after the options (absolute, or relative to the
# repository root) are formatted or checked instead of the whole tree.
#
# The tree is every tracked or new, not ignored file (git ls-files --cached --others
# --exclude-standard: a file not yet added is checked too), or every file under the checkout without git,
# except build*/, dist/, out/ and third-party folders (third_party/, external/, vendor/: none
# today, nothing is vendored). GLSL is left alone: clang-format has no GLSL mode, and its C++
# rules would reflow `layout(...)` declarations. shaders/shared/*.h are C++ as well and included.
#
# CLANG_FORMAT=path picks another binary; it must still be version 14, since other versions
# format the same input differently and CI would flap.
set -euo pipefail
cd "$(dirname "$0")/.."

usage() { echo "usage: scripts/format.sh [--check] [FILE...]" >&2; }
check=false
while [ $# -gt 0 ]; do
  case "$1" in
    --check) check=true ;;
    -h | --help) usage; exit 0 ;;
    --) shift; break ;;
    -*) usage; exit 2 ;;
    *) break ;;
  esac
  shift
done

clang_format=${CLANG_FORMAT:-clang-format-14}
if ! command -v "$clang_format" >/dev/null 2>&1; then
  echo "scripts/format.sh: $clang_format not found (Debian: apt-get install clang-format-14)" >&2
  exit 2
fi
if ! "$clang_format" --version | grep -Eq 'version 14\.'; then
  echo "scripts/format.sh: $clang_format is not clang-format 14: $("$clang_format" --version)" >&2
  exit 2
fi
style=$(pwd)/.clang-format  # explicit, so FILEs outside the tree get it too
[ -f "$style" ] || { echo "scripts/format.sh: no $style" >&2; exit 2; }

# NUL-separated list of the files to format.
list_files() {
  if [ $# -gt 0 ]; then
    printf '%s\0' "$@"
  elif git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    git ls-files -z --cached --others --exclude-standard -- '*.cpp' '*.h' '*.hpp' '*.cc'
  else
    find . -type f \( -name '*.cpp' -o -name '*.h' -o -name '*.hpp' -o -name '*.cc' \) -printf '%P\0'
  fi | grep -zEv '^(\./)?(build[^/]*|dist|out|third_party|external|vendor)/' || true
}

if ! $check; then
  list_files "$@" | xargs -0 -r "$clang_format" -i --style="file:$style"
  exit 0
fi

changed=0
while IFS= read -r -d '' f; do
  if ! "$clang_format" --style="file:$style" "$f" | cmp -s - "$f"; then
    echo "$f"
    changed=$((changed + 1))
  fi
done < <(list_files "$@")
if [ "$changed" -gt 0 ]; then
  echo "scripts/format.sh: $changed file(s) not formatted (run scripts/format.sh)" >&2
  exit 1
fi
