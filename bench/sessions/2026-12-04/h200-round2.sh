#!/bin/bash
# Round 2 of the whitted frame: the specular queue, probe lookups skipped at mirror and glass hits,
# reflection SVGF at 3 à-trous steps, AO at half rate; A/B of the AO rate and the queue in one call.
set -u
cd "$(dirname "$0")/../../.."  # the repository root
O=$OUT/all.txt
mkdir -p /tmp/res
export __GL_SHADER_DISK_CACHE_PATH=/tmp/nvcache
exec >"$O" 2>&1
date
R=dist/rayster-gpu/run.sh
$R bench builtin:whitted --size 1920x1080 --warmup 64 --frames 300 2>&1 | grep frame
while read -r name scene args; do
  [ -z "$name" ] && continue
  echo "== $name: $scene $args"
  $R bench $scene --size 1920x1080 --warmup 64 --frames 256 $args --json /tmp/res/$name.json 2>&1 | grep -E "frame|rror"
done <<'VARIANTS'
whitted builtin:whitted
whitted-aofull builtin:whitted --ao-rate full
whitted-noqueue builtin:whitted --specular-queue off
cornell builtin:cornell
spheres builtin:spheres
room assets/corpus/room.glb
whitted2 builtin:whitted
VARIANTS
dist/rayster-gpu/run.sh render builtin:whitted --size 1920x1080 --frames 2 --memory-report -o /tmp/res/w.png 2>&1 | tail -40
tar czf $OUT/res.tgz -C /tmp res
date
