#!/usr/bin/env bash
# Re-renders the fidelity test's path-traced references (tests/fidelity/refs/SCENE-seedN.exr): two
# seeds per scene, the second only for the noise floor. Then re-freeze the budgets if the renderer
# changed on purpose (see tests/fidelity/refs/README.md).
# Usage: scripts/fidelity-refs.sh [SCENE...] (default: all; samples per pixel per scene below)
# Paths get up to 32 vertices (Russian roulette from the third): the hybrid's probes carry every
# bounce, so a reference cut at the default 8 would be darker than the light it is checked against.
set -euo pipefail
cd "$(dirname "$0")/.."
declare -A SPPS=([whitted]=256 [cornell]=1024 [spheres]=1024 [room]=1024 [atrium]=2048 [product]=1024 [foliage]=512)
declare -A SOURCES=([whitted]=builtin:whitted [cornell]=builtin:cornell [spheres]=builtin:spheres
  [room]=assets/corpus/room.glb [atrium]=assets/corpus/atrium.glb [product]=assets/corpus/product.json
  [foliage]=assets/corpus/foliage.json)
BIN=${RAYSTER:-./build/rayster}
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scenes=("$@")
((${#scenes[@]})) || scenes=(whitted cornell spheres room atrium product foliage)
for scene in "${scenes[@]}"; do
  SPP=${SPPS[$scene]}
  for seed in 1 2; do
    out=tests/fidelity/refs/$scene-seed$seed.exr
    echo "$out ($SPP spp)"
    "$BIN" render "${SOURCES[$scene]}" --mode pathtrace --size 96x72 --spp "$SPP" --seed "$seed" --max-depth 32 \
      --hdr "$out" -o "$tmp/$scene-$seed.png" | grep -v 'frame [0-9]*/' || true
  done
done
