#!/usr/bin/env bash
# A parameter sweep: every point of a grid of --set values is one
# `atssim run`, with its own HDF5 file and JSON summary (docs/sweeps.md).
#
#   scripts/sweep.sh SCENE OUTDIR --set KEY=V1,V2,V3 [--set KEY2=…]… [options] [-- RUN ARGS…]
#
#   --set KEY=V1,V2,…   one axis of the grid (commas inside [..] stay: objects.0.grid.resolution=[8,8],[16,16])
#   --backend B         parallel (default: GNU parallel on this machine), slurm (a job array; sbatch
#                       --wait blocks until it is done), list (print the points, run nothing)
#   --jobs N            points at once (default 2); for slurm the array's %N limit
#   --sbatch "ARGS"     extra sbatch arguments (partition, time limit, …)
#   -- RUN ARGS         passed to every `atssim run` (e.g. --frames 60 --devices cpu)
#
# Resumable: a point whose summary says "complete" (and whose HDF5 file
# `atssim inspect` calls complete) is skipped, so a sweep that was killed
# is finished by running the same command again. Points that failed or were
# interrupted run again. OUTDIR/points.tsv lists the points;
# scripts/sweep_merge.py OUTDIR collects the summaries into sweep.csv + sweep.png.
# The atssim binary: $ATSSIM, else build/release/atssim of this checkout.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"

usage() { sed -n '2,20p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
die() { echo "sweep: $*" >&2; exit 2; }

[ $# -ge 2 ] || usage
scene="$1" out="$2"
shift 2
[ -f "$scene" ] || die "no scene file '$scene'"
axes=() backend=parallel jobs=2 sbatch_args="" run_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --set) [ $# -ge 2 ] || usage; axes+=("$2"); shift 2 ;;
    --backend) [ $# -ge 2 ] || usage; backend="$2"; shift 2 ;;
    --jobs) [ $# -ge 2 ] || usage; jobs="$2"; shift 2 ;;
    --sbatch) [ $# -ge 2 ] || usage; sbatch_args="$2"; shift 2 ;;
    --) shift; run_args=("$@"); break ;;
    -h|--help) usage ;;
    *) die "unknown option '$1' (see --help)" ;;
  esac
done
[ ${#axes[@]} -gt 0 ] || die "give at least one --set KEY=V1,V2,…"
case "$backend" in parallel|slurm|list) ;; *) die "--backend is parallel, slurm or list, not '$backend'" ;; esac
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || die "--jobs takes a positive number, not '$jobs'"

# Values of one axis: split at commas outside brackets.
split_values() {
  local text="$1" depth=0 current="" c i
  for ((i = 0; i < ${#text}; i++)); do
    c="${text:i:1}"
    case "$c" in
      "[" | "{") depth=$((depth + 1)) ;;
      "]" | "}") depth=$((depth - 1)) ;;
    esac
    if [ "$c" = "," ] && [ $depth -eq 0 ]; then
      printf '%s\n' "$current"
      current=""
    else
      current+="$c"
    fi
  done
  printf '%s\n' "$current"
}

# The grid, one point per line: KEY=VALUE<TAB>KEY=VALUE… (the last axis varies fastest).
points=("")
for axis in "${axes[@]}"; do
  [[ "$axis" == *=* ]] || die "--set '$axis' is not KEY=V1,V2,…"
  key="${axis%%=*}"
  mapfile -t values < <(split_values "${axis#*=}")
  next=()
  for p in "${points[@]}"; do
    for v in "${values[@]}"; do
      [ -n "$v" ] || die "--set '$axis' has an empty value"
      next+=("${p:+$p$'\t'}$key=$v")
    done
  done
  points=("${next[@]}")
done

mkdir -p "$out"
out="$(cd "$out" && pwd)"
scene="$(cd "$(dirname "$scene")" && pwd)/$(basename "$scene")"
atssim="${ATSSIM:-$here/../build/release/atssim}"
[ -x "$atssim" ] || die "no atssim binary at '$atssim' (build it, or set ATSSIM)"
atssim="$(cd "$(dirname "$atssim")" && pwd)/$(basename "$atssim")"

# The sweep's definition; a second run in the same folder must be the same sweep.
definition="$(
  printf 'scene\t%s\n' "$scene"
  printf 'atssim\t%s\n' "$atssim"
  for a in ${run_args[@]+"${run_args[@]}"}; do printf 'arg\t%s\n' "$a"; done
)"
if [ -f "$out/points.tsv" ]; then
  if [ "$(cat "$out/points.tsv")" != "$(printf '%s\n' "${points[@]}")" ] ||
     [ "$(cat "$out/sweep.def")" != "$definition" ]; then
    die "$out holds another sweep (points.tsv or sweep.def differ); use another folder"
  fi
else
  printf '%s\n' "${points[@]}" > "$out/points.tsv"
  printf '%s\n' "$definition" > "$out/sweep.def"
fi
n=${#points[@]}

if [ "$backend" = list ]; then
  for ((i = 0; i < n; i++)); do printf 'p%03d\t%s\n' "$i" "${points[i]}"; done
  exit 0
fi

todo=()
for ((i = 0; i < n; i++)); do
  bash "$here/sweep_point.sh" "$out" "$i" --done && continue
  todo+=("$i")
done
echo "sweep: $n points in $out; $((n - ${#todo[@]})) complete already, ${#todo[@]} to run ($backend)" >&2
[ ${#todo[@]} -gt 0 ] || exit 0

export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$HOME/.cache/atssim/pocl}"
status=0
if [ "$backend" = parallel ]; then
  command -v parallel >/dev/null || die "GNU parallel is not installed (bash scripts/setup.sh)"
  printf '%s\n' "${todo[@]}" |
    parallel --will-cite --jobs "$jobs" --joblog "$out/parallel.log" \
      bash "$here/sweep_point.sh" "$out" {} || status=$?
else
  command -v sbatch >/dev/null || die "Slurm's sbatch is not installed (bash scripts/setup.sh slurm)"
  array="$(IFS=,; echo "${todo[*]}")%$jobs"
  # shellcheck disable=SC2086  # sbatch_args are words on purpose
  job=$(sbatch --parsable --wait --array="$array" --job-name=atssim-sweep --cpus-per-task=1 \
          --output="$out/slurm-%A_%a.out" $sbatch_args \
          --wrap "bash '$here/sweep_point.sh' '$out' \$SLURM_ARRAY_TASK_ID") || status=$?
  echo "sweep: Slurm job array ${job:-?} finished" >&2
fi
failed=0
for ((i = 0; i < n; i++)); do bash "$here/sweep_point.sh" "$out" "$i" --done || failed=$((failed + 1)); done
echo "sweep: $((n - failed)) of $n points complete" >&2
[ $failed -eq 0 ] || exit 1
exit $status
