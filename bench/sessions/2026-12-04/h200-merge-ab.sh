#!/bin/bash
# A/B: the tree before the effects merge (990d4aa, dist/old-gpu) against this one (dist/rayster-gpu).
set -u
cd "$(dirname "$0")/../../.."  # the repository root
O=$OUT/all.txt
mkdir -p /tmp/res
export __GL_SHADER_DISK_CACHE_PATH=/tmp/nvcache
exec >"$O" 2>&1
date
dist/rayster-gpu/run.sh bench builtin:whitted --size 1920x1080 --warmup 64 --frames 300 | grep frame
for s in whitted cornell; do
  for v in old new; do
    [ $v = old ] && R=dist/old-gpu/run.sh || R=dist/rayster-gpu/run.sh
    echo "== $v $s"
    $R bench builtin:$s --size 1920x1080 --warmup 64 --frames 256 --json /tmp/res/$s-$v.json 2>&1 | grep -E "frame|rror"
  done
done
tar czf $OUT/res.tgz -C /tmp res
date
