#!/bin/bash
# A launch per specular segment (this tree, dist/rayster-gpu) against one continuation launch for
# all later segments (990d4aa, dist/old-gpu), interleaved; then the effects presets with per-pass JSON.
set -u
cd "$(dirname "$0")/../../.."  # the repository root
O=$OUT/all.txt
mkdir -p /tmp/res
export __GL_SHADER_DISK_CACHE_PATH=/tmp/nvcache
exec >"$O" 2>&1
date
dist/rayster-gpu/run.sh bench builtin:whitted --size 1920x1080 --warmup 64 --frames 300 | grep frame
for s in builtin:whitted builtin:spheres builtin:cornell; do
  for v in old new; do
    [ $v = old ] && R=dist/old-gpu/run.sh || R=dist/rayster-gpu/run.sh
    n=${s#builtin:}-$v
    echo "== $n"
    $R bench $s --size 1920x1080 --warmup 64 --frames 256 --json /tmp/res/$n.json 2>&1 | grep -E "frame|rror"
  done
done
for scene in shadows mirrors; do
  for effects in shadows mirrors all; do
    n=$scene-scene-$effects
    echo "== $n"
    dist/rayster-gpu/run.sh bench bench/scenes/effects-$scene.json --size 1920x1080 --warmup 64 --frames 256 \
      --effects $effects --raw-rays --json /tmp/res/$n.json 2>&1 | grep -E " frame|rror"
  done
done
n=mirrors-scene-mirrors-noqueue
echo "== $n"
dist/rayster-gpu/run.sh bench bench/scenes/effects-mirrors.json --size 1920x1080 --warmup 64 --frames 256 \
  --effects mirrors --specular-queue off --json /tmp/res/$n.json 2>&1 | grep -E " frame|rror"
rm -f /tmp/res/*.csv /tmp/res/*.svg
tar czf $OUT/res.tgz -C /tmp res
date
