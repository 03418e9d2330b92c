#!/usr/bin/env bash
# The H200's default output of scenes users bring (docs/gpu.md): each glTF under $SCENES (default
# dist/scenes, git-ignored: copy the files there first) is rendered at 1920x1080 with the default
# hybrid (--primary auto, which picks traced primaries on the H200) and with --primary raster, and
# the two are compared (`rayster compare`: FLIP and PSNR). Images and the report go to $OUT as one
# archive (the device tool returns at most 8 files). EXPOSURE_<stem>=EV sets a scene's exposure.
set -uo pipefail
cd "$(dirname "$0")/.."
R=dist/rayster-gpu/run.sh
OUT=${OUT:-bench/out}
SCENES=${SCENES:-dist/scenes}
FRAMES=${FRAMES:-64}
work=/tmp/user-scenes
rm -rf "$work" && mkdir -p "$work" "$OUT"
for scene in $(find "$SCENES" -name '*.gltf' -o -name '*.glb' | sort); do
  stem=$(basename "${scene%.*}")
  ev_var="EXPOSURE_${stem//-/_}"
  ev=${!ev_var:-0}
  for p in auto raster; do
    $R render "$scene" --size 1920x1080 --frames "$FRAMES" --seed 1 --primary $p --exposure "$ev" \
      -o "$work/$stem-$p.png" 2>&1 | grep -E 'error|warning|chose' | sed "s|^|$stem $p: |"
  done
  echo "== $stem (exposure $ev EV): default (auto) vs --primary raster"
  $R compare "$work/$stem-raster.png" "$work/$stem-auto.png" --metric all 2>&1 | grep -E 'flip|psnr|within'
done | tee "$work/report.txt"
tar czf "$OUT/user-scenes.tgz" -C /tmp user-scenes
cp "$work/report.txt" "$OUT/"
