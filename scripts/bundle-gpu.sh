#!/usr/bin/env bash
# Builds a Release rayster and packs it with the shared libraries and the Vulkan loader it needs
# into dist/rayster-gpu/, for a GPU machine that has a driver but no package manager (docs/gpu.md).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-release -G Ninja -DCMAKE_BUILD_TYPE=Release -DRAYSTER_BUILD_TESTS=OFF >/dev/null
ninja -C build-release rayster rayster-make-scene
out=dist/rayster-gpu
rm -rf "$out"
mkdir -p "$out/lib"
cp build-release/rayster build-release/rayster-make-scene "$out/"
# Every library the binary links, except the C/C++ runtime the target has (newer than Debian 12's),
# plus what is loaded at run time: the Vulkan loader (volk dlopens it) and glvnd's dispatch
# libraries, which NVIDIA's Vulkan driver (libGLX_nvidia) needs to load.
runtime='^(libc|libm|libdl|libpthread|librt|libstdc\+\+|libgcc_s|ld-linux-x86-64|linux-vdso)\.'
libs=$(ldd build-release/rayster | awk '/=> \// {print $1}' | grep -vE "$runtime")
for lib in $libs libvulkan.so.1 libGLdispatch.so.0 libGLX.so.0 libEGL.so.1 libOpenGL.so.0 libGL.so.1; do
  # No early `exit` in awk: ldconfig would die of SIGPIPE and pipefail would end the script silently.
  path=$(ldconfig -p | awk -v l="$lib" '$1 == l && /x86-64/ && !found {print $NF; found = 1}')
  [ -n "$path" ] || { echo "bundle-gpu: $lib not found (run scripts/setup.sh)" >&2; exit 1; }
  cp -L "$path" "$out/lib/$lib"
done
cat >"$out/run.sh" <<'RUN'
#!/bin/sh
# Runs the bundled rayster with its own libraries and the machine's NVIDIA Vulkan driver.
here=$(cd "$(dirname "$0")" && pwd)
export LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
if [ -z "${VK_DRIVER_FILES:-}${VK_ICD_FILENAMES:-}" ]; then
  for f in /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json /usr/share/vulkan/icd.d/nvidia_icd.json \
           /etc/vulkan/icd.d/nvidia_icd.json; do
    if [ -f "$f" ]; then export VK_DRIVER_FILES="$f" VK_ICD_FILENAMES="$f"; break; fi
  done
fi
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
exec "$here/rayster" "$@"
RUN
chmod +x "$out/run.sh"
# The load-time benchmark's scene generator (bench/make_big_scene.cpp, bench/gpu-load.sh).
cat >"$out/make-scene.sh" <<'RUN'
#!/bin/sh
here=$(cd "$(dirname "$0")" && pwd)
export LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
exec "$here/rayster-make-scene" "$@"
RUN
chmod +x "$out/make-scene.sh"
du -sh "$out"
echo "bundle-gpu: $out ready; run it as $out/run.sh render ..."
