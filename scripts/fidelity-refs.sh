#!/usr/bin/env bash
# Re-renders the fidelity test's path-traced references (tests/fidelity/refs/SCENE-seedN.exr): two
# seeds per scene, the second only for the noise floor. Then re-freeze the budgets if the renderer
# changed on purpose (see tests/fidelity/refs/README.md).
# Usage: scripts/fidelity-refs.sh [WHITTED_SPP CORNELL_SPP SPHERES_SPP] (samples per pixel per scene)
set -euo pipefail
cd "$(dirname "$0")/.."
declare -A SPPS=([whitted]=${1:-96} [cornell]=${2:-512} [spheres]=${3:-1024})
BIN=${RAYSTER:-./build/rayster}
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for scene in whitted cornell spheres; do
  SPP=${SPPS[$scene]}
  for seed in 1 2; do
    out=tests/fidelity/refs/$scene-seed$seed.exr
    echo "$out ($SPP spp)"
    "$BIN" render "builtin:$scene" --mode pathtrace --size 96x72 --spp "$SPP" --seed "$seed" \
      --hdr "$out" -o "$tmp/$scene-$seed.png"
  done
done
