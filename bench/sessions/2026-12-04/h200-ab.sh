#!/bin/bash
# A/B of the probe lookup: 05811f8 (before cascades) vs this tree, interleaved, plus cascade costs.
set -u
cd "$(dirname "$0")/../../.."  # the repository root
O=$OUT/all.txt
mkdir -p /tmp/res /tmp/scenes
export __GL_SHADER_DISK_CACHE_PATH=/tmp/nvcache
exec >"$O" 2>&1
date
nvidia-smi -L; nvidia-smi --query-gpu=index,uuid,name --format=csv
dist/rayster-gpu/run.sh info --json; dist/rayster-gpu/run.sh info
dist/rayster-gpu/make-scene.sh sponza /tmp/scenes/sponza >/tmp/make.log 2>&1 || echo "make-scene failed"
dist/rayster-gpu/run.sh bench builtin:whitted --size 1920x1080 --warmup 64 --frames 300 --json /tmp/res/warm.json 2>&1 | grep frame
for i in 1 2 3; do
  for v in old new; do
    [ $v = old ] && R=dist/old-gpu/run.sh || R=dist/rayster-gpu/run.sh
    echo "== $v whitted run $i"
    $R bench builtin:whitted --size 1920x1080 --warmup 64 --frames 256 --json /tmp/res/whitted-$v-$i.json 2>&1 | grep frame
  done
done
R=dist/rayster-gpu/run.sh
for spec in "spheres|builtin:spheres" "spheres-c1|builtin:spheres --probe-cascades 1" \
  "large|bench/scenes/large-room.json" "large-c1|bench/scenes/large-room.json --probe-cascades 1" \
  "sponza|/tmp/scenes/sponza/scene.gltf" "sponza-c1|/tmp/scenes/sponza/scene.gltf --probe-cascades 1" \
  "room|assets/corpus/room.glb" "cornell|builtin:cornell" "product|assets/corpus/product.json"; do
  name=${spec%%|*}; args=${spec#*|}
  echo "== bench $name: $args"
  $R bench $args --size 1920x1080 --warmup 64 --frames 256 --json /tmp/res/$name.json 2>&1 | grep frame
done
for s in spheres cornell; do
  echo "== old $s"; dist/old-gpu/run.sh bench builtin:$s --size 1920x1080 --warmup 64 --frames 256 --json /tmp/res/$s-old.json 2>&1 | grep frame
done
tar czf $OUT/res.tgz -C /tmp res
date
