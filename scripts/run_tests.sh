#!/usr/bin/env bash
# The project's tests.
#   bash scripts/run_tests.sh          everything (the README's test command, and CI's): C++ (ctest), the
#                                      Python module (pytest, also against numpy 2), the quality matrix's
#                                      fast subset (scripts/quality_matrix.py --fast), the Blender add-on
#                                      headless and in a real window (xvfb, Debian's Blender 3.4.1), the
#                                      farm engines (a single-node Slurm, openjd-cli, Flamenco's job type), the
#                                      headless suite in every Blender release PyPI serves as a bpy wheel,
#                                      the Windows/macOS cross check, the C++ tests under ASan+UBSan, a
#                                      bounded fuzzing run
#   bash scripts/run_tests.sh --fast   the quick tier for a developer changing a file: ctest without its
#                                      slow cases, pytest, the quality matrix's fast subset, and the
#                                      headless Blender suite (a couple of minutes with a warm build)
# Exits non-zero if any part fails; a summary of all parts is printed last.
set -uo pipefail
cd "$(dirname "$0")/.."
fast=0
case "${1:-}" in
  --fast) fast=1 ;;
  "") ;;
  *) echo "usage: bash scripts/run_tests.sh [--fast]" >&2; exit 2 ;;
esac
bash scripts/install_deps.sh || exit 1
# One compile of each source for every tree that builds it with the same flags (the main build, the wheels
# for each Python, the pybind11 2.10 module of the numpy 2 suite): ccache serves the repeats.
export CMAKE_CXX_COMPILER_LAUNCHER=ccache CMAKE_C_COMPILER_LAUNCHER=ccache
bash scripts/build.sh build || exit 1

# The slow C++ cases (tests/cpp/slow_tests.txt), which the fast tier leaves to the full run.
source scripts/slow_cpp_tests.sh

# The last three parts' own trees (the cross check's, the sanitizer tree, the fuzzing tree) are built
# from here on at the lowest priority, a lane beside the parts before them: those run one test, one
# Blender or one wheel build at a time and often leave a core idle, and a nice-19 build takes only what
# they leave. The cross check's Debian packages are installed first, here, so that no apt-get runs
# beside the tests. Each part still builds (incrementally) and reports its own build's failure; the
# lane says which of its builds failed. In a session of its own (setsid), so that an interrupted run
# stops it too instead of leaving it building.
if [ $fast -eq 0 ]; then
  bash scripts/cross_check.sh --install-only || exit 1
  prebuild_log="$PWD/build/prebuild.log"
  setsid bash -c 'start=$SECONDS failed=()
    nice -n 19 bash scripts/cross_check.sh --ci --build-only || failed+=(cross_check.sh)
    nice -n 19 bash scripts/run_sanitizers.sh --build-only || failed+=(run_sanitizers.sh)
    nice -n 19 bash scripts/run_fuzz.sh --build-only || failed+=(run_fuzz.sh)
    echo "prebuild lane: $((SECONDS - start)) s${failed:+, failed: ${failed[*]}}"' > "$prebuild_log" 2>&1 &
  prebuild_pid=$!
  trap 'kill -- -"$prebuild_pid" 2> /dev/null' EXIT
fi

results=()
failed=0
run_part() {  # name, command...
  local name="$1"; shift
  echo; echo "================ $name ================"
  local start=$SECONDS
  if "$@"; then results+=("PASS  $name ($((SECONDS - start)) s)")
  else results+=("FAIL  $name ($((SECONDS - start)) s)"); failed=$((failed + 1)); fi
}

export OMP_NUM_THREADS="${OMP_NUM_THREADS:-2}"
if [ $fast -eq 1 ]; then
  run_part "C++ tests (ctest, fast)" ctest --test-dir build --output-on-failure -E "$SLOW_CPP_TESTS_REGEX"
else
  run_part "C++ tests (ctest)" ctest --test-dir build --output-on-failure
fi
run_part "Python module (pytest)" env GAUSS_BUILD_DIR="$PWD/build" /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/python
run_part "Quality matrix, fast subset (docs/quality.md)" \
  env GAUSS_BUILD_DIR="$PWD/build" /usr/bin/python3 scripts/quality_matrix.py --fast
run_part "Blender add-on, headless" \
  blender -b --factory-startup --python-exit-code 1 -P tests/blender/run_headless.py -- "$PWD/build"
if [ $fast -eq 0 ]; then
  # The real-window suite mostly waits for redraws (one Blender, on one core): it runs beside the next
  # three parts, and its output and result follow theirs.
  windowed_name="Blender add-on, real window (xvfb)"
  windowed_log="$PWD/build/windowed_part.log"
  (start=$SECONDS
   if bash tests/blender/run_windowed.sh "$PWD/build" > "$windowed_log" 2>&1; then
     echo "PASS  $windowed_name ($((SECONDS - start)) s, beside the next parts)"
   else echo "FAIL  $windowed_name ($((SECONDS - start)) s, beside the next parts)"; fi) > "$windowed_log.result" &
  windowed_pid=$!
  # numpy 2 under the newest extension Python: Python 3.11 runs the module's suite above (Debian's) and,
  # beside numpy 2, the add-on's suite in bpy 4.2 to 4.4; scripts/test_numpy2.sh alone runs 3.11 as well.
  run_part "Python module against numpy 2 (Python 3.13)" bash scripts/test_numpy2.sh --newest
  run_part "Farm engines: Slurm, Open Job Description, Flamenco" \
    env GAUSS_BUILD_DIR="$PWD/build" /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/farm
  run_part "Blender add-on in every bpy release (4.2 to 5.3)" bash scripts/test_blender_versions.sh --ci
  wait "$windowed_pid"
  echo; echo "================ $windowed_name ================"
  cat "$windowed_log"
  results+=("$(cat "$windowed_log.result")")
  [[ "${results[-1]}" == PASS* ]] || failed=$((failed + 1))
  wait "$prebuild_pid"  # its trees are the next parts' (two builds of one tree at once would clash)
  echo; tail -n 1 "$prebuild_log"; echo "(its log: $prebuild_log)"
  run_part "Windows and macOS cross check (MinGW + wine, zig)" bash scripts/cross_check.sh --ci
  run_part "C++ tests under ASan+UBSan" bash scripts/run_sanitizers.sh
  run_part "libFuzzer (60 s)" bash scripts/run_fuzz.sh 60
fi

echo; echo "================ summary ================"
printf '%s\n' "${results[@]}"
passed=$(( ${#results[@]} - failed ))
echo "suites: $passed passed, $failed failed"
exit $(( failed > 0 ))
