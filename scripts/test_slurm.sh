#!/usr/bin/env bash
# The sweep's Slurm path, for real: starts a one-node cluster on this machine
# (scripts/slurm_cluster.sh), runs the `slurm`-labelled test (a 3×3 sweep as
# a job array, every output checked, merged into 9 rows), and stops the
# daemons again whatever happened. Needs root and a release build.
#   bash scripts/test_slurm.sh
set -euo pipefail
cd "$(dirname "$0")/.."
dir="$(mktemp -d /tmp/atssim-slurm.XXXXXX)"
trap 'bash scripts/slurm_cluster.sh stop "$dir"; rm -rf "$dir"' EXIT
eval "$(bash scripts/slurm_cluster.sh start "$dir")"
export SLURM_CONF
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$HOME/.cache/atssim/pocl}"
ctest --test-dir build/release -L slurm --output-on-failure "$@"
