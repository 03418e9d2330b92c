#!/bin/bash
# The specular queue (rt-specular-continue) against the in-place loop, same binary, interleaved.
set -u
cd "$(dirname "$0")/../../.."  # the repository root
O=$OUT/all.txt
mkdir -p /tmp/res
export __GL_SHADER_DISK_CACHE_PATH=/tmp/nvcache
exec >"$O" 2>&1
date
R=dist/rayster-gpu/run.sh
$R bench builtin:whitted --size 1920x1080 --warmup 64 --frames 300 2>&1 | grep frame
for s in whitted spheres cornell whitted; do
  for q in on off; do
    echo "== $s queue $q"
    $R bench builtin:$s --size 1920x1080 --warmup 64 --frames 256 --specular-queue $q --json /tmp/res/$s-$q.json 2>&1 | grep -E "frame|rror"
  done
done
for d in 2 3 5; do
  echo "== whitted depth $d"
  $R bench builtin:whitted --size 1920x1080 --warmup 64 --frames 256 --max-depth $d --json /tmp/res/whitted-d$d.json 2>&1 | grep -E "frame|rror"
done
tar czf $OUT/res.tgz -C /tmp res
date
