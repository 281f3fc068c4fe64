#!/usr/bin/env bash
# Builds the gauss_core wheel (pyproject.toml: scikit-build-core + CMake) for one Python and checks its
# platform tag with auditwheel.
#
#   bash scripts/build_wheel.sh PYTHON_EXE OUT_DIR
#
# PYTHON_EXE: the Python the module is for (e.g. ~/.pyenv/versions/3.13.0/bin/python3; Blender 4.2 to 5.0
# run 3.11, 5.1 and later 3.13). OUT_DIR: where the wheel goes, created if needed.
# Output: OUT_DIR/gauss_core-<version>-cpXY-cpXY-manylinux_2_28_x86_64.whl, its path printed as the LAST
# line of stdout. Exits non-zero (with auditwheel's reason) if the module needs anything beyond
# manylinux_2_28 (glibc 2.28, what official Blender builds target).
#
# Repeat runs are incremental: build-wheel-cpXY/ (ignored by git) keeps a venv of PYTHON_EXE with the build
# requirements pinned in pyproject.toml (remade when a pin changes) and a CMake build tree, per interpreter.
set -euo pipefail
if [ $# -ne 2 ]; then sed -n '5,6p' "$0" | sed 's/^# *//' >&2; exit 2; fi
python_exe="$1"
out_dir="$(mkdir -p "$2" && cd "$2" && pwd)"
cd "$(dirname "$0")/.."
repo="$PWD"

tag="$("$python_exe" -c 'import sys; print("cp%d%d" % sys.version_info[:2])')" \
  || { echo "build_wheel.sh: cannot run $python_exe" >&2; exit 2; }
tools_venv="$(bash scripts/install_deps.sh --print-tools-venv | tail -n1)"
work="$repo/build-wheel-$tag"
# One build venv and CMake tree per interpreter (Debian's and pyenv's 3.11 both make cp311 wheels; sharing
# a tree would rebuild it whenever the other one was used last).
real_python="$(readlink -f "$("$python_exe" -c 'import sys; print(sys.executable)')")"
interpreter_id="$(printf '%s' "$real_python" | sha1sum | cut -c1-8)"
build_venv="$work/venv-$interpreter_id"
mkdir -p "$work"
exec 9> "$work/$interpreter_id.lock"
flock 9  # two builds for one interpreter (e.g. the bpy matrix and the tests) take turns in its tree
requires="$("$tools_venv/bin/python" -c '
import tomllib
print("\n".join(tomllib.load(open("pyproject.toml", "rb"))["build-system"]["requires"]))')"
if [ "$(cat "$build_venv/requires.txt" 2>/dev/null)" != "$requires" ] \
    || [ "$(readlink -f "$build_venv/bin/python")" != "$real_python" ]; then
  echo "== build venv for $tag: $build_venv" >&2
  rm -rf "$build_venv"
  "$python_exe" -m venv "$build_venv"
  printf '%s\n' "$requires" > "$build_venv/requirements.in"
  "$build_venv/bin/python" -m pip install -q --disable-pip-version-check -r "$build_venv/requirements.in" >&2
  printf '%s\n' "$requires" > "$build_venv/requires.txt"
fi

# The backend's wheel (tagged linux_x86_64), then auditwheel's check and retag.
raw="$work/raw-$interpreter_id"
rm -rf "$raw" && mkdir -p "$raw"
CMAKE_BUILD_PARALLEL_LEVEL="${CMAKE_BUILD_PARALLEL_LEVEL:-2}" "$build_venv/bin/python" -m pip wheel -q --disable-pip-version-check --no-build-isolation --no-deps \
  --config-settings=build-dir="$work/cmake-$interpreter_id" --config-settings=cmake.build-type=Release \
  -w "$raw" "$repo" >&2
built=("$raw"/gauss_core-*.whl)
if [ ${#built[@]} -ne 1 ] || [ ! -f "${built[0]}" ]; then
  echo "build_wheel.sh: expected one wheel in $raw, found: ${built[*]}" >&2; exit 1
fi
"$tools_venv/bin/auditwheel" show "${built[0]}" >&2
name="$(basename "${built[0]}")"
rm -f "$out_dir/${name%-linux_x86_64.whl}-manylinux_2_28_x86_64.whl"
PATH="$tools_venv/bin:$PATH" "$tools_venv/bin/auditwheel" repair --plat manylinux_2_28_x86_64 \
  --only-plat -w "$out_dir" "${built[0]}" >&2
wheel="$out_dir/${name%-linux_x86_64.whl}-manylinux_2_28_x86_64.whl"
if [ ! -f "$wheel" ]; then
  echo "build_wheel.sh: auditwheel did not write $wheel" >&2; exit 1
fi
echo "$wheel"
