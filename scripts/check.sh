#!/usr/bin/env bash
# The reliability checks beyond the test suite (docs/reliability.md).
#
#   bash scripts/check.sh --quick   # CI (.ci/run, after the test command)
#   bash scripts/check.sh           # before an issue is called resolved: the whole suite
#
# Steps (each is run, then all are reported; any failure fails the script):
#   format  clang-format over every C, C++ and OpenCL file of the repository (check only)
#   build   the sanitizer build (ASan + UBSan at -O1, no benchmarks): the `sanitize`
#           preset, build/sanitize; --quick: only the target check_quick (the libraries
#           and the unit-test binaries tests/quick_tests.txt names); full: everything.
#           The fuzzer (scripts/fuzz_scene.sh --build-only) is built beside it
#   tests   --quick: each binary of tests/quick_tests.txt, one process each, without
#           the cases tagged [slow]; full: `ctest --preset sanitize` (the whole suite)
#   fuzz    libFuzzer on the scene parser (scripts/fuzz_scene.sh) from the kept corpus
#           tests/fuzz/corpus: 2 minutes (--quick) or 10
#   tidy    clang-tidy (.clang-tidy's check set) over the C++ files the change touched,
#           at most 24 of them (the others are named on stderr): relative to the
#           merge-base with main, or to HEAD~1 on main itself (CI); CHECK_BASE=<commit>
#           sets it
# Installs what it needs first (`scripts/setup.sh check`: clang, clang-tidy,
# clang-format, libclang-rt-dev).
set -uo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"

quick=0
for arg in "$@"; do
  case "$arg" in
    --quick) quick=1 ;;
    -h | --help) sed -n '2,23p' "$0"; exit 0 ;;
    *) echo "check.sh: unknown option '$arg' (use --quick or nothing)" >&2; exit 2 ;;
  esac
done
fuzz_seconds=$((quick ? 120 : 600))
jobs="$(nproc)"
tidy_limit=24  # clang-tidy takes tens of seconds a file here: a big merge would take an hour
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

# The fuzzer is built by clang beside the sanitizer build (gcc): its ~10
# files fill the cores while ninja links.
fuzz_build_pid=""
sanitizer_build() {
  mkdir -p build
  bash scripts/fuzz_scene.sh --build-only >build/fuzz-build.log 2>&1 &
  fuzz_build_pid=$!
  cmake --preset sanitize >/dev/null || return 1
  if [ "$quick" -eq 1 ]; then
    cmake --build --preset check_quick -j "$jobs"
  else
    cmake --build --preset sanitize -j "$jobs"
  fi
}

# One process per unit-test binary (no per-test start-up and device program
# builds), -w NoTests: a binary that runs no test fails. Cases tagged [slow]
# (minutes under ASan) are left to the full run and to ctest.
quick_tests() {
  local rc=0 bin count=0 list=build/sanitize/quick_tests.txt
  [ -f "$list" ] || { echo "check.sh: $list is missing (the build step failed?)" >&2; return 1; }
  while IFS= read -r bin; do
    count=$((count + 1))
    if [ ! -x "$bin" ]; then
      echo "check.sh: $bin was not built" >&2
      rc=1
      continue
    fi
    echo "-- $bin ~[slow]" >&2
    local start=$(date +%s)
    (cd build/sanitize && "$bin" -w NoTests "~[slow]") || rc=1
    echo "-- $(basename "$bin"): $(($(date +%s) - start)) s" >&2
  done <"$list"
  if [ "$count" -eq 0 ]; then
    echo "check.sh: $list names no binary" >&2
    rc=1
  fi
  return "$rc"
}

full_tests() {
  ctest --preset sanitize --output-junit "$root/build/sanitize/ctest-junit.xml"
  local rc=$?
  /usr/bin/python3 scripts/suite_summary.py build/sanitize/ctest-junit.xml
  return "$rc"
}

fuzz() {
  if [ -n "$fuzz_build_pid" ] && ! wait "$fuzz_build_pid"; then
    cat build/fuzz-build.log >&2
    echo "check.sh: building the fuzzer failed (above)" >&2
    return 1
  fi
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
  local db="build/sanitize/compile_commands.json" files=() f cpp
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
  if [ ${#files[@]} -gt "$tidy_limit" ]; then
    echo "check.sh: ${#files[@]} changed C++ files; clang-tidy checks the first $tidy_limit and skips:" \
      "${files[*]:$tidy_limit}" >&2
    files=("${files[@]:0:$tidy_limit}")
  fi
  echo "check.sh: clang-tidy ${files[*]}" >&2
  clang-tidy -p build/sanitize --quiet "${files[@]}"
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
