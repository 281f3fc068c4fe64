#!/usr/bin/env bash
# Runs the add-on's headless Blender suite (tests/blender) inside every Blender release PyPI serves as a
# `bpy` wheel (Blender as a Python module), as listed with their pins in scripts/blender_versions.txt.
#
#   bash scripts/test_blender_versions.sh [--ci] [RELEASE...]   e.g. 4.5.15 5.3.0 (default: every listed release)
#
# --ci: CI's budget: in a release whose CI column in the versions file says `smoke`, the suite without the
# modules of its `smoke-leaves-out` line (the summary line says "(smoke)").
#
# Per release: a venv of the listed pyenv Python with the pinned bpy, numpy and pytest, cached under
# ${XDG_CACHE_HOME:-$HOME/.cache}/gauss_stylization/bpy-<release> and reused while its pins match; the
# gauss_core wheel for that Python (scripts/build_wheel.sh) in the extension zip (scripts/package_addon.py),
# made once per Python ABI in build-bpy-zips/cpXY; the extension installed by that Blender itself
# (bpy.ops.extensions.package_install_files, which also installs the wheel) into a throw-away Blender
# user folder; then the suite against that installed copy, run by the venv's Python after `import bpy`
# (tests/blender/run_headless.py); in the newest release also every snippet of docs/scripting.md and
# docs/baking.md (tests/blender/doc_snippets.py). Logs: build-bpy-logs/.
# Prints one line per release and a summary:
#   blender 4.5.15 (Python 3.11.7, numpy 1.26.4): N passed, 0 failed, K skipped
#   blender versions: N passed, M failed
# Exits non-zero if any release fails or if fewer than two releases ran.
set -uo pipefail
cd "$(dirname "$0")/.."
repo="$PWD"
versions_file=scripts/blender_versions.txt
cache="${XDG_CACHE_HOME:-$HOME/.cache}/gauss_stylization"
pyenv_root="${PYENV_ROOT:-$HOME/.pyenv}"
logs="$repo/build-bpy-logs"
mkdir -p "$cache" "$logs"

fail() { echo "test_blender_versions: $*" >&2; exit 1; }

[ -f "$versions_file" ] || fail "$versions_file is missing"
mapfile -t releases < <(awk '$1 == "release" {print $2, $3, $4, $5}' "$versions_file")
read -r -a smoke_leaves_out < <(awk '$1 == "smoke-leaves-out" {$1 = ""; print}' "$versions_file")
mapfile -t installs < <(awk '$1 == "install" {print $2}' "$versions_file")
constraints="$cache/bpy-constraints.txt"
awk '$1 == "constrain" {print $2}' "$versions_file" > "$constraints"
[ ${#releases[@]} -gt 0 ] || fail "no release lines in $versions_file"
for module in "${smoke_leaves_out[@]}"; do
  [ -f "tests/blender/$module" ] || fail "smoke-leaves-out names tests/blender/$module, which does not exist"
done

ci=0
if [ "${1:-}" = --ci ]; then ci=1; shift; fi
wanted=("$@")
is_wanted() {
  [ ${#wanted[@]} -eq 0 ] && return 0
  local w; for w in "${wanted[@]}"; do [ "$w" = "$1" ] && return 0; done; return 1
}
for w in "${wanted[@]}"; do
  printf '%s\n' "${releases[@]}" | awk '{print $1}' | grep -qxF "$w" || fail "$w is not a release of $versions_file"
done

# make_venv RELEASE PYTHON NUMPY: the release's venv, (re)made unless its stamp holds the same pins.
make_venv() {
  local release="$1" python_version="$2" numpy="$3"
  local venv="$cache/bpy-$release" base="$pyenv_root/versions/$python_version/bin/python3"
  local pins
  pins="$(printf 'bpy==%s python %s numpy==%s\n%s\n%s\n' "$release" "$python_version" "$numpy" \
          "${installs[*]}" "$(cat "$constraints")")"
  if [ "$(cat "$venv/pins.txt" 2>/dev/null)" = "$pins" ]; then
    return 0
  fi
  [ -x "$base" ] || { echo "Python $python_version is missing: $base (install it with pyenv install $python_version)"; return 1; }
  rm -rf "$venv"
  "$base" -m venv "$venv" || return 1
  # --no-compile: pip's byte-compiling of bpy's 1.1 GB took a third of a cold venv's time (34 s against
  # 21 s here), and `import bpy` takes as long without it.
  "$venv/bin/python" -m pip install -q --no-compile -c "$constraints" \
      "bpy==$release" "numpy==$numpy" "${installs[@]}" || return 1
  printf '%s\n' "$pins" > "$venv/pins.txt"  # last: an interrupted install is redone next time
}

# The staged add-on tree scripts/package_addon.py packages from (its core_facts.json: the solver's
# defaults and limits, which the add-on reads when its module cannot load), built once per run.
facts_built=""
build_facts() {
  local build="$repo/build-bpy-facts" tools_venv
  [ -n "$facts_built" ] && return 0
  tools_venv="$(bash scripts/install_deps.sh --print-tools-venv 2> "$logs/build-facts.log" | tail -n1)" &&
    cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release -DGAUSS_BUILD_TESTS=OFF -DGAUSS_BUILD_BENCH=OFF \
      -Dpybind11_DIR="$("$tools_venv/bin/python" -m pybind11 --cmakedir)" >> "$logs/build-facts.log" 2>&1 &&
    cmake --build "$build" -j2 --target addon >> "$logs/build-facts.log" 2>&1 || {
      echo "the add-on build failed: $logs/build-facts.log"; tail -20 "$logs/build-facts.log"; return 1; }
  facts_built=1
}

# extension_zip PYTHON_VERSION ABI: sets zip to the linux-x64 extension zip holding the gauss_core wheel
# for that Python (scripts/build_wheel.sh, scripts/package_addon.py), made once per ABI in a run.
declare -A zips=()
extension_zip() {
  local python_version="$1" abi="$2" out="$repo/build-bpy-zips/$2" wheel
  if [ -z "${zips[$abi]:-}" ]; then
    build_facts || return 1
    rm -rf "$out" && mkdir -p "$out/wheel"
    wheel="$(bash scripts/build_wheel.sh "$pyenv_root/versions/$python_version/bin/python3" "$out/wheel" \
             2> "$logs/wheel-$abi.log" | tail -n1)" && [ -f "$wheel" ] || {
      echo "the $abi wheel build failed: $logs/wheel-$abi.log"; tail -20 "$logs/wheel-$abi.log"; return 1; }
    python3 scripts/package_addon.py "$repo/build-bpy-facts" "$out" --wheels "$wheel" > "$logs/package-$abi.log" 2>&1 || {
      echo "packaging the $abi extension failed: $logs/package-$abi.log"; cat "$logs/package-$abi.log"; return 1; }
    zips[$abi]="$(ls "$out"/gauss_stylization-*-extension-"$abi"-linux_x64.zip 2>/dev/null | head -1)"
    [ -f "${zips[$abi]}" ] || { echo "no $abi linux-x64 extension zip in $out"; return 1; }
  fi
  zip="${zips[$abi]}"
}

passed=0
failed=0
newest="$(printf '%s\n' "${releases[@]}" | awk '{print $1}' | sort -V | tail -n1)"
for line in "${releases[@]}"; do
  read -r release python_version numpy ci_suite <<< "$line"
  is_wanted "$release" || continue
  log="$logs/$release.log"
  : > "$log"
  venv="$cache/bpy-$release"
  if ! make_venv "$release" "$python_version" "$numpy" >> "$log" 2>&1; then
    echo "blender $release: its venv could not be made ($log)"; tail -5 "$log"; failed=$((failed + 1)); continue
  fi
  abi="cp$(echo "$python_version" | cut -d. -f1,2 | tr -d .)"
  if ! extension_zip "$python_version" "$abi"; then failed=$((failed + 1)); continue; fi
  # A throw-away Blender user folder: Blender installs the extension (and the wheel) there, as
  # Preferences > Get Extensions > Install from Disk does; the suite then tests that installed copy.
  user="$(mktemp -d "${TMPDIR:-/tmp}/gauss-blender-user.XXXXXX")"
  export BLENDER_USER_CONFIG="$user/config" BLENDER_USER_SCRIPTS="$user/scripts" \
         BLENDER_USER_DATAFILES="$user/datafiles" BLENDER_USER_RESOURCES="$user"
  if ! addon_dir="$("$venv/bin/python" tests/blender/install_extension.py "$zip" 2>> "$log" | tail -1)" \
      || [ ! -d "$addon_dir/gauss_stylization" ]; then
    echo "blender $release: the extension could not be installed ($log)"; tail -5 "$log"; failed=$((failed + 1))
    rm -rf "$user"; continue
  fi
  report="$user/junit.xml"
  leave_out=() suite_note=""
  if [ "$ci" = 1 ] && [ "$ci_suite" = smoke ]; then
    for module in "${smoke_leaves_out[@]}"; do leave_out+=("--ignore=$repo/tests/blender/$module"); done
    suite_note=" (smoke)"
  fi
  GAUSS_ADDON_DIR="$addon_dir" "$venv/bin/python" tests/blender/run_headless.py -- "$repo/build-bpy-facts" \
      -q --junitxml="$report" "${leave_out[@]}" >> "$log" 2>&1
  status=$?
  # Its last line: bpy 4.2 to 4.4 print "Unable to initialise audio" on import.
  summary="$("$venv/bin/python" tests/blender/release_line.py "$report" "$status" 2>> "$log" | tail -n1)"
  echo "$summary$suite_note"
  # In the newest release, every snippet of docs/scripting.md and docs/baking.md, against the installed
  # extension (once: the snippets use nothing that differs between the 5.x releases the suite covers).
  if [ "$release" = "$newest" ] && [ "$status" -eq 0 ]; then
    snippets_log="$logs/$release-doc-snippets.log"
    (cd tests/blender && "$venv/bin/python" doc_snippets.py "$zip") > "$snippets_log" 2>&1 || status=$?
    snippets_line="$(grep '^doc snippets: ' "$snippets_log" | tail -n1)"
    echo "  ${snippets_line:-doc snippets: no summary} (bpy $release; $snippets_log)"
    [ -n "$snippets_line" ] || status=1
  fi
  if [ "$status" -eq 0 ] && [[ "$summary" == *" 0 failed, "* ]]; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    grep -E '^(FAILED|ERROR) ' "$log" | head -40
    echo "  log: $log"
  fi
  rm -rf "$user"
done

echo "blender versions: $passed passed, $failed failed"
if [ $((passed + failed)) -lt 2 ]; then
  echo "test_blender_versions: fewer than two releases ran" >&2
  exit 1
fi
exit $(( failed > 0 ))
