#!/bin/bash
# One device call: probe cascade costs, sequence throughput, validation of cascades and sequences.
set -u
cd "$(dirname "$0")/../../.."  # the repository root
R=dist/rayster-gpu/run.sh
O=$OUT/all.txt
mkdir -p /tmp/res /tmp/scenes
export __GL_SHADER_DISK_CACHE_PATH=/tmp/nvcache
exec >"$O" 2>&1
date; nproc; nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv 2>&1 | head -3
dist/rayster-gpu/make-scene.sh sponza /tmp/scenes/sponza >/tmp/make.log 2>&1 || echo "make-scene failed"
echo "== warm"
$R bench builtin:whitted --size 1920x1080 --warmup 64 --frames 300 --json /tmp/res/warm.json 2>&1 | tail -2
for spec in "whitted|builtin:whitted" "whitted-c1|builtin:whitted --probe-cascades 1" \
  "spheres|builtin:spheres" "spheres-c1|builtin:spheres --probe-cascades 1" \
  "large|bench/scenes/large-room.json" "large-c1|bench/scenes/large-room.json --probe-cascades 1" \
  "sponza|/tmp/scenes/sponza/scene.gltf" "sponza-c1|/tmp/scenes/sponza/scene.gltf --probe-cascades 1"; do
  name=${spec%%|*}; args=${spec#*|}
  echo "== bench $name: $args"
  $R bench $args --size 1920x1080 --warmup 64 --frames 256 --json /tmp/res/$name.json 2>&1 | tail -3
done
for fr in 1 16; do
  for ext in png exr; do
    rm -rf /tmp/seq
    echo "== sequence 240 frames 1080p --frames $fr .$ext"
    s=$(date +%s%N)
    $R render bench/scenes/whitted-flythrough.json --frames-out 0:239 --path-fps 24 --size 1920x1080 --frames $fr \
      --primary rt -o /tmp/seq/f_####.$ext --json /tmp/res/seq-$fr-$ext.json --progress lines 2>&1 | tail -2
    echo "process wall $(( ($(date +%s%N) - s) / 1000000 )) ms; files $(ls /tmp/seq | wc -l); bytes $(du -sb /tmp/seq | cut -f1)"
  done
done
echo "== validation (sync validation on) of cascades and a sequence"
export VK_LAYER_PATH=$PWD/dist/validation
for args in "render bench/scenes/large-room.json --camera-path --frames 48 --size 640x360 -o /tmp/v1.png" \
  "render builtin:spheres --frames 16 --size 640x360 --probe-view on -o /tmp/v2.png" \
  "render bench/scenes/whitted-flythrough.json --frames-out 0:5 --frames 4 --size 640x360 -o /tmp/vs/f_##.png"; do
  echo "-- $args"
  $R --validation $args >/tmp/v.log 2>&1; rc=$?
  grep -v "^rayster: frame" /tmp/v.log | tail -4; echo "exit $rc; validation lines: $(grep -ci 'validation' /tmp/v.log)"
done
tar czf $OUT/res.tgz -C /tmp res
date
