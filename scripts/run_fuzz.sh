#!/usr/bin/env bash
# Builds the libFuzzer harness (clang; ASan + UBSan + LSan) in a build folder of its own
# (scripts/sanitizer_tree.sh), replays every
# input that ever crashed it (tests/fuzz/regressions/) and the seed corpus (tests/fuzz/corpus/), then
# fuzzes the solver for a bounded time on a temporary copy of the corpus. Exits non-zero on a crash, a
# sanitizer report, a violated contract (NaN out, unreferenced vertex moved, unexpected exception...;
# see tests/fuzz/fuzz_harness.h), a hang or running out of memory.
#
# A failing input is written to BUILD_DIR/artifacts/. Fix the bug, then keep the input as
# tests/fuzz/regressions/<short-name> (ctest replays it as well, via gauss_tests).
#
# usage: scripts/run_fuzz.sh [--build-only] [SECONDS=60] [BUILD_DIR=<repo>/build-fuzz]
# --build-only: configure and build the harness, run nothing (the test command builds early, beside
# other parts).
set -euo pipefail

build_only=0
if [ "${1:-}" = --build-only ]; then build_only=1; shift; fi
seconds="${1:-60}"
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${2:-$repo/build-fuzz}"
jobs="${GAUSS_JOBS:-2}"

source "$repo/scripts/sanitizer_tree.sh"
configure_sanitizer_tree "$build" -DGAUSS_BUILD_FUZZER=ON -DGAUSS_BUILD_TESTS=OFF
cmake --build "$build" --target fuzz_solver -j "$jobs"
[ "$build_only" = 0 ] || exit 0
fuzzer="$build/tests/fuzz/fuzz_solver"

export OMP_NUM_THREADS=2
export ASAN_OPTIONS="abort_on_error=1:detect_leaks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
mkdir -p "$build/artifacts"
common=(-rss_limit_mb=2048 -artifact_prefix="$build/artifacts/")
# A hang is an input that runs past the timeout. The seeds include deliberately long runs (*_long_run:
# thousands of steps, up to 27 s each here at load 9), and mutated inputs reach the harness's whole
# work budget too (a 120-vertex mesh's 4,000 rounds took 17 s here under load), so both timeouts leave
# room for a machine twice as slow: a known input or an ordinary long run must not count as a "hang",
# and a real hang runs past any of them.
replay_timeout=120 fuzz_timeout=60

# 1. Every input that ever crashed, and every seed: each runs once.
shopt -s nullglob
inputs=("$repo"/tests/fuzz/regressions/* "$repo"/tests/fuzz/corpus/*)
if [ "${#inputs[@]}" -gt 0 ]; then
  if ! "$fuzzer" "${common[@]}" -timeout="$replay_timeout" "${inputs[@]}" > "$build/replay.log" 2>&1; then
    cat "$build/replay.log" >&2
    echo "run_fuzz.sh: a regression or seed input fails (see above)" >&2
    exit 1
  fi
  echo "run_fuzz.sh: ${#inputs[@]} regression and seed inputs replayed cleanly"
fi

# 2. Fuzz for a bounded time on a scratch copy of the corpus (the repository's stays as it is), without
# the long runs: step 1 ran them, and at the fuzzing's timeout libFuzzer's first pass over its corpus
# would call them hangs.
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir "$work/corpus"
for seed in "$repo"/tests/fuzz/corpus/*; do
  case "$seed" in *_long_run) ;; *) cp "$seed" "$work/corpus/" ;; esac
done
status=0
"$fuzzer" "${common[@]}" -timeout="$fuzz_timeout" -max_total_time="$seconds" -max_len=2048 -print_final_stats=1 "$work/corpus" \
  > "$build/fuzz.log" 2>&1 || status=$?
grep -E "^#[0-9]+.*(DONE|pulse)|stat::number_of_executed_units|stat::peak_rss_mb" "$build/fuzz.log" | tail -4
if [ "$status" -ne 0 ]; then
  grep -vE "^#[0-9]+ " "$build/fuzz.log" | tail -60 >&2
  echo "run_fuzz.sh: the fuzzer failed (exit $status); the input is in $build/artifacts/" >&2
  exit "$status"
fi
echo "run_fuzz.sh: ${seconds}s of fuzzing, no failure"
