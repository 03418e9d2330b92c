#!/usr/bin/env bash
# Installs every Debian package Rayster needs to build, test and run headless.
# Idempotent: re-running it only installs what is missing. Needs root (or sudo).
set -euo pipefail

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive

# Lavapipe only has ray tracing in the Mesa from bookworm-backports. The entry is derived from the
# machine's own bookworm entry (same mirror, components and key), so no host is named here.
# shellcheck source=scripts/apt-backports.sh
. "$(dirname "$0")/apt-backports.sh"
status=0
add_backports || status=$?
case "$status" in
  0) NEED_UPDATE=1 ;;
  2) exit 1 ;;  # backports_entry said what to add
esac

PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  glslc spirv-tools
  libvulkan-dev vulkan-validationlayers vulkan-tools libvulkan-volk-dev
  libglm-dev libfmt-dev libcli11-dev nlohmann-json3-dev libstb-dev
  libtinyexr-dev libgtest-dev libgmock-dev
  libglvnd0 libgl1 libegl1 libopengl0  # bundled for GPU machines by scripts/bundle-gpu.sh
  libtinygltf-dev libtinyobjloader-dev assimp-testmodels clang libfuzzer-14-dev
  libdraco-dev libmeshoptimizer-dev libzstd-dev  # compressed glTF: Draco, meshopt, KTX2 zstd
  clang-format-14  # scripts/format.sh: the formatting CI checks (.ci/run)
  libglfw3-dev libimgui-dev xvfb xauth  # the viewer, and its tests under a virtual X server
  slurm-wlm slurmctld slurmd slurm-client munge  # farm_slurm: a real one-machine Slurm (docs/farm.md)
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done

# Mesa must come from backports (>= 25): bookworm's own lavapipe has no ray tracing.
mesa_ver=$(dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || true)
need_mesa=1
case "$mesa_ver" in 2[5-9].*|[3-9][0-9].*) need_mesa=0 ;; esac

if [ ${#missing[@]} -gt 0 ] || [ "$need_mesa" = 1 ]; then
  if [ "${NEED_UPDATE:-0}" = 1 ] || [ ! -d /var/lib/apt/lists ] || [ -z "$(ls /var/lib/apt/lists/ 2>/dev/null | grep -i backports)" ]; then
    $SUDO apt-get update -qq
  fi
  if [ ${#missing[@]} -gt 0 ]; then
    echo "setup: installing ${missing[*]}"
    $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
  fi
  if [ "$need_mesa" = 1 ]; then
    echo "setup: installing lavapipe with ray tracing from bookworm-backports"
    $SUDO apt-get install -y -qq --no-install-recommends -t bookworm-backports mesa-vulkan-drivers
  fi
fi
echo "setup: all packages present"

# The official glTF-Validator from npm, pinned, into tools/npm (git-ignored): the loader's
# cross-check. Without the registry the test says it skipped; nothing else needs it.
VALIDATOR=gltf-validator@2.0.0-dev.3.10
TOOLS="$(cd "$(dirname "$0")/.." && pwd)/tools/npm"
if ! command -v npm >/dev/null 2>&1; then
  # Debian's node and npm, unless the machine has its own (best effort: only this test needs them).
  $SUDO apt-get install -y -qq --no-install-recommends nodejs npm >/dev/null 2>&1 ||
    echo "setup: warning: could not install nodejs and npm" >&2
fi
if [ ! -f "$TOOLS/node_modules/gltf-validator/package.json" ] && command -v npm >/dev/null 2>&1; then
  mkdir -p "$TOOLS"
  if npm install --prefix "$TOOLS" --no-audit --no-fund --silent "$VALIDATOR" >/dev/null 2>&1; then
    echo "setup: installed $VALIDATOR into tools/npm"
  else
    echo "setup: warning: could not install $VALIDATOR from npm; GltfValidator.* will skip" >&2
  fi
fi
