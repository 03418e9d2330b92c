#!/usr/bin/env bash
# The hybrid frame with every effect on (denoisers, TAA) on a GPU machine (docs/gpu.md): per-pass
# GPU times at 1920x1080 for each built-in scene (one configuration per process), and the
# many-light sweep (8 and 256 lights on the whitted scene). Expects dist/rayster-gpu
# (scripts/bundle-gpu.sh). Output in $OUT.
set -uo pipefail
cd "$(dirname "$0")/.."
R=dist/rayster-gpu/run.sh
OUT=${OUT:-bench/out}
mkdir -p "$OUT"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null || true
for scene in whitted cornell spheres; do
  echo "== $scene (static camera, 128 frames)"
  $R render builtin:$scene --size 1920x1080 --frames 128 --seed 1 --primary auto --timings \
    --json "$OUT/$scene.json" -o "$OUT/$scene.png" 2>&1 | grep -vE '^rayster: (wrote|loaded)' || exit 1
done
# N lights scattered above the whitted scene (bench/scenes/whitted-lightsN.json, deterministic).
for n in 8 256; do
  echo "== whitted with $n lights"
  $R render bench/scenes/whitted-lights$n.json --size 1920x1080 --frames 128 --seed 1 --primary auto --timings \
    --json "$OUT/lights$n.json" -o "$OUT/lights$n.png" 2>&1 | grep -vE '^rayster: (wrote|loaded)' || exit 1
done
rm -f "$OUT"/lights*.png
# The device tool returns at most 8 files: pack the JSON results into one archive.
(cd "$OUT" && tar czf effects-json.tgz ./*.json && rm -f ./*.json)
