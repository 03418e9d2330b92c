#!/usr/bin/env bash
# Regenerates assets/corpus/transform/: compressed and restructured glTF made by the real
# glTF-Transform CLI from small uncompressed sources (docs/gltf-compression.md). A developer runs
# this; CI only reads the committed outputs (tests/render/test_transform_corpus.cpp).
#
#   scripts/corpus/make_transform_corpus.sh [OUTDIR]   (default assets/corpus/transform)
#
# Needs node and npm; installs the pinned CLI into tools/npm (git-ignored) when it is missing.
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
OUT="${1:-$ROOT/assets/corpus/transform}"
CLI_VERSION=4.5.1
TOOLS="$ROOT/tools/npm"
GT="$TOOLS/node_modules/.bin/gltf-transform"

if [ ! -x "$GT" ] || [ "$("$GT" --version 2>/dev/null | tail -1)" != "$CLI_VERSION" ]; then
  mkdir -p "$TOOLS"
  npm install --prefix "$TOOLS" --no-audit --no-fund --silent "@gltf-transform/cli@$CLI_VERSION"
fi

mkdir -p "$OUT"
rm -rf "$OUT"/*.glb "$OUT/meshopt-gltf"
python3 "$ROOT/scripts/corpus/make_transform_source.py" "$OUT"
cp "$ROOT/assets/corpus/room.glb" "$OUT/room.glb"

gt() { echo "+ gltf-transform $*" >&2; "$GT" "$@" 2>&1 | grep -v "^info:" >&2 || true; }
cd "$OUT"
# KHR_mesh_quantization: positions, normals, UVs as normalized/unnormalized integers, node scales undo it.
gt quantize source.glb quantize.glb
# EXT_meshopt_compression (level high: quantized, OCTAHEDRAL normals and tangents, fallback buffer).
gt meshopt source.glb meshopt.glb
gt meshopt room.glb room-meshopt.glb
# The same as .gltf + .bin: the fallback buffer of a text glTF.
mkdir -p meshopt-gltf
gt meshopt source.glb meshopt-gltf/meshopt.gltf
# KHR_draco_mesh_compression, edgebreaker (default) and sequential.
gt draco source.glb draco.glb
gt draco source.glb draco-sequential.glb --method sequential
gt draco room.glb room-draco.glb
# The two halves of source.glb merged into one scene again.
gt merge part-a.glb part-b.glb merge.glb --merge-scenes
# EXT_mesh_gpu_instancing over the six spheres, plain and meshopt-compressed (the instance
# attributes in meshopt streams too; gltf-transform filters them with none).
gt instance source.glb instance.glb
gt meshopt instance.glb instance-meshopt.glb
# Restructuring that must not change the picture.
gt dedup source.glb dedup.glb
gt weld source.glb weld.glb
rm -f part-a.glb part-b.glb

echo "glTF-Transform $CLI_VERSION wrote:" >&2
ls -l "$OUT" "$OUT/meshopt-gltf" >&2
