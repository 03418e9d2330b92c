#!/usr/bin/env bash
# Rewrites tests/costs.txt (the COST ctest gives each long test on a clean clone, tests/costs.cmake)
# from the costs ctest measured in a build folder: every test that took at least MIN_SECONDS
# (default 3), longest first, in whole seconds. Run it after a full `ctest -j2` on lavapipe.
# Usage: scripts/test-costs.sh [BUILD_DIR] [MIN_SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
min=${2:-3}
data=$build/Testing/Temporary/CTestCostData.txt
[ -f "$data" ] || { echo "scripts/test-costs.sh: no $data (run ctest in $build first)" >&2; exit 2; }
{
  cat <<'HEADER'
# The seconds each long test takes on lavapipe under `ctest -j2` (2 cores), as ctest COST: ctest
# starts the costliest first. Only the order matters; written by scripts/test-costs.sh.
# SECONDS NAME
HEADER
  # CTestCostData.txt: "NAME RUNS SECONDS" per test, then "---" and the tests that failed last.
  awk -v min="$min" '/^---/ { exit } NF >= 3 && $NF + 0 >= min + 0 {
      name = $0; sub(/ [0-9]+ [0-9.e+-]+$/, "", name); printf "%d %s\n", $NF + 0.5, name }' "$data" | sort -k1,1nr -k2
} >tests/costs.txt.new
mv tests/costs.txt.new tests/costs.txt
echo "tests/costs.txt: $(grep -vc '^#' tests/costs.txt) tests of at least ${min} s"
