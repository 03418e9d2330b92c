#!/bin/bash
# Issue 16 item 2: the effects presets on the scenes made for them (bench/scenes/effects-*.json),
# beside Sascha Willems' raytracingshadows / raytracingreflections ray mixes. Both presets on both
# scenes, each also with --raw-rays (the raw-rate twins: each traced pass's share of the device's
# raw ray rate). Run from the repository root carrying dist/ (scripts/bundle-gpu.sh), $OUT set;
# writes $OUT/all.txt (the bench tables) and one bench JSON per run under $OUT.
set -u
cd "$(dirname "$0")/../../.."  # the repository root
O=$OUT/all.txt
export __GL_SHADER_DISK_CACHE_PATH=/tmp/nvcache
exec >"$O" 2>&1
date
dist/rayster-gpu/run.sh info
dist/rayster-gpu/run.sh bench builtin:whitted --size 1920x1080 --warmup 64 --frames 300 | grep frame  # clocks up
for scene in shadows mirrors; do
  for effects in shadows mirrors; do
    for raw in "" --raw-rays; do
      name=$scene-scene-$effects${raw:+-raw}
      echo "== $name"
      dist/rayster-gpu/run.sh bench bench/scenes/effects-$scene.json --size 1920x1080 --warmup 64 --frames 256 \
        --effects $effects $raw --json $OUT/$name.json
    done
  done
done
# The default frame on the same scenes, for the saving the presets give.
for scene in shadows mirrors; do
  echo "== $scene-scene-all"
  dist/rayster-gpu/run.sh bench bench/scenes/effects-$scene.json --size 1920x1080 --warmup 64 --frames 256 \
    --effects all --json $OUT/$scene-scene-all.json
done
# The mirrors preset with the bounce loop in place (no queue), and the whitted frame of this tree.
echo "== mirrors-scene-mirrors-noqueue"
dist/rayster-gpu/run.sh bench bench/scenes/effects-mirrors.json --size 1920x1080 --warmup 64 --frames 256 \
  --effects mirrors --specular-queue off --json $OUT/mirrors-scene-mirrors-noqueue.json
for s in whitted cornell; do
  echo "== $s"
  dist/rayster-gpu/run.sh bench builtin:$s --size 1920x1080 --warmup 64 --frames 256 --json $OUT/$s.json
done
date
