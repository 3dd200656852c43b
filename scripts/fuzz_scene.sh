#!/usr/bin/env bash
# Fuzzes the scene parser with libFuzzer (Debian's clang; `bash scripts/setup.sh fuzz`
# installs it). It runs niced, one worker; scripts/check.sh runs it for 2
# minutes (CI, --quick) or 10.
#
#   scripts/fuzz_scene.sh [RUNS] [extra libFuzzer flags]   (default 1000000 runs; -1: no limit,
#                                                           e.g. with -max_total_time=120)
#   scripts/fuzz_scene.sh --build-only                     (scripts/check.sh, beside its build)
#
# Builds build/fuzz/fuzz_scene from lib/scene + lib/util with
# -fsanitize=fuzzer,address,undefined; the seed corpus is the kept corpus
# tests/fuzz/corpus (a minimised corpus of earlier runs), every bundled scene
# and every bad-input case; new inputs go to build/fuzz/corpus, crashes to
# build/fuzz/crash-*. Turn a crash into a case under tests/bad_input/cases.
# To refresh the kept corpus after a long run:
#   build/fuzz/fuzz_scene -merge=1 -max_len=8192 tests/fuzz/corpus build/fuzz/corpus
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build_only=0
if [[ "${1:-}" == --build-only ]]; then build_only=1; fi
runs="${1:-1000000}"
shift || true
out="$root/build/fuzz"
mkdir -p "$out/corpus" "$out/seeds"
cxx="$(command -v clang++-14 || command -v clang++ || true)"
if [[ -z "$cxx" ]]; then
  echo "fuzz_scene.sh: clang++ is not installed (bash scripts/setup.sh fuzz)" >&2
  exit 2
fi
sources=("$root"/lib/scene/*.cpp "$root"/lib/util/*.cpp "$root"/tests/fuzz/fuzz_scene.cpp)
if [[ ! -x "$out/fuzz_scene" || -n "$(find "${sources[@]}" "$root"/lib/scene "$root"/lib/util -newer "$out/fuzz_scene" 2>/dev/null | head -1)" ]]; then
  echo "building $out/fuzz_scene"
  nice -n 10 "$cxx" -std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    -I"$root/lib" $(pkg-config --cflags yaml-cpp assimp fmt 2>/dev/null || true) "${sources[@]}" \
    -lyaml-cpp -lassimp -lfmt -o "$out/fuzz_scene"
fi
if [[ "$build_only" -eq 1 ]]; then exit 0; fi
cp "$root"/scenes/*.yaml "$root"/tests/bad_input/cases/*.yaml "$out/seeds/"
if compgen -G "$root/tests/fuzz/corpus/*" >/dev/null; then cp "$root"/tests/fuzz/corpus/* "$out/seeds/"; fi
cd "$out"
echo "nice -n 19 $out/fuzz_scene -runs=$runs -timeout=10 -rss_limit_mb=2048 -max_len=8192 $* corpus seeds"
exec nice -n 19 "$out/fuzz_scene" -runs="$runs" -timeout=10 -rss_limit_mb=2048 -max_len=8192 -print_final_stats=1 \
  "$@" corpus seeds
