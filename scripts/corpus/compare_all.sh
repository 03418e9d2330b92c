#!/usr/bin/env bash
# Rayster's path tracer and hybrid against the Cycles references, by mean luminance (docs/corpus.md).
#   scripts/corpus/compare_all.sh [--spp N] [--lambert]
# Needs the .blend files of make_corpus.py in $BLEND and the Cycles EXRs of cycles.sh in $CYCLES
# (--lambert makes and renders the pure-Lambert variants itself). Writes Rayster's images to $RT.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
corpus=${CORPUS:-$root/assets/corpus}
blend=${BLEND:-/tmp/corpus-blend}
cycles=${CYCLES:-/tmp/corpus-cycles}
rt=${RT:-/tmp/corpus-rt}
rayster=${RAYSTER:-$root/build/rayster}
spp=256
lambert=0
while (($#)); do
  case $1 in
    --spp) spp=$2; shift 2 ;;
    --lambert) lambert=1; shift ;;
    *) echo "usage: $0 [--spp N] [--lambert]" >&2; exit 2 ;;
  esac
done
scenes=(room.glb atrium.glb product.json foliage.json)
means="/usr/bin/python3 $root/scripts/corpus/compare_means.py"
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}

render() {  # the binary disappears for a while when it is rebuilt
  for _ in $(seq 120); do [[ -x $rayster ]] && break; sleep 5; done
  "$rayster" render "$@" --size 160x120 --exr-float 2>&1 | grep -v 'frame [0-9]*/' || true
}

if ((lambert)); then  # same scenes, every material pure Lambert in both renderers
  mkdir -p "$rt/lambert-scenes" "$blend/lambert"
  cp "$corpus"/*.json "$corpus"/*.hdr "$rt/lambert-scenes/"
  for scene in "${scenes[@]}"; do
    name=${scene%.*}
    python3 "$root/scripts/corpus/lambert_variant.py" "$corpus/$name.glb" "$rt/lambert-scenes/$name.glb"
    blender -b "$blend/$name.blend" --python "$root/scripts/corpus/lambert_variant.py" -- \
      "$blend/lambert/$name.blend" >/dev/null 2>&1
  done
  "$root/scripts/corpus/cycles.sh" "$blend/lambert" "$cycles/lambert" "$spp"
  corpus=$rt/lambert-scenes cycles=$cycles/lambert rt=$rt/lambert
fi

mkdir -p "$rt"
for scene in "${scenes[@]}"; do
  name=${scene%.*}
  render "$corpus/$scene" --mode pathtrace --frames "$spp" --max-depth 9 -o "$rt/$name.png" --hdr "$rt/$name.exr"
  ((lambert)) || render "$corpus/$scene" --frames 16 -o "$rt/$name-hybrid.png" --hdr "$rt/$name-hybrid.exr"
done
echo "Rayster path tracer (/ 683) vs Cycles:"
for scene in "${scenes[@]}"; do
  name=${scene%.*}
  $means "$cycles/$name.exr" "$rt/$name.exr" --test-scale 683 --name "$name"
done
((lambert)) && exit 0
echo "Rayster hybrid vs Rayster path tracer:"
for scene in "${scenes[@]}"; do
  name=${scene%.*}
  $means "$rt/$name.exr" "$rt/$name-hybrid.exr" --name "$name"
done
