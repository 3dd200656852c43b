#!/usr/bin/env bash
# One point of a sweep made by scripts/sweep.sh (GNU parallel and Slurm array
# tasks both run this):
#   sweep_point.sh OUTDIR INDEX          run point INDEX unless it is complete
#   sweep_point.sh OUTDIR INDEX --done   exit 0 if it is complete, 1 if not
# Writes OUTDIR/pNNN.h5 (+ .xdmf), pNNN.json (`atssim run --json`) and pNNN.log.
set -euo pipefail
out="$1" index="$2"
name=$(printf 'p%03d' "$index")
line=$(sed -n "$((index + 1))p" "$out/points.tsv")
[ -n "$line" ] || { echo "sweep_point: no point $index in $out/points.tsv" >&2; exit 2; }
scene=$(awk -F'\t' '$1 == "scene" {print $2}' "$out/sweep.def")
atssim=$(awk -F'\t' '$1 == "atssim" {print $2}' "$out/sweep.def")
mapfile -t run_args < <(awk -F'\t' '$1 == "arg" {print $2}' "$out/sweep.def")

complete() {
  [ -f "$out/$name.json" ] && grep -q '"status": "complete"' "$out/$name.json" &&
    "$atssim" inspect "$out/$name.h5" 2>/dev/null | grep -q '^status: *complete'
}
if [ "${3:-}" = --done ]; then complete; exit $?; fi
if complete; then
  echo "sweep: $name complete, skipped" >&2
  exit 0
fi

sets=()
IFS=$'\t' read -r -a settings <<< "$line"
for s in "${settings[@]}"; do sets+=(--set "$s"); done
# The summary appears only once the run has ended (a killed run leaves none).
rc=0
"$atssim" run "$scene" -o "$out/$name.h5" ${run_args[@]+"${run_args[@]}"} "${sets[@]}" --json \
  > "$out/$name.json.tmp" 2> "$out/$name.log" || rc=$?
mv -f "$out/$name.json.tmp" "$out/$name.json"
echo "sweep: $name ($line) exit $rc" >&2
exit $rc
