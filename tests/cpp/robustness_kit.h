#pragma once
// What the robustness tests share: meshes built in code that are broken on purpose or awkward (a cube
// sphere, an open patch, a Moebius strip, loose tetrahedra), and a run of the solver with the checks
// every result must pass (finite, not blown up, pins exact, unreferenced vertices untouched).
// Used by test_broken_mesh.cpp and test_robustness.cpp.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

#include "gauss/mesh/alignment_share.h"
#include "gauss/solver/gauss_solver.h"
#include "gauss/mesh/mesh_io.h"
#include "gauss/style/preference_function.h"
#include "gauss/style/presets.h"

namespace robustness_kit {

using Eigen::Vector3d;
using gauss::GaussSolver;
using gauss::PreferenceFunction;
using Mesh = gauss::TriangleMesh;

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------------
// Mesh generators.

inline int add_vertex(Mesh& m, const Vector3d& p) {
  m.V.insert(m.V.end(), {p.x(), p.y(), p.z()});
  return m.num_vertices() - 1;
}
inline void add_face(Mesh& m, int64_t a, int64_t b, int64_t c) { m.F.insert(m.F.end(), {a, b, c}); }
inline Vector3d point(const std::vector<double>& V, int64_t v) { return Vector3d(V[3 * v], V[3 * v + 1], V[3 * v + 2]); }

inline void append(Mesh& m, const Mesh& other) {
  const int64_t base = m.num_vertices();
  m.V.insert(m.V.end(), other.V.begin(), other.V.end());
  for (int64_t i : other.F) m.F.push_back(i + base);
}

// A lumpy closed sphere from a subdivided cube (n by n quads per side), squashed and turned so that the
// cube style has work to do; consistently oriented, outward normals.
inline Mesh cube_sphere(int n) {
  Mesh m;
  std::map<std::array<int, 3>, int> index;
  const Eigen::Matrix3d turn = (Eigen::AngleAxisd(0.5, Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  auto vid = [&](std::array<int, 3> c) {
    auto it = index.find(c);
    if (it != index.end()) return it->second;
    Vector3d p(2.0 * c[0] / n - 1, 2.0 * c[1] / n - 1, 2.0 * c[2] / n - 1);
    p.normalize();
    p = turn * Vector3d(p.x() * 1.1, p.y() * 0.9 + 0.1 * p.x() * p.x(), p.z() * 0.8);
    return index[c] = add_vertex(m, p);
  };
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side)
      for (int u = 0; u < n; ++u)
        for (int v = 0; v < n; ++v) {
          auto corner = [&](int du, int dv) {
            std::array<int, 3> c;
            c[a] = side * n;
            c[(a + 1) % 3] = u + du;
            c[(a + 2) % 3] = v + dv;
            return vid(c);
          };
          const int p00 = corner(0, 0), p10 = corner(1, 0), p11 = corner(1, 1), p01 = corner(0, 1);
          if (side == 1) {
            add_face(m, p00, p10, p11);
            add_face(m, p00, p11, p01);
          } else {
            add_face(m, p00, p11, p10);
            add_face(m, p00, p01, p11);
          }
        }
  return m;
}

// An open, curved n by n patch (a paraboloid cap): one boundary loop.
inline Mesh open_patch(int n) {
  Mesh m;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double x = 2.0 * i / n - 1, y = 2.0 * j / n - 1;
      add_vertex(m, Vector3d(x, y, 0.4 * (x * x + y * y) + 0.1 * x * y));
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j, b = a + n + 1;
      add_face(m, a, b, b + 1);
      add_face(m, a, b + 1, a + 1);
    }
  return m;
}

// A Moebius strip: `segments` around, `rails` across; non-orientable, one boundary loop.
inline Mesh moebius(int segments, int rails) {
  Mesh m;
  for (int i = 0; i < segments; ++i) {
    const double a = 2 * kPi * i / segments;
    for (int j = 0; j < rails; ++j) {
      const double w = 0.6 * (j / double(rails - 1) - 0.5);
      add_vertex(m, Vector3d((1 + w * std::cos(a / 2)) * std::cos(a), (1 + w * std::cos(a / 2)) * std::sin(a),
                             w * std::sin(a / 2)));
    }
  }
  for (int i = 0; i < segments; ++i) {
    const int i1 = (i + 1) % segments;
    const bool seam = i1 == 0;  // crossing the seam reverses the width direction
    for (int j = 0; j + 1 < rails; ++j) {
      const int a = i * rails + j, b = a + 1;
      const int c = i1 * rails + (seam ? rails - 1 - j : j), d = i1 * rails + (seam ? rails - 2 - j : j + 1);
      add_face(m, a, c, d);
      add_face(m, a, d, b);
    }
  }
  return m;
}

inline Mesh tetrahedron(const Vector3d& at) {
  Mesh m;
  add_vertex(m, at + Vector3d(0, 0, 0));
  add_vertex(m, at + Vector3d(1, 0.1, 0.2));
  add_vertex(m, at + Vector3d(0.2, 0.9, 0.1));
  add_vertex(m, at + Vector3d(0.3, 0.2, 1.1));
  add_face(m, 0, 2, 1);
  add_face(m, 0, 1, 3);
  add_face(m, 0, 3, 2);
  add_face(m, 1, 2, 3);
  return m;
}

// ---------------------------------------------------------------------------------------------------
// Running and checking.

struct Options {
  int steps = 30;
  std::vector<int64_t> pins;
  std::vector<double> targets;  // empty: rest positions
  double lambda = 4.0;
  std::vector<PreferenceFunction> styles;  // empty: the default (cube)
  std::vector<int64_t> face_styles;        // empty: default
};

inline std::vector<double> run(const Mesh& m, const Options& o, gauss::Method method) {
  GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), o.pins,
                o.targets.empty() ? nullptr : o.targets.data(), o.lambda);
  if (!o.styles.empty()) s.set_styles(o.styles);
  if (!o.face_styles.empty()) s.set_face_styles(o.face_styles.data(), static_cast<int>(o.face_styles.size()));
  s.set_method(method);
  for (int i = 0; i < o.steps; ++i) s.step();
  std::vector<double> out(m.V.size());
  s.copy_vertices(out.data());
  EXPECT_TRUE(std::isfinite(s.arap_energy()) && std::isfinite(s.cubic_energy()));
  return out;
}

inline void expect_cubic_sane(const Mesh& m, const Options& o, const std::vector<double>& out);

// The Gauss method's result. Every mesh stylized here also goes through the cubic method (at its
// default lambda, with the same pins and styles), whose result must be just as sane: the cubic method
// survives every broken mesh the Gauss method survives.
inline std::vector<double> stylize(const Mesh& m, const Options& o = {}) {
  std::vector<double> gauss = run(m, o, gauss::Method::gauss);
  expect_cubic_sane(m, o, run(m, o, gauss::Method::cubic));
  return gauss;
}

inline std::vector<uint8_t> referenced(const Mesh& m) {
  std::vector<uint8_t> used(m.num_vertices(), 0);
  for (int f = 0; f < m.num_faces(); ++f) {
    const int64_t a = m.F[3 * f], b = m.F[3 * f + 1], c = m.F[3 * f + 2];
    if (a != b && b != c && a != c) used[a] = used[b] = used[c] = 1;
  }
  return used;
}

// Centre and longest side of the bounding box of the referenced vertices.
inline double extent(const Mesh& m, Vector3d* center = nullptr) {
  const std::vector<uint8_t> used = referenced(m);
  Vector3d lo = Vector3d::Constant(INFINITY), hi = -lo;
  for (int v = 0; v < m.num_vertices(); ++v)
    if (used[v]) {
      lo = lo.cwiseMin(point(m.V, v));
      hi = hi.cwiseMax(point(m.V, v));
    }
  if (center) *center = 0.5 * (lo + hi);
  return (hi - lo).maxCoeff();
}

// What a user would notice: a NaN, a vertex that got lost or moved although nothing references it,
// a mesh that blew up (a vertex further than `growth` bounding-box sizes from the centre).
inline void expect_sane(const Mesh& in, const std::vector<double>& out, double growth = 2.0) {
  ASSERT_EQ(out.size(), in.V.size());
  for (size_t i = 0; i < out.size(); ++i) ASSERT_TRUE(std::isfinite(out[i])) << "coordinate " << i << " = " << out[i];
  const std::vector<uint8_t> used = referenced(in);
  Vector3d center;
  const double size = extent(in, &center);
  for (int v = 0; v < in.num_vertices(); ++v) {
    if (!used[v]) {
      EXPECT_EQ(point(out, v), point(in.V, v)) << "unreferenced vertex " << v << " moved";
    } else {
      EXPECT_LE((point(out, v) - center).cwiseAbs().maxCoeff(), growth * size) << "vertex " << v << " flew away";
    }
  }
}

// Finite; unreferenced vertices bit for bit as given, pins exactly at their targets, every vertex
// within 2 sizes of the box around the mesh and the pin targets.
inline void expect_cubic_sane(const Mesh& m, const Options& o, const std::vector<double>& out) {
  ASSERT_EQ(out.size(), m.V.size());
  const std::vector<uint8_t> used = referenced(m);
  Vector3d lo = Vector3d::Constant(INFINITY), hi = -lo;
  for (int v = 0; v < m.num_vertices(); ++v)
    if (used[v]) lo = lo.cwiseMin(point(m.V, v)), hi = hi.cwiseMax(point(m.V, v));
  for (size_t i = 0; i < o.pins.size(); ++i) {
    const Vector3d target = o.targets.empty() ? point(m.V, o.pins[i]) : point(o.targets, static_cast<int>(i));
    EXPECT_EQ(point(out, static_cast<int>(o.pins[i])), target) << "cubic: pin " << o.pins[i] << " left its target";
    lo = lo.cwiseMin(target), hi = hi.cwiseMax(target);
  }
  const Vector3d center = 0.5 * (lo + hi);
  const double size = (hi - lo).maxCoeff();
  std::vector<uint8_t> pinned(m.num_vertices(), 0);
  for (int64_t p : o.pins) pinned[p] = 1;
  for (int v = 0; v < m.num_vertices(); ++v) {
    ASSERT_TRUE(point(out, v).allFinite()) << "cubic: vertex " << v;
    if (pinned[v]) continue;
    if (!used[v]) EXPECT_EQ(point(out, v), point(m.V, v)) << "cubic: unreferenced vertex " << v << " moved";
    else EXPECT_LE((point(out, v) - center).cwiseAbs().maxCoeff(), 2.0 * size) << "cubic: vertex " << v << " flew away";
  }
}

inline const std::vector<Eigen::Vector3d>& cube_normals() {
  static const PreferenceFunction g(gauss::preset_style("cube"));
  return g.normals();
}

// Area share of faces within 10 degrees of a cube normal: how much the cube style took hold.
inline double cube_share(const Mesh& m, const std::vector<double>& V) {
  return gauss::alignment_share(V.data(), m.F.data(), m.num_faces(), cube_normals(), 10.0);
}

// Largest coordinate difference between two vertex arrays, relative to `size`.
inline double max_rel_diff(const std::vector<double>& a, const std::vector<double>& b, double size) {
  double d = 0;
  for (size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d / size;
}

}  // namespace robustness_kit
