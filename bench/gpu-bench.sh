#!/usr/bin/env bash
# The full `rayster bench` plan on a GPU machine (docs/gpu.md): generates the large meshes of the
# triangle sweep, runs bench/plans/h100.json (one process per configuration) and packs the JSON,
# CSV and SVG into $OUT (default bench/out). Expects dist/rayster-gpu (scripts/bundle-gpu.sh).
set -uo pipefail
cd "$(dirname "$0")/.."
R=dist/rayster-gpu/run.sh
OUT=${OUT:-bench/out}
PLAN=${PLAN:-bench/plans/h100.json}
mkdir -p "$OUT" /tmp/rayster-bench
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv,noheader 2>/dev/null || true
for n in 1 4; do  # the triangle sweep's meshes, once per machine
  f=/tmp/rayster-bench/mesh-${n}m.glb
  [ -f "$f" ] || python3 bench/make_large_mesh.py "$f" ${n}000000 >/dev/null || exit 1
done
$R bench --plan "$PLAN" --json "$OUT/bench.json" 2>&1 | grep -vE '^rayster: (loaded|wrote [^,]*\.png)'
status=${PIPESTATUS[0]}
ls -l "$OUT"
exit "$status"
