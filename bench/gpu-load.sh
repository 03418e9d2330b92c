#!/bin/sh
# The load-time benchmark on the GPU machine (BENCHMARKS.md, "Loading big scenes"): writes the
# Sponza-sized glTF and the 10M-triangle GLB with the bundle's rayster-make-scene into /tmp (they
# are too big to carry), then loads each RUNS times (default 3) with `render --frames 1 --size
# 64x64 -v`, whose debug lines time every phase. make.log, load.log and summary.txt go to $OUT.
# Run from the repository root after scripts/bundle-gpu.sh, carrying dist/.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
dist="$here/dist/rayster-gpu"
out="${OUT:-/tmp/rayster-load}"
scenes="${SCENES_DIR:-/tmp/rayster-scenes}"
runs="${RUNS:-3}"
mkdir -p "$out" "$scenes"
export __GL_SHADER_DISK_CACHE_PATH=/tmp/rayster-nv-cache
# Written once per machine (a second call, e.g. with RAYSTER_THREADS=1, reuses them).
[ -f "$scenes/sponza/scene.gltf" ] || "$dist/make-scene.sh" sponza "$scenes/sponza" >>"$out/make.log" 2>&1
[ -f "$scenes/big10m.glb" ] || "$dist/make-scene.sh" big "$scenes/big10m.glb" >>"$out/make.log" 2>&1
: >"$out/load.log"
for s in sponza/scene.gltf big10m.glb; do
  for i in $(seq "$runs"); do
    echo "== $s run $i (threads ${RAYSTER_THREADS:-all})" >>"$out/load.log"
    start=$(date +%s%N)
    # Only the three logs go to $OUT (the device tool brings back few files).
    "$dist/run.sh" -v render "$scenes/$s" --frames 1 --size 64x64 -o /tmp/rayster-load.png \
      --json /tmp/rayster-load.json >>"$out/load.log" 2>&1 || echo "render failed: exit $?" >>"$out/load.log"
    grep -o '"upload_ms": [0-9.]*\|"accel_build_ms": [0-9.]*' /tmp/rayster-load.json >>"$out/load.log" || true
    echo "process wall $(( ($(date +%s%N) - start) / 1000000 )) ms" >>"$out/load.log"
  done
done
grep -E '^==|loaded |loading |on the device|BLAS|uploaded in|process wall|_ms' "$out/load.log" >"$out/summary.txt"
nproc >>"$out/summary.txt"
cat "$out/summary.txt"
