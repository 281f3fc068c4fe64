#pragma once
// Meshes the C++ tests build in code, so the suite does not depend on ../shared for its core checks.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "gauss/mesh/mesh_io.h"

namespace gauss_test {

// Unit icosphere with `levels` 1:4 subdivisions (levels = 3: 642 vertices, 1280 faces).
inline gauss::TriangleMesh icosphere(int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& p : v) p.normalize();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return mid[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> g;
    for (auto& tri : f) {
      const int a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]), c = midpoint(tri[2], tri[0]);
      g.push_back({tri[0], a, c});
      g.push_back({tri[1], b, a});
      g.push_back({tri[2], c, b});
      g.push_back({a, b, c});
    }
    f = g;
  }
  gauss::TriangleMesh m;
  for (auto& p : v) m.V.insert(m.V.end(), {p.x(), p.y(), p.z()});
  for (auto& tri : f) m.F.insert(m.F.end(), {tri[0], tri[1], tri[2]});
  return m;
}

// Closed cube [-1,1]^3 with an n x n grid of quads (two triangles each) on every side, outward normals.
inline gauss::TriangleMesh grid_cube(int n) {
  gauss::TriangleMesh m;
  std::map<std::array<long, 3>, int> index;
  auto vertex = [&](const Eigen::Vector3d& p) {
    std::array<long, 3> key = {std::lround(p.x() * 1e6), std::lround(p.y() * 1e6), std::lround(p.z() * 1e6)};
    auto it = index.find(key);
    if (it != index.end()) return it->second;
    m.V.insert(m.V.end(), {p.x(), p.y(), p.z()});
    return index[key] = m.num_vertices() - 1;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      Eigen::Vector3d nrm = Eigen::Vector3d::Zero();
      nrm[axis] = sign;
      Eigen::Vector3d u = Eigen::Vector3d::Zero(), w = Eigen::Vector3d::Zero();
      u[(axis + 1) % 3] = 1;
      w[(axis + 2) % 3] = 1;
      if (sign < 0) std::swap(u, w);  // keep (u x w) = outward normal
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          auto P = [&](int a, int b) { return Eigen::Vector3d(nrm + u * (-1 + 2.0 * a / n) + w * (-1 + 2.0 * b / n)); };
          const int p00 = vertex(P(i, j)), p10 = vertex(P(i + 1, j)), p11 = vertex(P(i + 1, j + 1)), p01 = vertex(P(i, j + 1));
          m.F.insert(m.F.end(), {p00, p10, p11, p00, p11, p01});
        }
    }
  return m;
}

// One mesh of two components: `a`, and `b` moved by 3 along x (the vertices of b follow a's).
inline gauss::TriangleMesh beside(const gauss::TriangleMesh& a, const gauss::TriangleMesh& b) {
  gauss::TriangleMesh m = a;
  const int64_t offset = a.num_vertices();
  for (size_t i = 0; i < b.V.size(); ++i) m.V.push_back(b.V[i] + (i % 3 == 0 ? 3.0 : 0.0));
  for (int64_t i : b.F) m.F.push_back(i + offset);
  return m;
}

// Two thin plates (grid_cube(n) squashed to 1 x 0.05 x 0.3) leaning towards each other like an upside
// down V, their near ends 0.08 apart: a style that turns each flat swings their near ends into each
// other (the guard's and the contact springs' tests).
inline gauss::TriangleMesh leaning_plates(int n) {
  gauss::TriangleMesh out;
  for (const double side : {-1.0, 1.0}) {
    gauss::TriangleMesh m = grid_cube(n);
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(-side * 35 * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const int64_t offset = out.num_vertices();
    for (int v = 0; v < m.num_vertices(); ++v) {
      const Eigen::Vector3d p = turn * Eigen::Vector3d(0.5 * m.V[3 * v], 0.025 * m.V[3 * v + 1], 0.15 * m.V[3 * v + 2]);
      out.V.insert(out.V.end(), {p.x() + side * 0.45, p.y(), p.z()});
    }
    for (int64_t i : m.F) out.F.push_back(i + offset);
  }
  return out;
}

inline std::string shared_mesh(const std::string& rel) { return std::string(GAUSS_MESH_DIR) + "/" + rel; }

// A mesh's faces and a flat #V*3 coordinate array in the forms the collision code takes.
inline std::vector<std::array<int, 3>> faces_of(const gauss::TriangleMesh& m) {
  std::vector<std::array<int, 3>> f;
  for (int i = 0; i < m.num_faces(); ++i)
    f.push_back({static_cast<int>(m.F[3 * i]), static_cast<int>(m.F[3 * i + 1]), static_cast<int>(m.F[3 * i + 2])});
  return f;
}

inline std::vector<Eigen::Vector3d> points_of(const std::vector<double>& flat) {
  std::vector<Eigen::Vector3d> p(flat.size() / 3);
  for (size_t v = 0; v < p.size(); ++v) p[v] = Eigen::Vector3d(flat[3 * v], flat[3 * v + 1], flat[3 * v + 2]);
  return p;
}

// A surface of revolution about z with `sides` sides (tests/common/flat_meshes.py builds the same):
// profile (r, z) from bottom to top; an end at r == 0 is a pole, an end at r > 0 is closed by a flat
// disk of `disk_rings` rings. Outward normals.
inline gauss::TriangleMesh revolve(const std::vector<std::array<double, 2>>& profile, int sides, int disk_rings) {
  std::vector<std::array<double, 2>> rings;  // (r, z) from bottom to top; r == 0 is a pole
  const auto disk = [&](double r, double z, bool inward) {  // the rings inside radius r, a pole at the centre
    for (int i = 0; i < disk_rings; ++i) {
      const int k = inward ? disk_rings - 1 - i : i;
      rings.push_back({r * k / disk_rings, z});
    }
  };
  if (profile.front()[0] > 0) disk(profile.front()[0], profile.front()[1], false);
  rings.insert(rings.end(), profile.begin(), profile.end());
  if (profile.back()[0] > 0) disk(profile.back()[0], profile.back()[1], true);
  gauss::TriangleMesh m;
  std::vector<int> start;
  for (const auto& ring : rings) {
    start.push_back(m.num_vertices());
    const int n = ring[0] > 0 ? sides : 1;
    for (int j = 0; j < n; ++j) {
      const double a = 2 * 3.14159265358979323846 * j / sides;
      m.V.insert(m.V.end(), {ring[0] * std::cos(a), ring[0] * std::sin(a), ring[1]});
    }
  }
  for (size_t i = 0; i + 1 < rings.size(); ++i)
    for (int j = 0; j < sides; ++j) {
      const int k = (j + 1) % sides;
      const bool pole_a = rings[i][0] == 0, pole_b = rings[i + 1][0] == 0;
      const int a0 = start[i] + (pole_a ? 0 : j), a1 = start[i] + (pole_a ? 0 : k);
      const int b0 = start[i + 1] + (pole_b ? 0 : j), b1 = start[i + 1] + (pole_b ? 0 : k);
      if (!pole_a) m.F.insert(m.F.end(), {a0, a1, b1});
      if (!pole_b) m.F.insert(m.F.end(), {a0, b1, b0});
    }
  return m;
}

// A capped cylinder of radius 1 and height 2 with 32 sides, subdivided: 16 rows, caps of 8 rings.
inline gauss::TriangleMesh capped_cylinder() {
  std::vector<std::array<double, 2>> profile;
  for (int i = 0; i <= 16; ++i) profile.push_back({1.0, -1.0 + 2.0 * i / 16});
  return revolve(profile, 32, 8);
}

// A pot: a round belly (radius 1.2) closed at the bottom, a short upright neck of radius 0.72, and a
// flat lid, the one flat region, smaller than the belly.
inline gauss::TriangleMesh pot() {
  std::vector<std::array<double, 2>> profile;
  const double top = std::acos(-0.8);
  for (int i = 0; i <= 20; ++i) {
    const double t = top * i / 20;
    profile.push_back({1.2 * std::sin(t), -0.1 - std::cos(t)});
  }
  for (int i = 1; i <= 3; ++i) profile.push_back({1.2 * 0.6, 0.7 + 0.2 * i / 3});
  return revolve(profile, 32, 6);
}

}  // namespace gauss_test
