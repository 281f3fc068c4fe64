#!/usr/bin/env bash
# Measures the solver on a ~1M-face mesh (set-up time, time per step, peak memory) through gauss_core,
# under /usr/bin/time -v for the peak resident set size. Needs a built module in $GAUSS_BUILD_DIR/python
# (default <repo>/build; build it with cmake first).
#
# usage: scripts/measure_scale.sh [extra arguments for cpp/bench/measure_scale.py, e.g. --steps 10 --n 289]
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export GAUSS_BUILD_DIR="${GAUSS_BUILD_DIR:-$repo/build}"
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
status=0
/usr/bin/time -v /usr/bin/python3 "$repo/cpp/bench/measure_scale.py" "$@" 2> "$log" || status=$?
grep -E "Maximum resident set size|Elapsed \(wall clock\)" "$log" | sed 's/^\s*/time -v: /'
grep -vE "^\s+[A-Z].*: |^\s*Command being timed" "$log" >&2 || true
exit "$status"
