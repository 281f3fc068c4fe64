#pragma once
// Reading a fuzz input: bytes consumed front to back, missing bytes read as 0, turned into small ints,
// indices (valid or not), reals (ordinary, huge, tiny, NaN, infinite) and vectors. Also how the harness
// reports: fail() (a contract violation aborts, which the fuzzer and ctest both catch) and
// GAUSS_FUZZ_TRACE (GAUSS_FUZZ_TRACE=1 in the environment).
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

#include <Eigen/Core>

namespace gauss_fuzz {

constexpr double kPi = 3.14159265358979323846;

[[noreturn]] inline void fail(const char* what) {
  std::fprintf(stderr, "gauss fuzz contract violated: %s\n", what);
  std::abort();
}

// GAUSS_FUZZ_TRACE=1 prints what an input does (to read a crash input or check a seed).
inline bool tracing() {
  static const bool on = std::getenv("GAUSS_FUZZ_TRACE") != nullptr;
  return on;
}
#define GAUSS_FUZZ_TRACE(...) \
  do {                        \
    if (tracing()) std::fprintf(stderr, __VA_ARGS__); \
  } while (0)

class Reader {
 public:
  Reader(const uint8_t* data, size_t size) : p_(data), n_(size) {}
  bool empty() const { return n_ == 0; }
  uint8_t byte() {
    if (n_ == 0) return 0;
    --n_;
    return *p_++;
  }
  uint64_t u64() {
    uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<uint64_t>(byte()) << (8 * i);
    return v;
  }
  double raw_double() {
    const uint64_t bits = u64();
    double d;
    std::memcpy(&d, &bits, sizeof d);
    return d;
  }
  // Mostly small lattice values (meshes that make sense), sometimes special or raw doubles.
  double real() {
    const uint8_t mode = byte();
    if (mode < 224) return (static_cast<int>(byte()) - 128) / 32.0;
    static const double special[16] = {0.0,     -0.0,     1e-6,    1e6,
                                       1e-300,  1e300,    DBL_MAX, -DBL_MAX,
                                       DBL_MIN, std::numeric_limits<double>::denorm_min(),
                                       std::numeric_limits<double>::quiet_NaN(),
                                       std::numeric_limits<double>::infinity(),
                                       -std::numeric_limits<double>::infinity(),
                                       1e-12,   1e12,     0.5};
    if (mode < 240) return special[mode - 224];
    return raw_double();
  }
  // Three real() in order (a function's arguments are evaluated in no specified order, so every read
  // here is a statement of its own: the same bytes decode the same way under any compiler).
  Eigen::Vector3d vec3() {
    const double x = real();
    const double y = real();
    const double z = real();
    return Eigen::Vector3d(x, y, z);
  }
  // A parameter such as sigma, mu or lambda: mostly 2^-14 .. 2^14 on a log scale, else real().
  double param() {
    const uint8_t mode = byte();
    if (mode < 224) return std::ldexp(1.0 + (mode & 7) / 8.0, (mode >> 3) - 14);
    return real();
  }
  // A vertex index for a mesh with n vertices: mostly valid, sometimes out of range.
  int64_t index(int64_t n) {
    const uint8_t mode = byte();
    if (mode < 240) {
      const int64_t lo = byte();
      const int64_t v = lo | (static_cast<int64_t>(byte()) << 8);
      return n > 0 ? v % n : v;
    }
    const int64_t special[8] = {-1, n, n + 1, std::numeric_limits<int64_t>::min(),
                                std::numeric_limits<int64_t>::max(), std::numeric_limits<int32_t>::max(),
                                int64_t(1) << 32, -n};
    return special[mode % 8];
  }

 private:
  const uint8_t* p_;
  size_t n_;
};

}  // namespace gauss_fuzz
