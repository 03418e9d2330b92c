#!/usr/bin/env bash
# The foundation measurements on a GPU machine (docs/gpu.md): device info, the Cornell box at
# 1920x1080 with each G-buffer producer, timed per pass, and the images compared with the lavapipe
# renders of the same seed. Expects dist/rayster-gpu (scripts/bundle-gpu.sh) and dist/ref/ (lavapipe
# references, see docs/gpu.md). Writes JSON and images to $OUT (default bench/out).
set -uo pipefail
cd "$(dirname "$0")/.."
R=dist/rayster-gpu/run.sh
OUT=${OUT:-bench/out}
mkdir -p "$OUT"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null || true
$R info || exit $?
common="builtin:cornell --size 1920x1080 --seed 1"
for p in raster rt; do
  # Same seed and frame count as the lavapipe reference: the images must agree.
  $R render $common --frames 16 --primary $p -o "$OUT/h100-$p.png" || exit $?
  if [ -f "dist/ref/lavapipe-$p.png" ]; then
    echo "== $p vs lavapipe (same seed, 16 frames)"
    $R compare "dist/ref/lavapipe-$p.png" "$OUT/h100-$p.png" --tolerance 2 --min-fraction 0.99
  fi
  # Timing: one configuration per process, 256 frames, median per pass.
  echo "== timings, primary $p"
  $R render $common --frames 256 --primary $p --timings --json "$OUT/h100-$p.json" -o "$OUT/timing-$p.png" || exit $?
done
echo "== primary auto"
$R render $common --frames 256 --primary auto --timings --json "$OUT/h100-auto.json" -o "$OUT/timing-auto.png" || exit $?
rm -f "$OUT"/timing-*.png
