#!/usr/bin/env bash
# Proves on this Debian 12 (x86_64) machine what it can of Windows and macOS: the C++ core (gauss_lib,
# gauss_tools) and the C++ test suite (gauss_tests)
#   - cross-compiled for Windows x64 with MinGW-w64, linked statically, and run under wine (all but
#     the slow cases of tests/cpp/slow_tests.txt);
#   - compiled and linked for macOS arm64 and x86_64 with zig (no Apple SDK; they cannot run here).
# Run as root on a fresh machine it installs what it needs: Debian packages (apt-get) and zig from PyPI
# (pinned in packaging/cross-check-requirements.txt) in a venv under the cache folder below.
#
# Output (stdout), each line once its part succeeded:
#   windows-x64 (mingw, wine): N passed, 0 failed
#   macos-arm64 (zig): built
#   macos-x64 (zig): built
# Exit status non-zero, with the reason and the end of the failing step's log on stderr, if any
# install, build or test fails. Progress goes to stderr; each step's full output to a log in its
# build folder.
#
# Folders: build-cross-<platform> (the project) and build-cross-gtest-<platform> (googletest, built
# from Debian's source in /usr/src/googletest) in the work tree; the venv, zig's compiler cache and
# wine's prefix in ${XDG_CACHE_HOME:-$HOME/.cache}/gauss_stylization/cross. Builds are incremental: a
# second run only rebuilds what changed.
set -euo pipefail
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
  local log="$1" what="$2"; shift 2
  echo "== $what" >&2
  mkdir -p "$(dirname "$log")"
  if ! "$@" > "$log" 2>&1; then
    tail -n 40 "$log" >&2
    fail "$what (full log: $log)"
  fi
}

# ---- What the check needs from Debian ---------------------------------------------------------------
packages=(cmake make libeigen3-dev googletest python3-venv g++-mingw-w64-x86-64-posix wine wine64)
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
# CMake needs each tool as one executable: wrappers that run `python -m ziglang TOOL -target ARCH-macos`.
zig_bin="$cache/zig-bin"
mkdir -p "$zig_bin"
for arch in aarch64 x86_64; do
  for tool in cc c++ ar ranlib; do
    target_args=""
    case "$tool" in cc | c++) target_args="-target $arch-macos" ;; esac
    printf '#!/bin/sh\nexec "%s" -m ziglang %s %s "$@"\n' "$venv/bin/python" "$tool" "$target_args" \
      > "$zig_bin/$arch-macos-$tool"
    chmod +x "$zig_bin/$arch-macos-$tool"
  done
done
export ZIG_GLOBAL_CACHE_DIR="$cache/zig-cache" ZIG_LOCAL_CACHE_DIR="$cache/zig-cache"

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
    -DGTest_DIR="$gtest/install/lib/cmake/GTest" -DEigen3_DIR=/usr/share/eigen3/cmake "$@"
  step "$build/build.log" "$name: building gauss_tests" cmake --build "$build" -j"$jobs" --target gauss_tests
}

# Windows: strict C++17 (no GNU extensions, so no M_PI unless asked for, as with MSVC) and no
# variable-length arrays (MSVC has none). The tests find the meshes through wine's drive Z: (= /).
meshes="$(realpath -m "$root/../shared/meshes")"
build_platform windows-x64 -DCMAKE_TOOLCHAIN_FILE="$root/cmake/toolchains/mingw-w64-x86_64.cmake" \
  -DCMAKE_CXX_EXTENSIONS=OFF -DCMAKE_CXX_FLAGS="-Werror=vla" -DGAUSS_MESH_DIR:STRING="Z:$meshes"
for arch in aarch64 x86_64; do
  build_platform "macos-$arch" -DCMAKE_TOOLCHAIN_FILE="$root/cmake/toolchains/zig-macos.cmake" \
    -DGAUSS_ZIG_BIN="$zig_bin" -DGAUSS_MACOS_ARCH="$arch" -DCMAKE_CXX_FLAGS="-Werror=vla"
done

# ---- Windows: the whole suite under wine -----------------------------------------------------------------
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
skipped=$(tr -d '\r' < "$log" | sed -n 's/^\[  SKIPPED \] \([0-9]*\) tests\{0,1\}, listed below.*/\1/p')
if [ -z "$passed" ]; then
  tail -n 40 "$log" >&2
  fail "windows-x64: gauss_tests.exe ended (status $status) without gtest's summary (full log: $log)"
fi
# The tests skip, or (the SharedMesh suite) leave out, what needs files they cannot find: with the
# meshes here, a skip or a missing suite means the path did not reach them through wine.
if [ -d "$meshes" ] && { [ -n "$skipped" ] || ! grep -q '^\[ RUN      \] All/SharedMesh\.' "$log"; }; then
  tr -d '\r' < "$log" | grep '^\[  SKIPPED \] [A-Za-z]' | sort -u >&2 || true
  fail "windows-x64: ${skipped:-0} tests skipped or the SharedMesh suite missing: are $meshes (Z:$meshes) and the sources readable under wine? (full log: $log)"
fi
if [ "${failed:-0}" != 0 ] || [ "$status" != 0 ]; then
  tr -d '\r' < "$log" | grep '^\[  FAILED  \] [A-Za-z]' | sort -u >&2 || true
  echo "windows-x64 (mingw, wine): $passed passed, ${failed:-0} failed"
  fail "windows-x64: gauss_tests.exe (status $status; full log: $log)"
fi
echo "windows-x64 (mingw, wine): $passed passed, 0 failed"

# ---- macOS: linked executables of the right architecture --------------------------------------------------
# A thin 64-bit Mach-O file starts with cf fa ed fe, then its CPU type: 0x0100000c arm64, 0x01000007 x86_64.
for arch in aarch64 x86_64; do
  bin="$root/build-cross-macos-$arch/gauss_tests"
  [ -f "$bin" ] || fail "$bin was not built"
  case "$arch" in aarch64) want="cffaedfe0c000001" label=macos-arm64 ;; x86_64) want="cffaedfe07000001" label=macos-x64 ;; esac
  head_bytes=$(od -An -tx1 -N8 "$bin" | tr -d ' \n')
  [ "$head_bytes" = "$want" ] || fail "$bin is not a Mach-O $arch executable (starts with $head_bytes)"
  echo "$label (zig): built"
done
