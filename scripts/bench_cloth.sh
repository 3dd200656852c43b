#!/usr/bin/env bash
# Frame time and peak resident memory of hanging cloths on one device.
# Usage: scripts/bench_cloth.sh [FRAMES] [DEVICES]   (build first: scripts/test.sh or quickstart.sh)
# Prints a Markdown table. The fixed OpenCL/pocl start-up memory is measured
# with a 2x2 cloth and subtracted to give the bytes per vertex.
set -euo pipefail
cd "$(dirname "$0")/.."
frames="${1:-30}"
devices="${2:-cpu}"
bin=build/release/atssim
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$HOME/.cache/atssim/pocl}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

run() {  # run RES -> prints "ms_per_frame peak_kib"
  local res=$1
  local out
  out=$(/usr/bin/time -f "%M" "$bin" run scenes/hanging_cloth.yaml -o "$tmp/out.h5" --frames "$frames" \
        --devices "$devices" --set "objects.0.grid.resolution=[$res,$res]" 2>"$tmp/time")
  local ms
  ms=$(echo "$out" | sed -E 's/.* ([0-9.]+) ms\/frame.*/\1/')
  echo "$ms $(tail -n 1 "$tmp/time")"
}

read -r _ base_kib < <(run 2)
echo "| cloth | vertices | ms/frame | peak RSS (MiB) | beyond start-up (bytes/vertex) | growth from previous row (bytes/vertex) |"
echo "|---|---|---|---|---|---|"
echo "| 2×2 (start-up) | 4 | – | $(awk "BEGIN{printf \"%.1f\", $base_kib/1024}") | – | – |"
prev_kib=$base_kib
prev_n=4
for res in 64 128 256; do
  read -r ms kib < <(run "$res")
  n=$((res * res))
  echo "| ${res}×${res} | $n | $ms | $(awk "BEGIN{printf \"%.1f\", $kib/1024}") | $(awk "BEGIN{printf \"%.0f\", ($kib-$base_kib)*1024/$n}") | $(awk "BEGIN{printf \"%.0f\", ($kib-$prev_kib)*1024/($n-$prev_n)}") |"
  prev_kib=$kib
  prev_n=$n
done
echo
echo "frames=$frames devices=$devices scene=scenes/hanging_cloth.yaml (16 substeps, 8 iterations, stretch + bending)"
