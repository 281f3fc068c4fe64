#!/usr/bin/env bash
# The module's own pytest suite (tests/python) against numpy 2, with the gauss_core wheel installed the
# way Blender's extension system installs it (a top-level module in site-packages).
#
#   bash scripts/test_numpy2.sh [PYTHON_EXE... | --newest]
#
# Default Pythons: pyenv's 3.11.7 (Blender 4.2 to 5.0's Python; PyPI's bpy 4.2 to 4.4 let pip bring
# numpy 2 beside it) and 3.13.0 (Blender 5.1 and later, which bundle numpy 2); --newest: 3.13.0 only.
# For each, a venv build-wheel-cpXY/numpy2-venv with numpy and pytest pinned in packaging/numpy2-test-requirements.txt
# (remade when a pin changes), the wheel of scripts/build_wheel.sh installed into it, then pytest. The
# packaging tests, which read the main build tree, run in the main suite only (scripts/run_tests.sh);
# tests/python/test_numpy_mismatch.py runs here, where numpy 2 is.
# Prints one line per Python: "numpy2 suite, Python 3.11.7, numpy 2.3.5: N passed, 0 failed, 0 skipped"
# (pytest's own summary above it; its log in build-wheel-cpXY/numpy2-pytest.log) and exits non-zero if
# any run fails.
set -uo pipefail
cd "$(dirname "$0")/.."
repo="$PWD"
defaults=("$HOME/.pyenv/versions/3.11.7/bin/python3" "$HOME/.pyenv/versions/3.13.0/bin/python3")
if [ $# -eq 0 ]; then
  set -- "${defaults[@]}"
elif [ "$1" = --newest ]; then
  set -- "${defaults[-1]}"
fi
requirements="$repo/packaging/numpy2-test-requirements.txt"
pins="$(grep -v '^\s*\(#\|$\)' "$requirements")"
[ -f build/addon/gauss_stylization/core_facts.json ] || bash scripts/build.sh build >&2 || exit 1

failed=0
lines=()
for python_exe in "$@"; do
  if [ ! -x "$python_exe" ]; then
    lines+=("numpy2 suite: $python_exe is missing (pyenv install it)"); failed=1; continue
  fi
  tag="$("$python_exe" -c 'import sys; print("cp%d%d" % sys.version_info[:2])')"
  work="$repo/build-wheel-$tag"
  venv="$work/numpy2-venv"
  if [ "$(cat "$venv/pins.txt" 2>/dev/null)" != "$pins" ]; then
    rm -rf "$venv"
    "$python_exe" -m venv "$venv" && "$venv/bin/python" -m pip install -q --disable-pip-version-check \
      -r "$requirements" && printf '%s' "$pins" > "$venv/pins.txt" || { lines+=("numpy2 suite, $tag: venv failed"); failed=1; continue; }
  fi
  wheel="$(bash scripts/build_wheel.sh "$python_exe" "$work/dist" 2> "$work/build_wheel.log" | tail -n1)"
  if [ ! -f "$wheel" ]; then lines+=("numpy2 suite, $tag: the wheel build failed ($work/build_wheel.log)"); failed=1; continue; fi
  "$venv/bin/python" -m pip install -q --disable-pip-version-check --force-reinstall --no-deps "$wheel" || {
    lines+=("numpy2 suite, $tag: installing $wheel failed"); failed=1; continue; }
  # The tests read the facts file of the main build (the same source); no build tree's module may
  # shadow the installed wheel, so GAUSS_BUILD_DIR is a tree that has the facts only.
  tree="$work/numpy2-tree"
  mkdir -p "$tree/addon/gauss_stylization"
  cp build/addon/gauss_stylization/core_facts.json "$tree/addon/gauss_stylization/"
  log="$work/numpy2-pytest.log"
  (cd "$work" && GAUSS_BUILD_DIR="$tree" "$venv/bin/python" -m pytest -q -p no:cacheprovider "$repo/tests/python" \
      --ignore="$repo/tests/python/test_packaging.py" --ignore="$repo/tests/python/test_module_reach.py" \
      --ignore="$repo/tests/python/test_release_workflow.py") \
      2>&1 | tee "$log" | tail -n 3
  status=${PIPESTATUS[0]}
  versions="$("$venv/bin/python" -c 'import platform, numpy; print("Python %s, numpy %s" % (platform.python_version(), numpy.__version__))')"
  last="$(tail -n1 "$log")"
  count() { grep -o "[0-9]* $1" <<< "$last" | cut -d' ' -f1 || true; }
  lines+=("numpy2 suite, $versions: $(count passed | grep . || echo 0) passed, $(( $(count failed | grep . || echo 0) + $(count error | grep . || echo 0) )) failed, $(count skipped | grep . || echo 0) skipped")
  [ "$status" -eq 0 ] || failed=1
done
printf '%s\n' "${lines[@]}"
exit "$failed"
