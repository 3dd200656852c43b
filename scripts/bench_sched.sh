#!/usr/bin/env bash
# Scheduling time of HEFT / CPOP / PEFT on layered random DAGs, 2 devices.
# Builds bench_sched (Release) and prints the Markdown table that
# docs/benchmarks-sched.md quotes, preceded by the machine and commit.
#
#   scripts/bench_sched.sh [--sizes 300,3000,30000,100000] [--seconds 1.0]
#
# BUILD_DIR (default build/release) must be configured with the benchmarks
# on (ATSSIM_BUILD_BENCHMARKS, the default) — `cmake --preset release`.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${BUILD_DIR:-build/release}
if [ ! -f "$build_dir/build.ninja" ]; then
  cmake --preset release >/dev/null
fi
cmake --build "$build_dir" --target bench_sched -j "${JOBS:-2}" >/dev/null
echo "commit $(git rev-parse --short HEAD), $(date -u +%Y-%m-%d), $(nproc) cores," \
     "$(lscpu | sed -n 's/^Model name: *//p' | head -1), load $(cut -d' ' -f1 /proc/loadavg)"
echo
"$build_dir/bench/bench_sched" "$@"
