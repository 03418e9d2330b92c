#!/bin/bash
# Attribution of builtin:whitted's 1080p frame: the default next to variants that remove one cost each.
set -u
cd "$(dirname "$0")/../../.."  # the repository root
O=$OUT/all.txt
mkdir -p /tmp/res
export __GL_SHADER_DISK_CACHE_PATH=/tmp/nvcache
exec >"$O" 2>&1
date
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv
R=dist/rayster-gpu/run.sh
$R bench builtin:whitted --size 1920x1080 --warmup 64 --frames 300 2>&1 | grep frame
i=0
while read -r name args; do
  [ -z "$name" ] && continue
  echo "== $name: $args"
  $R bench builtin:whitted --size 1920x1080 --warmup 64 --frames 256 $args --json /tmp/res/$name.json 2>&1 | grep -E "frame|rror"
done <<'VARIANTS'
default
depth2 --max-depth 2
depth3 --max-depth 3
depth5 --max-depth 5
noglossy --glossy-threshold 0
noindirect --indirect off
noao --ao off
nodenoise --denoise off
notaa --taa off
default2
VARIANTS
tar czf $OUT/res.tgz -C /tmp res
date
