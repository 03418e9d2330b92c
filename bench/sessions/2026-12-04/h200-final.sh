#!/bin/bash
# One device call: the 10000-frame soak, sequence throughput with the writer threads, whitted A/B.
set -u
cd "$(dirname "$0")/../../.."  # the repository root
O=$OUT/all.txt
mkdir -p /tmp/res
export __GL_SHADER_DISK_CACHE_PATH=/tmp/nvcache
exec >"$O" 2>&1
date; nproc
echo "== soak"
s=$(date +%s)
OUT=/tmp/res/soak timeout 300 sh bench/gpu-soak.sh 2>&1 | tail -15
echo "soak wall $(( $(date +%s) - s )) s"
R=dist/rayster-gpu/run.sh
for fr in 1 16; do
  for ext in png exr; do
    rm -rf /tmp/seq
    echo "== sequence 240 frames 1080p --frames $fr .$ext"
    s=$(date +%s%N)
    $R render bench/scenes/whitted-flythrough.json --frames-out 0:239 --path-fps 24 --size 1920x1080 --frames $fr \
      --primary rt -o /tmp/seq/f_####.$ext --json /tmp/res/seq-$fr-$ext.json --progress lines 2>&1 | tail -1
    echo "process wall $(( ($(date +%s%N) - s) / 1000000 )) ms; files $(ls /tmp/seq | wc -l)"
  done
done
for i in 1 2; do
  for v in old new; do
    [ $v = old ] && B=dist/old-gpu/run.sh || B=$R
    echo "== $v whitted run $i"
    $B bench builtin:whitted --size 1920x1080 --warmup 64 --frames 256 --json /tmp/res/whitted-$v-$i.json 2>&1 | grep frame
  done
done
rm -f /tmp/res/soak/soak.log
tar czf $OUT/res.tgz -C /tmp res
date
