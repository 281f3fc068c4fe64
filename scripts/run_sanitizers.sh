#!/usr/bin/env bash
# Builds the C++ tests with AddressSanitizer + UndefinedBehaviorSanitizer (LeakSanitizer included) in a
# clang tree of their own (scripts/sanitizer_tree.sh) and runs them through ctest with the solver on 2
# threads. Exits non-zero on any sanitizer report or test failure.
#
# usage: scripts/run_sanitizers.sh [--build-only] [BUILD_DIR]     (default: <repo>/build-asan; incremental)
# --build-only: configure and build, run nothing (the test command builds early, beside other parts).
set -euo pipefail

build_only=0
if [ "${1:-}" = --build-only ]; then build_only=1; shift; fi
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$repo/build-asan}"
jobs="${GAUSS_JOBS:-2}"

source "$repo/scripts/sanitizer_tree.sh"
configure_sanitizer_tree "$build" -DGAUSS_BUILD_TESTS=ON
cmake --build "$build" --target gauss_tests -j "$jobs"
[ "$build_only" = 0 ] || exit 0

# Every report is fatal (the build adds -fno-sanitize-recover=all; ASan and LSan abort or exit non-zero
# on their own). The thread pool (cpp/src/util/parallel.cpp) is reachable from a global, so LSan has
# nothing to report about it.
export OMP_NUM_THREADS=2
export ASAN_OPTIONS="abort_on_error=1:detect_leaks=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"

# The slow cases (tests/cpp/slow_tests.txt) run for minutes each under ASan; every code path they take
# also runs, on smaller meshes, in the cases that remain.
source "$repo/scripts/slow_cpp_tests.sh"

status=0
(cd "$build" && ctest --output-on-failure -j "$jobs" --timeout 600 -E "$SLOW_CPP_TESTS_REGEX") || status=$?

# Belt and braces: a report in a test that still passed (none should exist) fails the run too.
log="$build/Testing/Temporary/LastTest.log"
if [ -f "$log" ] && grep -qE "ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:|SUMMARY: UndefinedBehaviorSanitizer" "$log"; then
  echo "run_sanitizers.sh: sanitizer report in $log" >&2
  grep -nE "ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:" "$log" | head -20 >&2
  status=1
fi
if [ "$status" -eq 0 ]; then echo "run_sanitizers.sh: clean"; else echo "run_sanitizers.sh: FAILED" >&2; fi
exit "$status"
