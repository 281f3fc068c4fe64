#pragma once
// What a fuzz input decodes into (fuzz_reader.h reads the bytes): the mesh (built shapes and arbitrary
// arrays, with arbitrary indices and coordinates), the pins and their targets, and styles from presets
// or from arbitrary normals, rings, sigma, mu and rotation.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "fuzz_reader.h"
#include "gauss/style/preference_function.h"
#include "gauss/style/presets.h"

namespace gauss_fuzz {

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
  std::vector<double> target;   // empty: the rest positions
  std::vector<double> earlier;  // #E by 3: the targets of the session's earlier pins (see retire())
};

// `next` replaces `old` as the session's pins: old's targets join the earlier ones. A vertex pinned far
// away and then let go springs back over steps, not at once, so the bound must keep its old place.
inline void retire(Pins& next, const Pins& old, const Mesh& m) {
  next.earlier = old.earlier;
  for (size_t i = 0; i < old.index.size(); ++i)
    for (int k = 0; k < 3; ++k)
      next.earlier.push_back(old.target.empty() ? m.V[3 * old.index[i] + k] : old.target[3 * i + k]);
}

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

}  // namespace gauss_fuzz
