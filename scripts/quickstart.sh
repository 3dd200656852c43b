#!/usr/bin/env bash
# Quick start (1): install what is missing, build, run the default scene.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$HOME/.cache/atssim/pocl}"
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" --target atssim
build/release/atssim run scenes/hanging_cloth.yaml -o hanging_cloth.h5 "$@"
