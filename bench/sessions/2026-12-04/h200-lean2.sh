#!/bin/bash
# Frame memory after the flat layers target and the late probe lookup (this tree, dist/rayster-gpu):
# the whitted frame's memory listing, its timings, the effects presets and the other built-ins.
set -u
cd "$(dirname "$0")/../../.."  # the repository root
O=$OUT/all.txt
mkdir -p /tmp/res
export __GL_SHADER_DISK_CACHE_PATH=/tmp/nvcache
exec >"$O" 2>&1
date
R=dist/rayster-gpu/run.sh
$R info
$R bench builtin:whitted --size 1920x1080 --warmup 64 --frames 300 | grep frame  # clocks up
$R render builtin:whitted --size 1920x1080 --frames 2 --memory-report -o /tmp/w.png 2>&1 | grep -v "warmup"
for s in whitted cornell spheres; do
  echo "== $s"
  $R bench builtin:$s --size 1920x1080 --warmup 64 --frames 256 --json /tmp/res/$s.json 2>&1 | grep -E " frame|rror"
done
echo "== room"
$R bench assets/corpus/room.glb --size 1920x1080 --warmup 64 --frames 256 --json /tmp/res/room.json 2>&1 | grep -E " frame|rror"
for scene in shadows mirrors; do
  for effects in shadows mirrors all; do
    n=$scene-scene-$effects
    echo "== $n"
    $R bench bench/scenes/effects-$scene.json --size 1920x1080 --warmup 64 --frames 256 \
      --effects $effects --json /tmp/res/$n.json 2>&1 | grep -E " frame|rror"
  done
done
rm -f /tmp/res/*.csv /tmp/res/*.svg
tar czf $OUT/res.tgz -C /tmp res
date
