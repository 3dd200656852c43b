#!/usr/bin/env bash
# The reliability checks beyond the test suite (docs/reliability.md).
#
#   bash scripts/check.sh --quick   # CI (.ci/run, after the test command)
#   bash scripts/check.sh           # before an issue is called resolved: the whole suite
#
# Steps (each is run, then all are reported; any failure fails the script):
#   format  clang-format over every C, C++ and OpenCL file of the repository (check only)
#   build   the sanitizer build (ASan + UBSan, no benchmarks): --quick: the preset
#           `sanitize-quick` (-O0, build/sanitize-quick), only the target check_quick
#           (the libraries, atssim and the test binaries tests/quick_tests.txt names);
#           full: the preset `sanitize` (-O1, build/sanitize), everything.
#           The fuzzer (scripts/fuzz_scene.sh --build-only) is built beside it
#   tests   --quick: each binary of tests/quick_tests.txt, one process each, without
#           the cases tagged [slow] (test_app_core: only those tagged [fast], the app
#           layer through the sanitized binary); full: `ctest --preset sanitize` (the whole suite)
#   fuzz    libFuzzer on the scene parser (scripts/fuzz_scene.sh) from the kept corpus
#           tests/fuzz/corpus: 2 minutes (--quick) or 10; one core, beside tidy
#   tidy    clang-tidy (.clang-tidy's check set) over the C++ files the change touched,
#           at most 8 of them and 240 s (--quick; full: 24 and 1200 s), the files
#           left unchecked named on stderr: relative to the
#           merge-base with main, or to HEAD~1 on main itself (CI); CHECK_BASE=<commit>
#           sets it. A shallow clone is deepened from its remote; with no base at
#           all, --quick notes "no file checked" in its summary and the full check fails
# Installs what it needs first (`scripts/setup.sh check`: clang, clang-tidy,
# clang-format, libclang-rt-dev).
set -uo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"

quick=0
for arg in "$@"; do
  case "$arg" in
    --quick) quick=1 ;;
    -h | --help) sed -n '2,/^set -uo/p' "$0" | sed '$d'; exit 0 ;;
    *) echo "check.sh: unknown option '$arg' (use --quick or nothing)" >&2; exit 2 ;;
  esac
done
fuzz_seconds=$((quick ? 120 : 600))
preset=$([ "$quick" -eq 1 ] && echo sanitize-quick || echo sanitize)
bdir="build/$preset"
jobs="$(nproc)"
# clang-tidy takes 10-30 s a file here (25 s for lib/device/fused_runner.cpp
# beside a build): a big merge would take an hour. --quick checks at most 8
# changed files, starts none after 240 s, stops any after 120 s; the full run
# 24 files and 1200 s. What is left unchecked is named on stderr.
tidy_limit=$((quick ? 8 : 24))
tidy_seconds=$((quick ? 240 : 1200))
tidy_file_seconds=120
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
  cmake --preset "$preset" >/dev/null || return 1
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
  local rc=0 bin filter count=0 list=$bdir/quick_tests.txt
  [ -f "$list" ] || { echo "check.sh: $list is missing (the build step failed?)" >&2; return 1; }
  while IFS=$'\t' read -r bin filter; do
    [ -n "$bin" ] || continue
    count=$((count + 1))
    if [ ! -x "$bin" ]; then
      echo "check.sh: $bin was not built" >&2
      rc=1
      continue
    fi
    if [ -z "$filter" ]; then
      filter="~[slow]"
      "$bin" --list-test-names-only "[slow]" 2>/dev/null | grep . | sed 's/^/   left out ([slow]; the full check and ctest run it): /' >&2
    fi
    echo "-- $bin $filter" >&2
    local start=$(date +%s)
    (cd "$bdir" && "$bin" -w NoTests "$filter") || rc=1
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

# The fuzzer (one process, niced) runs beside clang-tidy (one file at a
# time): each takes one core. Its output goes to build/fuzz.log; the fuzz
# step waits for it and prints the log's end.
fuzz_pid=""
fuzz_started=0
start_fuzz() {
  if [ -n "$fuzz_build_pid" ] && ! wait "$fuzz_build_pid"; then
    cat build/fuzz-build.log >&2
    echo "check.sh: building the fuzzer failed (above)" >&2
    return 1
  fi
  fuzz_started=$(date +%s)
  bash scripts/fuzz_scene.sh -1 -max_total_time="$fuzz_seconds" -timeout=30 >build/fuzz.log 2>&1 &
  fuzz_pid=$!
}
fuzz() {
  [ -n "$fuzz_pid" ] || return 1  # the fuzzer was not built (above)
  wait "$fuzz_pid"
  local rc=$?
  tail -n 40 build/fuzz.log >&2
  echo "check.sh: the fuzzer ran $(($(date +%s) - fuzz_started)) s (exit $rc; whole log: build/fuzz.log)" >&2
  return "$rc"
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
  # A shallow clone may lack the base: deepen it from its remote if it has
  # one; otherwise nothing can say what changed, and tidy says so.
  if ! git rev-parse -q --verify "$base^{commit}" >/dev/null && [ -f "$(git rev-parse --git-dir)/shallow" ]; then
    git fetch -q --deepen=50 2>/dev/null || true
  fi
  if ! git rev-parse -q --verify "$base^{commit}" >/dev/null; then
    echo "check.sh: clang-tidy has no base: '$base' is not in this clone (shallow, or one commit);" \
      "clone with history or set CHECK_BASE=<commit>" >&2
    return 3
  fi
  echo "check.sh: clang-tidy over the C++ files changed since $base" >&2
  git diff --name-only --diff-filter=d "$base" -- '*.cpp' '*.hpp' '*.h'
}

tidy() {
  local db="$bdir/compile_commands.json" files=() f cpp
  [ -f "$db" ] || { echo "check.sh: $db is missing (the build step failed?)" >&2; return 1; }
  # changed_files's status 3: no base to compare with (named on stderr).
  # --quick (CI) goes on and notes it in the summary; the full check fails.
  local changed listed
  changed="$(changed_files)"
  listed=$?
  if [ "$listed" -eq 3 ]; then
    tidy_note="tidy: no base commit in this clone, no file checked"
    [ "$quick" -eq 1 ] && return 0
    return 1
  fi
  while IFS= read -r f; do
    [ -n "$f" ] || continue
    case "$f" in
      kernels/* | tests/fuzz/*) continue ;;  # OpenCL C headers; the fuzzer is built by clang itself
      *.cpp) cpp="$f" ;;
      *) cpp="${f%.*}.cpp" ;;  # a header: checked through its own .cpp
    esac
    [ -f "$cpp" ] && grep -q "\"$root/$cpp\"" "$db" && files+=("$cpp")
  done <<<"$changed"
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
  # One file at a time: no file is started after tidy_seconds, and none runs
  # longer than tidy_file_seconds; the files left unchecked are named.
  local rc=0 start now i skipped=() status
  start=$(date +%s)
  for ((i = 0; i < ${#files[@]}; i++)); do
    now=$(date +%s)
    if [ $((now - start)) -ge "$tidy_seconds" ]; then
      skipped=("${files[@]:$i}")
      break
    fi
    echo "check.sh: clang-tidy ${files[$i]}" >&2
    timeout "$tidy_file_seconds" clang-tidy -p "$bdir" --quiet "${files[$i]}"
    status=$?
    if [ "$status" -eq 124 ]; then
      echo "check.sh: clang-tidy stopped on ${files[$i]} after $tidy_file_seconds s (not checked)" >&2
      skipped+=("${files[$i]}")
    elif [ "$status" -ne 0 ]; then
      rc=1
    fi
  done
  echo "check.sh: clang-tidy checked $((${#files[@]} - ${#skipped[@]})) of ${#files[@]} files in $(($(date +%s) - start)) s" >&2
  if [ ${#skipped[@]} -gt 0 ]; then
    echo "check.sh: clang-tidy skipped (time limit $tidy_seconds s): ${skipped[*]}" >&2
  fi
  return "$rc"
}

started=$(date +%s)
step format format_check
step build sanitizer_build
if [ "$quick" -eq 1 ]; then step tests quick_tests; else step tests full_tests; fi
start_fuzz
tidy_note=""
step tidy tidy
[ -n "$tidy_note" ] && results+=("       ($tidy_note)")
step fuzz fuzz
echo "== check.sh$([ "$quick" -eq 1 ] && echo " --quick"): $(($(date +%s) - started)) s, commit $(git rev-parse --short HEAD)" >&2
printf '   %s\n' "${results[@]}" >&2
exit "$failed"
