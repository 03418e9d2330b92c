#!/usr/bin/env bash
# One device call (docs/gpu.md) that measures a commit for BENCHMARKS.md: the frame plan
# (bench/plans/h200-frame.json: scenes, resolution and depth sweeps), the scaling plan (lights,
# triangles) and the culling plan, each packed as a .tgz in $OUT; and the start-up time of a
# process with Rayster's pipeline cache cold and warm (the driver's own disk cache off).
set -uo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-bench/out}
PLANS=${PLANS:-"h200-frame h200-scaling culling"}
mkdir -p "$OUT"
export __GL_SHADER_DISK_CACHE=0
R=dist/rayster-gpu/run.sh
for cache in cold warm; do
  [ $cache = cold ] && rm -rf /tmp/rayster-pcache
  start=$(date +%s%N)
  RAYSTER_CACHE_DIR=/tmp/rayster-pcache $R render builtin:whitted --size 640x360 --frames 1 -o /tmp/startup.png >/dev/null 2>&1
  echo "startup ($cache pipeline cache, driver cache off): $(( ($(date +%s%N) - start) / 1000000 )) ms"
done
ls -la /tmp/rayster-pcache
# The plans themselves may use the driver's cache too (faster process start, same GPU times).
export __GL_SHADER_DISK_CACHE=1 __GL_SHADER_DISK_CACHE_PATH=/tmp/nvcache __GL_SHADER_DISK_CACHE_SKIP_CLEANUP=1
mkdir -p /tmp/nvcache
for plan in $PLANS; do
  PLAN=bench/plans/$plan.json OUT=/tmp/bench-$plan bash bench/gpu-bench.sh 2>&1 | grep -E "frame|failed|wrote|error"
  tar czf "$OUT/$plan.tgz" -C /tmp "bench-$plan"
done
ls -la "$OUT"
