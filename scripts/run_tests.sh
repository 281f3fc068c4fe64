#!/usr/bin/env bash
# Every test: C++ (ctest), the Python module (pytest), the Blender add-on headless and in a real
# window (xvfb), the C++ tests under ASan+UBSan, and a bounded fuzzing run. Exits non-zero if any
# part fails; a summary of all parts is printed last.
set -uo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh || exit 1
bash scripts/build.sh build || exit 1

results=()
failed=0
run_part() {  # name, command...
  local name="$1"; shift
  echo; echo "================ $name ================"
  if "$@"; then results+=("PASS  $name"); else results+=("FAIL  $name"); failed=$((failed + 1)); fi
}

export OMP_NUM_THREADS="${OMP_NUM_THREADS:-2}"
run_part "C++ tests (ctest)" ctest --test-dir build --output-on-failure
run_part "Python module (pytest)" env GAUSS_BUILD_DIR="$PWD/build" /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/python
run_part "Blender add-on, headless" \
  blender -b --factory-startup --python-exit-code 1 -P tests/blender/run_headless.py -- "$PWD/build"
run_part "Blender add-on, real window (xvfb)" bash tests/blender/run_windowed.sh "$PWD/build"
run_part "C++ tests under ASan+UBSan" bash scripts/run_sanitizers.sh build-asan
run_part "libFuzzer (60 s)" bash scripts/run_fuzz.sh 60

echo; echo "================ summary ================"
printf '%s\n' "${results[@]}"
passed=$(( ${#results[@]} - failed ))
echo "suites: $passed passed, $failed failed"
exit $(( failed > 0 ))
