#!/usr/bin/env bash
# Cycles references of the corpus scenes (docs/corpus.md):
#   scripts/corpus/cycles.sh [BLENDDIR] [OUTDIR] [SAMPLES]
# renders BLENDDIR/{room,atrium,product,foliage}.blend (from make_corpus.py) to OUTDIR/NAME.exr.
set -euo pipefail
blend_dir=${1:-/tmp/corpus-blend}
out_dir=${2:-/tmp/corpus-cycles}
samples=${3:-256}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out_dir"
for name in room atrium product foliage; do
  start=$SECONDS
  blender -b "$blend_dir/$name.blend" --python "$here/cycles_render.py" -- "$out_dir/$name.exr" "$samples" \
    >"$out_dir/$name.log" 2>&1 || { tail -20 "$out_dir/$name.log"; exit 1; }
  echo "$out_dir/$name.exr ($samples samples, $((SECONDS - start)) s)"
done
