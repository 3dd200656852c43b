#!/usr/bin/env bash
# The reliability checks beyond the test suite (docs/reliability.md).
#
#   bash scripts/check.sh --quick   # CI (.ci/run): a few minutes
#   bash scripts/check.sh           # before an issue is called resolved: the whole suite
#
# Steps (each is run, then all are reported; any failure fails the script):
#   format  clang-format over every C, C++ and OpenCL file of the repository (check only)
#   build   the sanitizer build (ASan + UBSan): the `debug` preset, benchmarks left out
#   tests   --quick: every unit-test binary (tests/<stage>, one process each) and the
#           app tests tagged [fast]; full: `ctest --preset debug` (the whole suite)
#   fuzz    libFuzzer on the scene parser (scripts/fuzz_scene.sh) from the kept corpus
#           tests/fuzz/corpus: 2 minutes (--quick) or 10
#   tidy    clang-tidy (.clang-tidy's check set) over the C++ files the change touched:
#           relative to the merge-base with main, or to HEAD~1 on main itself (CI);
#           CHECK_BASE=<commit> sets it
# Installs what it needs first (`scripts/setup.sh check`: clang, clang-tidy,
# clang-format, libclang-rt-dev).
set -uo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"

quick=0
for arg in "$@"; do
  case "$arg" in
    --quick) quick=1 ;;
    -h | --help) sed -n '2,19p' "$0"; exit 0 ;;
    *) echo "check.sh: unknown option '$arg' (use --quick or nothing)" >&2; exit 2 ;;
  esac
done
fuzz_seconds=$((quick ? 120 : 600))
jobs="$(nproc)"
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$HOME/.cache/atssim/pocl}"
# LeakSanitizer is off: its thread tracer crashes at exit on pocl's worker
# threads (README); ASan's memory checks and UBSan (fatal) stay on.
export ASAN_OPTIONS="detect_leaks=0" UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"

bash scripts/setup.sh check || exit 1

results=()
failed=0
step() {  # step NAME COMMAND...: runs it, records its status and time
  local name="$1" start rc
  shift
  echo "== check.sh: $name" >&2
  start=$(date +%s)
  "$@"
  rc=$?
  local took=$(($(date +%s) - start))
  if [ "$rc" -eq 0 ]; then
    results+=("$(printf '%-6s ok     %4d s' "$name" "$took")")
  else
    results+=("$(printf '%-6s FAILED %4d s (exit %d)' "$name" "$took" "$rc")")
    failed=1
  fi
  return "$rc"
}

format_check() {
  git ls-files -z '*.cpp' '*.hpp' '*.h' '*.c' '*.cl' | xargs -0 clang-format --dry-run --Werror
}

sanitizer_build() {
  cmake --preset debug -DATSSIM_BUILD_BENCHMARKS=OFF >/dev/null && cmake --build --preset debug -j "$jobs"
}

# One process per unit-test binary (no per-test start-up and device program
# builds), -w NoTests: a binary that runs no test fails.
quick_tests() {
  local rc=0 bin count=0
  for bin in build/debug/tests/*/test_*; do
    [ -f "$bin" ] && [ -x "$bin" ] || continue
    case "$bin" in */test_app) continue ;; esac
    count=$((count + 1))
    echo "-- $bin" >&2
    (cd build/debug && "$root/$bin" -w NoTests) || rc=1
  done
  if [ "$count" -lt 9 ]; then
    echo "check.sh: only $count unit-test binaries under build/debug/tests (expected every stage's)" >&2
    rc=1
  fi
  echo "-- build/debug/tests/app/test_app [fast]" >&2
  (cd build/debug && "$root/build/debug/tests/app/test_app" -w NoTests "[fast]") || rc=1
  return "$rc"
}

full_tests() {
  ctest --preset debug --output-junit "$root/build/debug/ctest-junit.xml"
  local rc=$?
  /usr/bin/python3 scripts/suite_summary.py build/debug/ctest-junit.xml
  return "$rc"
}

fuzz() {
  bash scripts/fuzz_scene.sh -1 -max_total_time="$fuzz_seconds" -timeout=30
}

changed_files() {
  local base="${CHECK_BASE:-}"
  if [ -z "$base" ]; then
    local main_ref=""
    for ref in main origin/main; do
      if git rev-parse -q --verify "$ref^{commit}" >/dev/null; then
        main_ref="$ref"
        break
      fi
    done
    if [ -n "$main_ref" ]; then base="$(git merge-base HEAD "$main_ref")"; fi
    if [ -z "$base" ] || [ "$base" = "$(git rev-parse HEAD)" ]; then base="HEAD~1"; fi
  fi
  echo "check.sh: clang-tidy over the C++ files changed since $base" >&2
  git diff --name-only --diff-filter=d "$base" -- '*.cpp' '*.hpp' '*.h'
}

tidy() {
  local db="build/debug/compile_commands.json" files=() f cpp
  [ -f "$db" ] || { echo "check.sh: $db is missing (the build step failed?)" >&2; return 1; }
  while IFS= read -r f; do
    case "$f" in
      kernels/* | tests/fuzz/*) continue ;;  # OpenCL C headers; the fuzzer is built by clang itself
      *.cpp) cpp="$f" ;;
      *) cpp="${f%.*}.cpp" ;;  # a header: checked through its own .cpp
    esac
    [ -f "$cpp" ] && grep -q "\"$root/$cpp\"" "$db" && files+=("$cpp")
  done < <(changed_files)
  if [ ${#files[@]} -eq 0 ]; then
    echo "check.sh: no changed C++ file to check" >&2
    return 0
  fi
  mapfile -t files < <(printf '%s\n' "${files[@]}" | sort -u)
  echo "check.sh: clang-tidy ${files[*]}" >&2
  clang-tidy -p build/debug --quiet "${files[@]}"
}

started=$(date +%s)
step format format_check
step build sanitizer_build
if [ "$quick" -eq 1 ]; then step tests quick_tests; else step tests full_tests; fi
step fuzz fuzz
step tidy tidy
echo "== check.sh$([ "$quick" -eq 1 ] && echo " --quick"): $(($(date +%s) - started)) s, commit $(git rev-parse --short HEAD)" >&2
printf '   %s\n' "${results[@]}" >&2
exit "$failed"
