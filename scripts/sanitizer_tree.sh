# Sourced by scripts/run_sanitizers.sh and scripts/run_fuzz.sh: how both configure their clang trees.
#
#   configure_sanitizer_tree BUILD_DIR [CMAKE_ARGS...]
#
# clang, -O2 -gline-tables-only: reports keep file and line, and clang compiles the sanitized sources
# about three times faster than GCC with -g (docs/building.md, "Sanitizers and fuzzing"). The two trees
# stay apart: libFuzzer's coverage instrumentation of the library would halve the C++ tests' speed.
# Unity builds (CMAKE_UNITY_BUILD): both trees are built afresh in CI, where compiling several sources per
# compiler run saves much of their time (docs/building.md, "Unity builds").
sanitizer_tree_repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
configure_sanitizer_tree() {
  local build="$1"; shift
  cmake -S "$sanitizer_tree_repo" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
    -DGAUSS_SANITIZE=address,undefined -DGAUSS_BUILD_PYTHON=OFF -DGAUSS_BUILD_BENCH=OFF \
    -DCMAKE_UNITY_BUILD=ON "$@"
}
