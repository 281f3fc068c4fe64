# Cross-compiling for macOS with zig's bundled clang, libc++ and macOS libc headers (no Apple SDK):
# enough to compile and link; the result cannot run here. Used by scripts/cross_check.sh.
# Inputs (cache entries, -D...):
#   GAUSS_ZIG_BIN     a folder with the wrapper scripts <arch>-macos-cc, -c++, -ar and -ranlib, each
#                     running `python -m ziglang cc|c++ -target <arch>-macos` (ar, ranlib) from a venv
#                     with ziglang (CMAKE_CXX_COMPILER must be one executable, not a command line)
#   GAUSS_MACOS_ARCH  aarch64 or x86_64
set(CMAKE_SYSTEM_NAME Darwin)
if(NOT GAUSS_ZIG_BIN OR NOT GAUSS_MACOS_ARCH MATCHES "^(aarch64|x86_64)$")
  message(FATAL_ERROR "zig-macos.cmake needs -DGAUSS_ZIG_BIN=<folder> and -DGAUSS_MACOS_ARCH=aarch64|x86_64")
endif()
# try_compile projects read this file again: they need the same two inputs.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES GAUSS_ZIG_BIN GAUSS_MACOS_ARCH)
set(CMAKE_SYSTEM_PROCESSOR ${GAUSS_MACOS_ARCH})
set(CMAKE_C_COMPILER ${GAUSS_ZIG_BIN}/${GAUSS_MACOS_ARCH}-macos-cc)
set(CMAKE_CXX_COMPILER ${GAUSS_ZIG_BIN}/${GAUSS_MACOS_ARCH}-macos-c++)
set(CMAKE_AR ${GAUSS_ZIG_BIN}/${GAUSS_MACOS_ARCH}-macos-ar CACHE FILEPATH "zig ar")
set(CMAKE_RANLIB ${GAUSS_ZIG_BIN}/${GAUSS_MACOS_ARCH}-macos-ranlib CACHE FILEPATH "zig ranlib")
# No strip: the host's binutils cannot read Mach-O, and stripping after zig's linker signed an arm64 file
# would void its ad-hoc signature. pybind11 strips Release modules with CMAKE_STRIP, so it runs `true`.
set(CMAKE_STRIP /bin/true CACHE FILEPATH "no strip for Mach-O (zig signs at link time)")
