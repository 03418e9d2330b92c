#!/usr/bin/env bash
# Re-renders every golden image and overwrites tests/golden/*.png. Review the new images (git diff
# shows which changed) before committing them.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja >/dev/null
ninja -C build rayster rayster_tests
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
RAYSTER_BLESS=1 ./build/tests/rayster_tests --gtest_filter='Render*:Scenes*:EffectGoldens*:WhittedRun*:RasterMode.Golden*'
git status --short tests/golden
