#pragma once
// The fuzz target's body: one input = one session with GaussSolver through its public entry points
// (mesh arrays with arbitrary indices and coordinates, pins and their targets, styles from presets or
// from arbitrary normals/rings/sigma/mu/rotation, face styles, lambda, ADMM iterations, steps, reset,
// read-outs, moving the pins). Shared by the libFuzzer target (fuzz_solver.cpp) and by the replay of the corpus and of
// the regressions in tests/cpp/test_robustness.cpp, so every input the fuzzer ever crashed on stays
// covered by ctest under any compiler.
//
// Besides what the sanitizers check, a violation of this contract calls abort():
//  * bad input is refused with std::invalid_argument (any other exception escapes: a crash);
//  * a solver that was built steps and reads out finite coordinates and energies, and the coordinates
//    stay bounded: within kGrowth times the extent of the rest mesh and the pin targets of their
//    centre, however many steps ran (slivers once made meshes explode, finite but 1e80 wide);
//  * nothing is lost: vertices that no usable face references come back bit for bit as given, and
//    pinned vertices exactly at their targets.
//
// Input layout (bytes consumed front to back; missing bytes read as 0): mesh, pins, lambda, then up
// to 16 operations, then new pin targets, then a continuation with the cubic method. tests/fuzz/make_corpus.py writes seeds in this layout.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "gauss/gauss_solver.h"
#include "gauss/preference_function.h"
#include "gauss/presets.h"

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

struct Mesh {
  std::vector<double> V;
  std::vector<int64_t> F;
  int nv() const { return static_cast<int>(V.size() / 3); }
  int nf() const { return static_cast<int>(F.size() / 3); }
  void vertex(double x, double y, double z) { V.insert(V.end(), {x, y, z}); }
  void face(int64_t a, int64_t b, int64_t c) { F.insert(F.end(), {a, b, c}); }
};

// A prism with n-gon caps whose sides are split by `cuts` vertices, collinear up to an alternating
// offset of 2^-21 (float rounding of Blender's coordinates, made deterministic: pure rounding noise
// decided by the last bit whether an old area test caught a triangle). Each cap is triangulated as Blender's loop triangles of such an n-gon
// are: by clipping every other corner, (p0 p1 p2), (p2 p3 p4), ..., then the same on what remains, so
// three consecutive points of one side make a zero-area triangle (at rounding level, |cot| ~ 1e7)
// next to good ones.
inline void add_ngon_prism(Mesh& m, int sides, int cuts, double height) {
  const int ring = sides * (cuts + 1);
  for (int level = 0; level < 2; ++level)
    for (int i = 0; i < sides; ++i)
      for (int c = 0; c <= cuts; ++c) {
        const double a0 = 2 * kPi * i / sides, a1 = 2 * kPi * (i + 1) / sides, t = c / double(cuts + 1);
        const double r = 1.0 + ((c % 2) ? 1.0 : -1.0) * std::ldexp(1.0, -21) * (c > 0);
        m.vertex(r * ((1 - t) * std::cos(a0) + t * std::cos(a1)), r * ((1 - t) * std::sin(a0) + t * std::sin(a1)),
                 level * height);
      }
  for (int i = 0; i < ring; ++i) {
    const int j = (i + 1) % ring;
    m.face(i, j, ring + j);
    m.face(i, ring + j, ring + i);
  }
  std::vector<int> polygon(ring);
  for (int i = 0; i < ring; ++i) polygon[i] = i;
  while (polygon.size() >= 3) {
    const int n = static_cast<int>(polygon.size());
    std::vector<int> rest;
    for (int k = 0; k + 1 < n; k += 2) {
      const int a = polygon[k], b = polygon[k + 1], c = polygon[(k + 2) % n];
      m.face(a, c, b);                        // bottom, facing down
      m.face(ring + a, ring + b, ring + c);   // top, facing up
      rest.push_back(a);
    }
    if (n % 2 == 1) rest.push_back(polygon[n - 1]);
    polygon = std::move(rest);
  }
}

inline Mesh make_mesh(Reader& r) {
  Mesh m;
  switch (r.byte() % 7) {
    case 0: {  // arbitrary arrays
      const int nv = r.byte() % 48;
      for (int i = 0; i < 3 * nv; ++i) m.V.push_back(r.real());
      const int nf = r.byte() % 64;
      for (int i = 0; i < 3 * nf; ++i) m.F.push_back(r.index(nv));
      break;
    }
    case 1: {  // octahedron
      const double p[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
      for (const auto& v : p) m.vertex(v[0], v[1], v[2]);
      const int f[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
      for (const auto& t : f) m.face(t[0], t[1], t[2]);
      break;
    }
    case 2: {  // cube
      for (int i = 0; i < 8; ++i) m.vertex(i & 1, (i >> 1) & 1, (i >> 2) & 1);
      const int f[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                            {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
      for (const auto& t : f) m.face(t[0], t[1], t[2]);
      break;
    }
    case 3: {  // grid, optionally rolled into a tube or a Moebius strip
      const int nu = 3 + r.byte() % 6, nw = 2 + r.byte() % 3, kind = r.byte() % 3;
      for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nw; ++j) {
          const double w = j / double(nw - 1) - 0.5, a = 2 * kPi * i / nu;
          if (kind == 0) m.vertex(i, j, 0.1 * ((i * 7 + j * 3) % 5));
          else if (kind == 1) m.vertex(std::cos(a), std::sin(a), w);
          else m.vertex((1 + w * std::cos(a / 2)) * std::cos(a), (1 + w * std::cos(a / 2)) * std::sin(a),
                        w * std::sin(a / 2));
        }
      const int cols = kind == 0 ? nu - 1 : nu;
      for (int i = 0; i < cols; ++i)
        for (int j = 0; j + 1 < nw; ++j) {
          const int i1 = (i + 1) % nu;
          const bool flip = kind == 2 && i1 == 0;  // the Moebius seam reverses the width direction
          const int a = i * nw + j, b = i * nw + j + 1;
          const int c = i1 * nw + (flip ? nw - 1 - j : j), d = i1 * nw + (flip ? nw - 2 - j : j + 1);
          m.face(a, c, d);
          m.face(a, d, b);
        }
      break;
    }
    case 4: {  // separate tetrahedra
      const int k = 1 + r.byte() % 12;
      for (int i = 0; i < k; ++i) {
        const double o = 3.0 * i;
        m.vertex(o, 0, 0);
        m.vertex(o + 1, 0, 0);
        m.vertex(o, 1, 0);
        m.vertex(o, 0, 1);
        m.face(4 * i, 4 * i + 2, 4 * i + 1);
        m.face(4 * i, 4 * i + 1, 4 * i + 3);
        m.face(4 * i, 4 * i + 3, 4 * i + 2);
        m.face(4 * i + 1, 4 * i + 2, 4 * i + 3);
      }
      break;
    }
    case 6: {  // n-gon prism: slivers and collinear fans
      const int sides = 3 + r.byte() % 14, cuts = r.byte() % 9;
      add_ngon_prism(m, sides, cuts, 0.25 + (r.byte() % 8) / 4.0);
      break;
    }
    default: {  // k triangles on one edge: a non-manifold fan
      const int k = 1 + r.byte() % 6;
      m.vertex(0, 0, 0);
      m.vertex(0, 0, 1);
      for (int i = 0; i < k; ++i) {
        m.vertex(std::cos(2 * kPi * i / k), std::sin(2 * kPi * i / k), 0.5);
        m.face(0, 1, 2 + i);
      }
      break;
    }
  }
  // Damage: move vertices, rewrite indices, add faces, add loose vertices.
  const int edits = r.byte() % 8;
  for (int e = 0; e < edits; ++e) {
    const int nv = m.nv(), nf = m.nf();
    switch (r.byte() % 4) {
      case 0: {
        const int v = r.byte() % std::max(nv, 1);
        const int k = r.byte() % 3;
        const double x = r.real();
        if (nv > 0) m.V[3 * v + k] = x;
        break;
      }
      case 1: {
        const int f = r.byte() % std::max(nf, 1);
        const int k = r.byte() % 3;
        const int64_t i = r.index(nv);
        if (nf > 0) m.F[3 * f + k] = i;
        break;
      }
      case 2: {
        const int64_t a = r.index(nv), b = r.index(nv), c = r.index(nv);
        m.face(a, b, c);
        break;
      }
      default: {
        const Eigen::Vector3d p = r.vec3();
        m.vertex(p.x(), p.y(), p.z());
        break;
      }
    }
  }
  // Place: scale and translate the whole mesh.
  static const double scales[8] = {1.0, 1e6, 1e-6, 1e150, 1e-150, 1e300, 1e-300, 3.0};
  const double scale = scales[r.byte() % 8];
  const double offset[3] = {r.real(), r.real(), r.real()};
  for (size_t i = 0; i < m.V.size(); ++i) m.V[i] = m.V[i] * scale + offset[i % 3] * scale;
  return m;
}

struct Pins {
  std::vector<int64_t> index;
  std::vector<double> target;  // empty: the rest positions
};

inline Pins make_pins(Reader& r, const Mesh& m) {
  Pins p;
  const uint8_t n = r.byte();
  const int count = n < 128 ? 0 : n % 6;
  const int mode = r.byte() % 3;
  for (int i = 0; i < count; ++i) {
    const int64_t v = r.index(m.nv());
    p.index.push_back(v);
    if (mode == 0) continue;
    for (int k = 0; k < 3; ++k) {
      const bool valid = v >= 0 && v < m.nv();
      const double rest = valid ? m.V[3 * v + k] : 0.0;
      // mode 1: near the rest position (a deformation); mode 2: anywhere.
      p.target.push_back(mode == 1 ? rest + r.real() / 8.0 : r.real());
    }
  }
  return p;
}

inline std::optional<gauss::PreferenceFunction> make_style(Reader& r) {
  gauss::StyleParams p;
  switch (r.byte() % 4) {
    case 0:
    case 1: {
      const auto& names = gauss::preset_names();
      p = gauss::preset_style(names[r.byte() % names.size()]);
      break;
    }
    case 2: {  // arbitrary normals
      const int k = r.byte() % 6;
      for (int i = 0; i < k; ++i) p.normals.push_back(r.vec3());
      break;
    }
    default: {  // rings, with or without normals
      p.normals.clear();
      const int k = r.byte() % 3;
      for (int i = 0; i < k; ++i) p.normals.push_back(r.vec3());
      p.axis = r.vec3();
      const int rings = r.byte() % 4;
      for (int i = 0; i < rings; ++i) p.ring_offsets.push_back(r.real() / 4.0);
      break;
    }
  }
  const uint8_t flags = r.byte();
  if (flags & 1) p.sigma = r.param();
  if (flags & 2) p.mu = r.param();
  if (flags & 4) p.axis_contribution = r.param();
  if (flags & 8) {  // a proper rotation from a quaternion
    const double w = r.real();
    const Eigen::Vector3d xyz = r.vec3();
    Eigen::Quaterniond q(w, xyz.x(), xyz.y(), xyz.z());
    if (q.norm() > 1e-6 && std::isfinite(q.norm())) p.rotation = q.normalized().toRotationMatrix();
  }
  if (flags & 16)  // anything
    for (int i = 0; i < 9; ++i) p.rotation(i / 3, i % 3) = r.real();
  try {
    return gauss::PreferenceFunction(p);
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

// How far results may spread, in extents of the rest mesh and pin targets, from their centre.
constexpr double kGrowth = 10.0;

// Moves the current pins (set_pin_positions, no re-factorization): near their targets or anywhere, or
// with a wrong count. It runs after the operations, so inputs saved before it still replay the sessions
// they were saved for.
inline void drag_pins(Reader& r, gauss::GaussSolver& s, const Mesh& m, Pins& pins) {
  Pins moved = pins;
  if (moved.target.empty())
    for (int64_t v : moved.index) moved.target.insert(moved.target.end(), &m.V[3 * v], &m.V[3 * v] + 3);
  const uint8_t mode = r.byte();
  for (double& x : moved.target) x = mode % 2 ? r.real() : x + r.real() / 8.0;
  const int count = static_cast<int>(moved.index.size()) - (mode >= 224 ? 1 : 0);
  GAUSS_FUZZ_TRACE("  set_pin_positions (%d of %zu)\n", count, moved.index.size());
  try {
    s.set_pin_positions(moved.target.empty() ? nullptr : moved.target.data(), count);
    if (count != static_cast<int>(moved.index.size())) fail("a wrong number of pin positions was accepted");
    pins = std::move(moved);
  } catch (const std::invalid_argument& e) {
    GAUSS_FUZZ_TRACE("    refused: %s\n", e.what());
  }
}

// The read-outs, checked against the contract above.
inline void check(const gauss::GaussSolver& s, const Mesh& m, const std::vector<uint8_t>& referenced,
                  const Pins& pins) {
  const int nv = m.nv();
  std::vector<double> out(3 * static_cast<size_t>(nv));
  std::vector<float> out_f(3 * static_cast<size_t>(nv));
  s.copy_vertices(out.data());
  s.copy_vertices(out_f.data());
  for (size_t i = 0; i < out.size(); ++i) {
    if (!std::isfinite(out[i])) fail("a vertex coordinate is NaN or infinite");
    if (!(out_f[i] == static_cast<float>(out[i]))) fail("float and double read-outs differ");
  }
  // Bounded: the box of the referenced rest vertices and the pin targets, grown kGrowth times.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (int v = 0; v < nv; ++v)
    if (referenced[v])
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], m.V[3 * v + k]), hi[k] = std::max(hi[k], m.V[3 * v + k]);
  for (size_t i = 0; i < pins.index.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const double t = pins.target.empty() ? m.V[3 * pins.index[i] + k] : pins.target[3 * i + k];
      lo[k] = std::min(lo[k], t), hi[k] = std::max(hi[k], t);
    }
  const Eigen::Vector3d centre = 0.5 * lo + 0.5 * hi;  // halves first: no overflow near DBL_MAX
  const double extent = (0.5 * hi - 0.5 * lo).maxCoeff() * 2.0;
  for (int v = 0; v < nv; ++v)
    if (referenced[v])
      for (int k = 0; k < 3; ++k)
        if (!(std::abs(out[3 * v + k] - centre[k]) <= kGrowth * extent + 1e-300)) fail("the mesh blew up");
  std::vector<uint8_t> pinned(nv, 0);
  for (size_t i = 0; i < pins.index.size(); ++i) {
    const int64_t v = pins.index[i];
    pinned[v] = 1;
    for (int k = 0; k < 3; ++k) {
      const double target = pins.target.empty() ? m.V[3 * v + k] : pins.target[3 * i + k];
      if (std::memcmp(&out[3 * v + k], &target, sizeof(double)) != 0) fail("a pinned vertex is off its target");
    }
  }
  for (int v = 0; v < nv; ++v)
    if (!referenced[v] && !pinned[v] && std::memcmp(&out[3 * v], &m.V[3 * v], 3 * sizeof(double)) != 0)
      fail("an unreferenced vertex moved");
  if (!std::isfinite(s.arap_energy())) fail("E_ARAP is NaN or infinite");
  if (!std::isfinite(s.g_energy())) fail("E_g is NaN or infinite");
  if (!std::isfinite(s.cubic_energy())) fail("E_cubic is NaN or infinite");
}

// The same session continued with the cubic method (cubic_local_step.h): a cubic lambda (default or
// any), a run, optionally new styles or a reset and back to the Gauss method for a step. It runs after
// drag_pins, so inputs saved before it still replay the sessions they were saved for first.
template <class Step>
void cubic_session(Reader& r, gauss::GaussSolver& s, const Mesh& m, const std::vector<uint8_t>& referenced,
                   const Pins& pins, Step&& step) {
  const uint8_t mode = r.byte();
  try {
    if (mode & 1) s.set_cubic_lambda(r.param());
  } catch (const std::invalid_argument& e) {
    GAUSS_FUZZ_TRACE("  set_cubic_lambda refused: %s\n", e.what());
  }
  s.set_method(gauss::Method::cubic);
  const int n = 1 + r.byte() % 64;
  GAUSS_FUZZ_TRACE("  cubic: lambda %g, %d steps\n", s.cubic_lambda(), n);
  for (int i = 0; i < n; ++i) step();
  check(s, m, referenced, pins);
  if (mode & 2)
    if (auto g = make_style(r)) {  // the cubic method reads its mu and rotation
      try {
        s.set_style(0, *g);
      } catch (const std::invalid_argument&) {  // there is no style 0
      }
      step();
    }
  if (mode & 4) s.reset(), step(), step();
  if (mode & 8) s.set_method(gauss::Method::gauss), step();
  check(s, m, referenced, pins);
}

inline void run_one(const uint8_t* data, size_t size) {
  Reader r(data, size);
  const Mesh m = make_mesh(r);
  Pins pins = make_pins(r, m);
  const double lambda = r.byte() < 128 ? 4.0 : r.param();
  std::unique_ptr<gauss::GaussSolver> s;
  try {
    s = std::make_unique<gauss::GaussSolver>(m.V.data(), m.nv(), m.F.data(), m.nf(), pins.index,
                                             pins.target.empty() ? nullptr : pins.target.data(), lambda);
  } catch (const std::invalid_argument& e) {
    GAUSS_FUZZ_TRACE("mesh %d vertices, %d faces, %zu pins, lambda %g: refused: %s\n", m.nv(), m.nf(),
                     pins.index.size(), lambda, e.what());
    return;
  }
  GAUSS_FUZZ_TRACE("mesh %d vertices, %d faces, %zu pins, lambda %g: accepted\n", m.nv(), m.nf(), pins.index.size(),
                   lambda);
  // Accepted: every index is in range. A face is usable if its three indices differ.
  std::vector<uint8_t> referenced(m.nv(), 0);
  for (int f = 0; f < m.nf(); ++f) {
    const int64_t a = m.F[3 * f], b = m.F[3 * f + 1], c = m.F[3 * f + 2];
    if (a != b && b != c && c != a) referenced[a] = referenced[b] = referenced[c] = 1;
  }
  if (s->num_vertices() != m.nv() || s->num_input_faces() != m.nf()) fail("the solver lost vertices or faces");

  // Work budget: dozens of 1000-round steps take seconds under the sanitizers and teach nothing new.
  long rounds_left = 4000;  // a 1000-step run fits, with room for the other operations
  auto step = [&] {
    if (rounds_left < s->admm_iterations()) return;
    rounds_left -= s->admm_iterations();
    s->step();
  };
  const int ops = 1 + r.byte() % 16;
  for (int op = 0; op < ops && !r.empty(); ++op) {
    const int code = r.byte() % 10;
    static const char* const names[10] = {"set_styles", "set_style", "set_face_styles", "set_lambda", "set_pins",
                                          "set_admm_iterations", "step", "reset", "check", "long_run"};
    GAUSS_FUZZ_TRACE("  %s\n", names[code]);
    try {
      switch (code) {
        case 0: {
          std::vector<gauss::PreferenceFunction> styles;
          const int n = r.byte() % 4;
          for (int i = 0; i < n; ++i)
            if (auto g = make_style(r)) styles.push_back(*g);
          s->set_styles(std::move(styles));
          break;
        }
        case 1: {
          const int index = static_cast<int>(r.byte() % (s->num_styles() + 2)) - 1;
          if (auto g = make_style(r)) s->set_style(index, *g);
          break;
        }
        case 2: {
          const int count = r.byte() < 224 ? m.nf() : r.byte() % (m.nf() + 2);
          std::vector<int64_t> fs(count);
          for (int64_t& x : fs) {
            const uint8_t b = r.byte();
            x = b < 250 ? static_cast<int64_t>(b % (s->num_styles() + 1)) - 1
                        : (b == 250 ? -2 : b == 251 ? s->num_styles() : b == 252 ? INT64_MIN : INT64_MAX);
          }
          s->set_face_styles(fs.data(), count);
          break;
        }
        case 3:
          s->set_lambda(r.param());
          break;
        case 4: {
          Pins p = make_pins(r, m);
          s->set_pins(p.index, p.target.empty() ? nullptr : p.target.data());
          pins = std::move(p);
          break;
        }
        case 5: {
          static const int counts[16] = {-1, 0, 1, 1, 1, 2, 2, 2, 3, 3, 4, 5, 8, 20, 1000, 1001};
          s->set_admm_iterations(counts[r.byte() % 16]);
          break;
        }
        case 6: {
          const int n = 1 + r.byte() % 4;
          for (int i = 0; i < n; ++i) step();
          break;
        }
        case 7:
          s->reset();
          if (s->step_count() != 0) fail("reset did not reset the step count");
          break;
        case 8:
          check(*s, m, referenced, pins);
          break;
        default: {  // a live run left going: up to 1000 steps, then the read-outs
          const int n = 100 * (1 + r.byte() % 10);
          for (int i = 0; i < n; ++i) step();
          check(*s, m, referenced, pins);
          break;
        }
      }
    } catch (const std::invalid_argument& e) {
      // Refused with a message: fine, and the solver must still work (checked below).
      GAUSS_FUZZ_TRACE("    refused: %s\n", e.what());
    }
  }
  step();
  check(*s, m, referenced, pins);
  drag_pins(r, *s, m, pins);
  step();
  check(*s, m, referenced, pins);
  try {
    cubic_session(r, *s, m, referenced, pins, step);
  } catch (const std::invalid_argument& e) {
    GAUSS_FUZZ_TRACE("    refused: %s\n", e.what());
  }
  GAUSS_FUZZ_TRACE("  done: %d steps since reset, %d styles, E_g %g\n", s->step_count(), s->num_styles(), s->g_energy());
}

}  // namespace gauss_fuzz
