#!/usr/bin/env bash
# Regenerates assets/meshes/{teapot,bunny}.mesh from the public-domain npm packages `teapot` and
# `bunny`. Versions are pinned so the output (and the sha256 in assets/meshes/README.md) is stable.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

npm install --no-save --no-audit --no-fund --ignore-scripts --prefix "$work" teapot@1.0.0 bunny@1.0.1 >/dev/null
node "$root/tools/convert-npm-meshes.js" "$work/node_modules" "$root/assets/meshes"
(cd "$root/assets/meshes" && sha256sum teapot.mesh bunny.mesh)
