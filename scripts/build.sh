#!/usr/bin/env bash
# Configures (once) and builds the solver library, Python module, staged add-on, benchmark and C++
# tests in BUILD_DIR (default: build). Incremental: a second run only rebuilds what changed.
#   bash scripts/build.sh [BUILD_DIR]           everything (scripts/run_tests.sh)
#   bash scripts/build.sh [BUILD_DIR] --main    only what the main job needs: the module and the staged
#                                               add-on (scripts/run_main.sh); the C++ tests and the
#                                               benchmark are left to a later full build of the same tree
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
targets=()
case "${2:-}" in
  --main) targets=(--target addon) ;;
  "") ;;
  *) echo "usage: bash scripts/build.sh [BUILD_DIR] [--main]" >&2; exit 2 ;;
esac
# pybind11 is PyPI's, pinned in pyproject.toml, from the tools venv scripts/install_deps.sh keeps.
tools_venv="$(bash scripts/install_deps.sh --print-tools-venv | tail -n1)"
pybind11_dir="$("$tools_venv/bin/python" -m pybind11 --cmakedir)"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DGAUSS_BUILD_TESTS=ON -Dpybind11_DIR:PATH="$pybind11_dir"
elif ! grep -qxF "pybind11_DIR:PATH=$pybind11_dir" "$build/CMakeCache.txt"; then
  cmake "$build" -Dpybind11_DIR:PATH="$pybind11_dir"  # a tree configured with another pybind11
fi
cmake --build "$build" -j"$(nproc)" "${targets[@]}"
