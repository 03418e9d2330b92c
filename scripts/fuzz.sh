#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) and runs each for SECONDS (default 60;
# the scene-file and image targets, smaller and faster to saturate, for half of it) on its committed
# corpus in fuzz/corpus/NAME/. New interesting inputs go to a scratch folder; copy the ones worth
# keeping into the corpus. Usage: scripts/fuzz.sh [SECONDS] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DRAYSTER_BUILD_FUZZERS=ON -DRAYSTER_BUILD_TESTS=OFF >/dev/null
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for f in fuzz/fuzz_*.cpp; do targets+=("$(basename "$f" .cpp)"); done
fi
ninja -C build-fuzz "${targets[@]}"
for t in "${targets[@]}"; do
  corpus=fuzz/corpus/${t#fuzz_}
  scratch=build-fuzz/corpus-${t#fuzz_}
  mkdir -p "$corpus" "$scratch"
  run_seconds=$seconds
  extra=()
  asan=${ASAN_OPTIONS:-}
  case "$t" in
    fuzz_scene_file) run_seconds=$(( (seconds + 1) / 2 )) ;;
    # Debian's tinyexr 1.0.1 leaks a few hundred bytes in LoadEXR when a file's pixel data is corrupt
    # (and frees the image it hands back, so no caller can release it): leaks are not reported here.
    fuzz_image) run_seconds=$(( (seconds + 1) / 2 )); extra=(-detect_leaks=0); asan=detect_leaks=0 ;;
  esac
  echo "fuzz: $t for ${run_seconds}s on $corpus"
  # -rss_limit_mb bounds memory; a crash, leak, timeout or sanitizer report fails the run.
  ASAN_OPTIONS=$asan build-fuzz/fuzz/"$t" -max_total_time="$run_seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
    "${extra[@]}" "$scratch" "$corpus" 2>&1 | tail -n 12
done
