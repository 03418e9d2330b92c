#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine (packages, lavapipe with ray tracing), builds Rayster with its
# tests, and runs them all on lavapipe with Vulkan validation on (any validation error fails).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo
cmake --build build
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
# Fuzz smoke run of the glTF and OBJ loaders (20 s each), the scene-file reader and the image
# decoders (10 s each; clang, ASan + UBSan) on their committed corpora: a smoke test that the fuzzers
# build and run clean, not a fuzzing campaign (scripts/fuzz.sh SECONDS for that);
# RAYSTER_FUZZ_SECONDS=N changes it, 0 skips it.
fuzz_seconds=${RAYSTER_FUZZ_SECONDS:-20}
if [ "$fuzz_seconds" -gt 0 ]; then ./scripts/fuzz.sh "$fuzz_seconds"; fi
cd build && ctest --output-on-failure -j2
