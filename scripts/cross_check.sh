#!/usr/bin/env bash
# Proves on this Debian 12 (x86_64) machine what it can of Windows and macOS:
#   - the C++ core (gauss_lib, gauss_tools) and the C++ test suite (gauss_tests) cross-compiled for
#     Windows x64 with MinGW-w64, linked statically, and run under wine (all
#     but the slow cases of tests/cpp/slow_tests.txt);
#   - the same compiled and linked for macOS arm64 with zig (no Apple SDK; it cannot run here), for the
#     release's minimum macOS (pyproject.toml's MACOSX_DEPLOYMENT_TARGET); not with --ci;
#   - the Python module gauss_core, as it ships, for every Python an extension zip is made for (3.11,
#     3.13: scripts/package_addon.py's BLENDER_FOR_PYTHON) on Windows x64, macOS arm64 and macOS x86_64,
#     against that CPython's headers (and Windows import library) from scripts/cross_cpython.py, then
#     inspected by scripts/check_cross_module.py (format, architecture, imports, exports, minimum macOS,
#     code signature, Python).
# Run as root on a fresh machine it installs what it needs: Debian packages (apt-get) and zig from PyPI
# (pinned in packaging/cross-check-requirements.txt) in a venv under the cache folder below.
#
# Output (stdout), each line once its part succeeded:
#   windows-x64 (mingw, wine): N passed, 0 failed, 0 skipped
#   macos-arm64 (zig): built, minos 11.0          (not with --ci)
#   windows-x64 module (cp313): built, imports python313.dll KERNEL32.dll msvcrt.dll
#   macos-arm64 module (cp313): built, minos 11.0, ad-hoc signed
#   macos-x64 module (cp313): built, minos 11.0
#   ... (one line per platform and Python)
# A skipped C++ test fails the check in CI (CI=true) unless its reason is in ALLOWED_SKIPS below, and
# locally whenever the meshes are there; the totals line counts the skips and names the allowed reasons.
# Exit status non-zero, with the reason and the end of the failing step's log on stderr, if any
# install, build, test or inspection fails. Progress goes to stderr; each step's full output to a log
# in its build folder.
#
# Folders: build-cross-<platform> (the project's tests), build-cross-<platform>-cpXY (the module) and
# build-cross-gtest-<platform> (googletest, built from Debian's source in /usr/src/googletest) in the
# work tree; the venv, zig's compiler cache, wine's prefix and CPython's headers in
# ${XDG_CACHE_HOME:-$HOME/.cache}/gauss_stylization/cross. Builds are incremental: a second run only
# rebuilds what changed; with ccache (scripts/install_deps.sh installs it) the module trees share the
# library's objects with the test trees.
set -euo pipefail
# --modules: only the Python modules (for a change to the bindings or the build of the module).
# --newest-python: the modules for the newest extension Python only (the modules of each Python differ
# only in CPython's headers; the full run builds every one).
# --ci: CI's budget: --newest-python, and no macOS test program (it cannot run here; what ships to macOS,
# the modules, is built and inspected all the same, and the Windows test program still runs under wine).
# --install-only: the Debian packages and zig, nothing built.
# --build-only: what the other options ask for is installed and built, nothing run or inspected (the test
# command installs first, then builds early beside other parts; the check itself then finds it built).
only_modules=0 newest_only=0 macos_tests=1 build_only=0 install_only=0
for arg in "$@"; do
  case "$arg" in
    --modules) only_modules=1 ;;
    --newest-python) newest_only=1 ;;
    --ci) newest_only=1 macos_tests=0 ;;
    --build-only) build_only=1 ;;
    --install-only) install_only=1 ;;
    *) echo "usage: bash scripts/cross_check.sh [--modules] [--newest-python] [--ci] [--install-only | --build-only]" >&2; exit 2 ;;
  esac
done
cd "$(dirname "$0")/.."
root="$PWD"
cache="${XDG_CACHE_HOME:-$HOME/.cache}/gauss_stylization/cross"
jobs=2  # the machine's cores are shared
# One run at a time: two would remake the same venv and build folders under each other.
mkdir -p "$cache"
exec 9> "$cache/lock"
flock 9

fail() { echo "cross_check: FAILED: $*" >&2; exit 1; }
# step LOG WHAT COMMAND...: runs COMMAND with its output in LOG; on failure shows the log's end and stops.
step() {
  local log="$1" what="$2" start=$SECONDS; shift 2
  echo "== $what" >&2
  mkdir -p "$(dirname "$log")"
  if ! "$@" > "$log" 2>&1; then
    tail -n 40 "$log" >&2
    fail "$what (full log: $log)"
  fi
  echo "   ($((SECONDS - start)) s)" >&2
}

# ---- What the check needs from Debian ---------------------------------------------------------------
packages=(cmake make ccache libeigen3-dev googletest python3-venv g++-mingw-w64-x86-64-posix wine wine64 dpkg-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "== installing: ${missing[*]}" >&2
  apt-get update -q >&2 || fail "apt-get update"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}" >&2 ||
    fail "apt-get install ${missing[*]}"
fi
wine=/usr/lib/wine/wine64
[ -x "$wine" ] || fail "$wine is missing (Debian package wine64)"
[ -f /usr/src/googletest/CMakeLists.txt ] || fail "/usr/src/googletest is missing (Debian package googletest)"

# ---- zig from PyPI, in a venv remade when its pin changes ------------------------------------------------
requirements="$root/packaging/cross-check-requirements.txt"
venv="$cache/venv"
if ! cmp -s "$requirements" "$venv/requirements.txt"; then
  echo "== making the venv $venv" >&2
  rm -rf "$venv"
  /usr/bin/python3 -m venv "$venv" || fail "python3 -m venv $venv"
  "$venv/bin/python" -m pip install -q --disable-pip-version-check -r "$requirements" >&2 ||
    fail "pip install -r $requirements"
  cp "$requirements" "$venv/requirements.txt"
fi
# The release's minimum macOS, written once in pyproject.toml ([tool.cibuildwheel.macos] environment).
minos="$(sed -n 's/.*MACOSX_DEPLOYMENT_TARGET *= *"\([0-9.]*\)".*/\1/p' "$root/pyproject.toml")"
[ -n "$minos" ] || fail "no MACOSX_DEPLOYMENT_TARGET in pyproject.toml"
# CMake needs each tool as one executable: wrappers that run `python -m ziglang TOOL -target ARCH-macos.MINOS`.
zig_bin="$cache/zig-bin"
mkdir -p "$zig_bin"
for arch in aarch64 x86_64; do
  for tool in cc c++ ar ranlib; do
    target_args=""
    case "$tool" in cc | c++) target_args="-target $arch-macos.$minos" ;; esac
    printf '#!/bin/sh\nexec "%s" -m ziglang %s %s "$@"\n' "$venv/bin/python" "$tool" "$target_args" \
      > "$zig_bin/$arch-macos-$tool"
    chmod +x "$zig_bin/$arch-macos-$tool"
  done
done
export ZIG_GLOBAL_CACHE_DIR="$cache/zig-cache" ZIG_LOCAL_CACHE_DIR="$cache/zig-cache"
[ "$install_only" = 0 ] || exit 0

# ccache keeps the objects outside the work tree: the module trees compile the same library as the test trees.
launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR="$root"
# Unity builds (several sources per compiler run): these trees are built afresh in CI, where parsing Eigen
# and googletest once per batch instead of once per file saves most of their compile time
# (docs/building.md, "Unity builds"); the same bits as a build file by file (measured on Linux).
unity=(-DCMAKE_UNITY_BUILD=ON)

# ---- Builds ---------------------------------------------------------------------------------------------
# build_platform NAME TOOLCHAIN_ARGS...: googletest, then gauss_tests, for one platform.
build_platform() {
  local name="$1"; shift
  local gtest="$root/build-cross-gtest-$name" build="$root/build-cross-$name"
  if [ ! -f "$gtest/install/lib/cmake/GTest/GTestConfig.cmake" ]; then
    step "$gtest/configure.log" "$name: configuring googletest" \
      cmake -S /usr/src/googletest -B "$gtest" -DCMAKE_BUILD_TYPE=Release -DBUILD_GMOCK=OFF \
      -DINSTALL_GTEST=ON -DCMAKE_INSTALL_PREFIX="$gtest/install" -DCMAKE_INSTALL_LIBDIR=lib "$@"
    step "$gtest/build.log" "$name: building googletest" cmake --build "$gtest" -j"$jobs" --target install
  fi
  step "$build/configure.log" "$name: configuring" \
    cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release \
    -DGAUSS_BUILD_TESTS=ON -DGAUSS_BUILD_PYTHON=OFF -DGAUSS_BUILD_BENCH=OFF \
    -DGTest_DIR="$gtest/install/lib/cmake/GTest" -DEigen3_DIR=/usr/share/eigen3/cmake "${launcher[@]}" "${unity[@]}" "$@"
  step "$build/build.log" "$name: building gauss_tests" cmake --build "$build" -j"$jobs" --target gauss_tests
}

# Windows: strict C++17 (no GNU extensions, so no M_PI unless asked for, as with MSVC) and no
# variable-length arrays (MSVC has none). The tests find the meshes through wine's drive Z: (= /).
meshes="$(realpath -m "$root/../shared/meshes")"
windows_args=(-DCMAKE_TOOLCHAIN_FILE="$root/cmake/toolchains/mingw-w64-x86_64.cmake"
  -DCMAKE_CXX_EXTENSIONS=OFF -DCMAKE_CXX_FLAGS="-Werror=vla")
macos_args=(-DCMAKE_TOOLCHAIN_FILE="$root/cmake/toolchains/zig-macos.cmake" -DGAUSS_ZIG_BIN="$zig_bin"
  -DCMAKE_CXX_FLAGS="-Werror=vla")
if [ "$only_modules" = 0 ]; then
build_platform windows-x64 "${windows_args[@]}" -DGAUSS_MESH_DIR:STRING="Z:$meshes"
# The test program for arm64 only: x86_64's compiler and linker are proven by its modules below, and a
# second macOS build of the whole test suite cost CI minutes for no more than that.
test_arches=(aarch64)
[ "$macos_tests" = 1 ] || test_arches=()
for arch in "${test_arches[@]}"; do
  build_platform "macos-$arch" "${macos_args[@]}" -DGAUSS_MACOS_ARCH="$arch"
done

if [ "$build_only" = 0 ]; then
# ---- Windows: the whole suite under wine -----------------------------------------------------------------
# Reasons a C++ test may skip in CI (GTEST_SKIP's message, matched as a prefix); any other skip fails it.
ALLOWED_SKIPS=()
exe="$root/build-cross-windows-x64/gauss_tests.exe"
[ -f "$exe" ] || fail "$exe was not built"
log="$root/build-cross-windows-x64/tests.log"
echo "== windows-x64: running gauss_tests.exe under wine" >&2
mkdir -p "$cache/wine-prefix"
# Without the slow cases (tests/cpp/slow_tests.txt), as the sanitizer run: wine adds its own slowness.
source "$root/scripts/slow_cpp_tests.sh"
# No Mono or Gecko prompts while the prefix is made; no wine debug chatter in the log.
status=0
(cd "$root/build-cross-windows-x64" &&
  WINEPREFIX="$cache/wine-prefix" WINEDEBUG=-all WINEDLLOVERRIDES="mscoree,mshtml=" \
    "$wine" "$exe" --gtest_color=no --gtest_filter="$SLOW_CPP_TESTS_FILTER") > "$log" 2>&1 || status=$?
passed=$(tr -d '\r' < "$log" | sed -n 's/^\[  PASSED  \] \([0-9]*\) tests\{0,1\}\..*/\1/p')
failed=$(tr -d '\r' < "$log" | sed -n 's/^\[  FAILED  \] \([0-9]*\) tests\{0,1\}, listed below.*/\1/p')
if [ -z "$passed" ]; then
  tail -n 40 "$log" >&2
  fail "windows-x64: gauss_tests.exe ended (status $status) without gtest's summary (full log: $log)"
fi
# Each skip with its reason: gtest prints "FILE:LINE: Skipped", the message, then "[  SKIPPED ] TEST".
skips="$(tr -d '\r' < "$log" | awk '/: Skipped$/ { getline reason; next_reason = reason == "" ? "(no reason given)" : reason }
  /^\[  SKIPPED \] [A-Za-z]/ && next_reason != "" { print $4 "\t" next_reason; next_reason = "" }')"
skipped=0 refused=()
while IFS=$'\t' read -r test reason; do
  [ -n "$test" ] || continue
  skipped=$((skipped + 1))
  allowed=0
  for prefix in "${ALLOWED_SKIPS[@]}"; do [[ "$reason" == "$prefix"* ]] && allowed=1; done
  [ "$allowed" = 1 ] || refused+=("$test: $reason")
done <<< "$skips"
totals="windows-x64 (mingw, wine): $passed passed, ${failed:-0} failed, $skipped skipped"
allowed_text="skips allowed in CI: $( [ ${#ALLOWED_SKIPS[@]} -gt 0 ] && printf '"%s" ' "${ALLOWED_SKIPS[@]}" || echo none)"
if [ "${failed:-0}" != 0 ] || [ "$status" != 0 ]; then
  tr -d '\r' < "$log" | grep '^\[  FAILED  \] [A-Za-z]' | sort -u >&2 || true
  echo "$totals"
  fail "windows-x64: gauss_tests.exe (status $status; full log: $log)"
fi
# The tests skip, or (the SharedMesh suite) leave out, what needs files they cannot find. In CI, and
# wherever the meshes are, that is a failure: the path did not reach them through wine.
if [ ${#refused[@]} -gt 0 ] && { [ "${CI:-}" = true ] || [ -d "$meshes" ]; }; then
  printf '  skipped: %s\n' "${refused[@]}" >&2
  echo "$totals ($allowed_text)"
  fail "windows-x64: ${#refused[@]} tests skipped for reasons not allowed: are $meshes (Z:$meshes) and the sources readable under wine? (full log: $log)"
fi
if [ -d "$meshes" ] && ! grep -q '^\[ RUN      \] All/SharedMesh\.' "$log"; then
  fail "windows-x64: the SharedMesh suite is missing: is $meshes (Z:$meshes) readable under wine? (full log: $log)"
fi
echo "$totals ($allowed_text)"

# ---- macOS: linked executables of the right architecture and minimum macOS ----------------------------------
for arch in "${test_arches[@]}"; do
  bin="$root/build-cross-macos-$arch/gauss_tests"
  [ -f "$bin" ] || fail "$bin was not built"
  case "$arch" in aarch64) label=macos-arm64 want=arm64 ;; x86_64) label=macos-x64 want=x86_64 ;; esac
  facts="$(python3 "$root/scripts/binary_facts.py" "$bin")" || fail "$bin: not a readable executable"
  python3 -c 'import json, sys; f = json.loads(sys.argv[3])
sys.exit(not (f["format"] == "Mach-O" and f["arch"] == sys.argv[1] and f["minos"] == sys.argv[2]))' \
    "$want" "$minos" "$facts" || fail "$bin is not a Mach-O $want executable for macOS $minos: $facts"
  echo "$label (zig): built, minos $minos"
done
fi  # not --build-only

fi  # the C++ tests

# ---- The Python module, for each Python the extension zips are made for -------------------------------------
pythons="$(cd "$root/scripts" && python3 -c 'import package_addon as p
print(" ".join(v for v in p.BLENDER_FOR_PYTHON if p.blender_ranges(v, (0, 0))[1]))')" ||
  fail "cannot read the extension Pythons from scripts/package_addon.py"
[ "$newest_only" = 0 ] || pythons="$(tr ' ' '\n' <<< "$pythons" | sort -V | tail -n1)"
tools_venv="$(bash "$root/scripts/install_deps.sh" --print-tools-venv | tail -n1)" || fail "scripts/install_deps.sh"
pybind11_dir="$("$tools_venv/bin/python" -m pybind11 --cmakedir)" || fail "no pybind11 in $tools_venv"
# build_module PLATFORM PYTHON SUFFIX CPYTHON_TARGET TOOLCHAIN_ARGS...: configure (once) and build gauss_core.
build_module() {
  local platform="$1" python="$2" suffix="$3" target="$4"; shift 4
  local tag="cp${python/./}" build="$root/build-cross-$platform-cp${python/./}" paths include library=()
  paths="$(python3 "$root/scripts/cross_cpython.py" "$cache/cpython" "$python" "$target")" ||
    fail "$platform: CPython $python's headers (scripts/cross_cpython.py)"
  include="$(sed -n 1p <<< "$paths")"
  [ "$target" = windows ] && library=(-DPython_LIBRARY="$(sed -n 2p <<< "$paths")")
  if [ ! -f "$build/CMakeCache.txt" ]; then
    step "$build/configure.log" "$platform: configuring gauss_core ($tag)" \
      cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release \
      -DGAUSS_BUILD_TESTS=OFF -DGAUSS_BUILD_PYTHON=ON -DGAUSS_BUILD_BENCH=OFF \
      -Dpybind11_DIR="$pybind11_dir" -DPython_INCLUDE_DIR="$include" "${library[@]}" \
      -DPYTHON_MODULE_EXTENSION="$suffix" -DPYTHON_IS_DEBUG=OFF -DPYTHON_MODULE_DEBUG_POSTFIX= \
      -DEigen3_DIR=/usr/share/eigen3/cmake "${launcher[@]}" "${unity[@]}" "$@"
  fi
  step "$build/build.log" "$platform: building gauss_core ($tag)" cmake --build "$build" -j"$jobs" --target gauss_core
  module="$build/python/gauss_core$suffix"
  [ -f "$module" ] || fail "$module was not built"
}
for python in $pythons; do
  tag="cp${python/./}"
  build_module windows-x64 "$python" ".$tag-win_amd64.pyd" windows "${windows_args[@]}"
  if [ "$build_only" = 0 ]; then
    line="$(python3 "$root/scripts/check_cross_module.py" windows-x64 "$python" "$minos" "$module")" ||
      fail "windows-x64 module ($tag) is not what Windows needs"
    echo "windows-x64 module ($tag): $line"
  fi
  for arch in aarch64 x86_64; do
    case "$arch" in aarch64) label=macos-arm64 ;; x86_64) label=macos-x64 ;; esac
    build_module "$label" "$python" ".cpython-${python/./}-darwin.so" macos "${macos_args[@]}" -DGAUSS_MACOS_ARCH="$arch"
    [ "$build_only" = 0 ] || continue
    line="$(python3 "$root/scripts/check_cross_module.py" "$label" "$python" "$minos" "$module")" ||
      fail "$label module ($tag) is not what macOS needs"
    echo "$label module ($tag): $line"
  done
done
