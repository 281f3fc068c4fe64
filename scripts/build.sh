#!/usr/bin/env bash
# Configures (once) and builds the solver library, Python module, staged add-on, benchmark and C++
# tests in BUILD_DIR (default: build). Incremental: a second run only rebuilds what changed.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DGAUSS_BUILD_TESTS=ON
fi
cmake --build "$build" -j"$(nproc)"
