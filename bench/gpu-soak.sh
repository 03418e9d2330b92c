#!/bin/sh
# The sequence soak (issue 17, docs/sequences.md "Faults, signals and exit codes"): one process
# renders FRAMES output frames (default 10000) of the animated whitted scene at SIZE (default
# 640x360), --frames 1, PNGs into a scratch folder that is emptied as it goes, while this script
# samples the process's resident host memory (VmRSS, /proc/PID/status) and the device memory it
# reports per frame (`-v`: "frame F: device memory B bytes in use", and nvidia-smi's per-process
# figure where there is one) every INTERVAL seconds (default 2). It prints each series'
# least-squares slope in bytes per 1000 frames, over all samples and over the samples after the
# first tenth of the run (warm-up: pipeline caches, allocator blocks). samples.csv, soak.log and
# summary.txt go to $OUT.
# Run from the repository root after scripts/bundle-gpu.sh, carrying dist/. RAYSTER=./build/rayster
# runs a local build instead (e.g. FRAMES=200 SIZE=64x36 on lavapipe, to check the script).
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
rayster="${RAYSTER:-$here/dist/rayster-gpu/run.sh}"
out="${OUT:-/tmp/rayster-soak}"
frames="${FRAMES:-10000}"
size="${SIZE:-640x360}"
interval="${INTERVAL:-2}"
scene="${SCENE:-builtin:whitted}"
scratch="${SCRATCH:-/tmp/rayster-soak-frames}"
mkdir -p "$out"
rm -rf "$scratch"
mkdir -p "$scratch"
export __GL_SHADER_DISK_CACHE_PATH=/tmp/rayster-nv-cache
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"

# Raster primaries and no indirect light: the soak is about memory across output frames, not about
# the cost of one; every output frame still restarts every history (docs/sequences.md).
"$rayster" -v render "$scene" --size "$size" --frames 1 --primary raster --frames-out "0:$((frames - 1))" \
  --progress lines -o "$scratch/f_########.png" --json "$out/soak.json" >"$out/soak.log" 2>&1 &
pid=$!
trap 'kill "$pid" 2>/dev/null || true; rm -rf "$scratch"' EXIT
trap 'exit 143' INT TERM

have_smi=0
command -v nvidia-smi >/dev/null 2>&1 && have_smi=1
echo "seconds,frame,host_rss_bytes,device_used_bytes,device_reserved_bytes,smi_used_bytes" >"$out/samples.csv"
start=$(date +%s)
while kill -0 "$pid" 2>/dev/null; do
  sleep "$interval"
  rss_kb=$(awk '/^VmRSS:/ {print $2}' "/proc/$pid/status" 2>/dev/null || true)
  [ -n "$rss_kb" ] || continue
  last=$(grep -o 'frame [0-9]*: device memory [0-9]* bytes in use, [0-9]* reserved' "$out/soak.log" | tail -n 1 || true)
  [ -n "$last" ] || continue
  frame=$(echo "$last" | awk '{print $2}' | tr -d :)
  used=$(echo "$last" | awk '{print $5}')
  reserved=$(echo "$last" | awk '{print $9}')
  smi=""
  if [ "$have_smi" = 1 ]; then
    mib=$(nvidia-smi --query-compute-apps=pid,used_memory --format=csv,noheader,nounits 2>/dev/null |
      awk -F', *' -v p="$pid" '$1 == p {print $2}' | head -n 1)
    [ -n "$mib" ] && smi=$((mib * 1048576))
  fi
  echo "$(($(date +%s) - start)),$frame,$((rss_kb * 1024)),$used,$reserved,$smi" >>"$out/samples.csv"
  # Written frames go as they come (never the temporary files: f_*.png.tmp-PID).
  find "$scratch" -name 'f_*.png' -delete
done
code=0
wait "$pid" || code=$?

# Least squares over (frame, value) for column `col`, from the samples with frame >= `from`.
slope() {
  awk -F, -v col="$1" -v from="$2" 'NR > 1 && $col != "" && $2 >= from {
      n++; x = $2; y = $col; sx += x; sy += y; sxx += x * x; sxy += x * y
      if (n == 1) first = y; last = y }
    END {
      d = n * sxx - sx * sx
      if (n < 3 || d == 0) { printf "n/a (%d samples)", n; exit }
      printf "%+.0f bytes per 1000 frames (%d samples, first %.1f MiB, last %.1f MiB)",
             1000 * (n * sxy - sx * sy) / d, n, first / 1048576, last / 1048576 }' "$out/samples.csv"
}
warm=$((frames / 10))
{
  echo "soak: $scene $size, --frames 1, frames 0:$((frames - 1)), exit $code, $(($(date +%s) - start)) s"
  grep -o '"device": "[^"]*"\|"driver": "[^"]*"\|"commit": "[^"]*"\|"frames_per_s": [0-9.e+-]*' "$out/soak.json" \
    2>/dev/null | tr '\n' ' ' || true
  echo
  for series in "3 host RSS" "4 device memory in use" "5 device memory reserved" "6 nvidia-smi used"; do
    col=${series%% *}
    name=${series#* }
    echo "$name: all $(slope "$col" 0); after frame $warm $(slope "$col" "$warm")"
  done
} >"$out/summary.txt"
cat "$out/summary.txt"
exit "$code"
