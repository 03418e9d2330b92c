#!/usr/bin/env bash
# Scene measurements on a GPU machine (docs/gpu.md): per-pass GPU times at 1920x1080 for each
# built-in scene and G-buffer producer (one configuration per process), and the load and build
# times of a 1M-triangle glTF. Expects dist/rayster-gpu (scripts/bundle-gpu.sh). Output in $OUT.
set -uo pipefail
cd "$(dirname "$0")/.."
R=dist/rayster-gpu/run.sh
OUT=${OUT:-bench/out}
mkdir -p "$OUT"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null || true
for scene in whitted cornell spheres; do
  for p in raster rt auto; do
    echo "== $scene, primary $p"
    $R render builtin:$scene --size 1920x1080 --frames 256 --seed 1 --primary $p --timings \
      --json "$OUT/$scene-$p.json" -o "$OUT/$scene-$p.png" 2>&1 | grep -vE '^rayster: (wrote|loaded)' || exit 1
  done
done
echo "== 1M-triangle glTF: load, upload, BLAS build"
python3 bench/make_large_mesh.py /tmp/large.glb 1000000
$R render /tmp/large.glb --size 1920x1080 --frames 64 --primary auto --timings --json "$OUT/large-1m.json" \
  -o "$OUT/large.png" || exit 1
rm -f "$OUT"/*-raster.png "$OUT"/*-auto.png "$OUT"/large.png "$OUT"/cornell-rt.png
# The device tool returns at most 8 files: pack the JSON results into one archive.
(cd "$OUT" && tar czf scenes-json.tgz ./*.json && rm -f ./*.json)
