// Keep Volume (volume_keeper.h, GaussSolver::set_keep_volume): closed components keep their volume,
// open ones their area; pinned and degenerate components are left alone.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "gauss/solver/gauss_solver.h"
#include "gauss/mesh/mesh_topology.h"
#include "gauss/solver/volume_keeper.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_volume_keeper {

using Eigen::Vector3d;
using gauss::GaussSolver;
using gauss::TriangleMesh;

namespace {

double volume(const std::vector<double>& V, const std::vector<int64_t>& F, size_t first = 0, size_t end = SIZE_MAX) {
  double sum = 0;
  for (size_t f = first; f < std::min(end, F.size() / 3); ++f) {
    const Vector3d a(&V[3 * F[3 * f]]), b(&V[3 * F[3 * f + 1]]), c(&V[3 * F[3 * f + 2]]);
    sum += a.dot(b.cross(c)) / 6.0;
  }
  return sum;
}

double area(const std::vector<double>& V, const std::vector<int64_t>& F) {
  double sum = 0;
  for (size_t f = 0; f < F.size() / 3; ++f) {
    const Vector3d a(&V[3 * F[3 * f]]), b(&V[3 * F[3 * f + 1]]), c(&V[3 * F[3 * f + 2]]);
    sum += 0.5 * (b - a).cross(c - a).norm();
  }
  return sum;
}

// Runs until converged (reldV < 1e-3) with or without Keep Volume; returns the vertices.
std::vector<double> converged(const TriangleMesh& m, bool keep, const std::vector<int64_t>& pins = {}) {
  GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), pins);
  s.set_keep_volume(keep);
  EXPECT_EQ(s.keep_volume(), keep);
  EXPECT_LT(s.step_until(1e-3, 2000), 2000);
  std::vector<double> out(m.V.size());
  s.copy_vertices(out.data());
  return out;
}

// The faces of `m` whose centroid lies below height z: an open cap of a sphere.
TriangleMesh cut_below(const TriangleMesh& m, double z) {
  TriangleMesh out = m;
  out.F.clear();
  for (int f = 0; f < m.num_faces(); ++f) {
    double h = 0;
    for (int k = 0; k < 3; ++k) h += m.V[3 * m.F[3 * f + k] + 2] / 3;
    if (h < z) out.F.insert(out.F.end(), &m.F[3 * f], &m.F[3 * f] + 3);
  }
  return out;
}

}  // namespace

TEST(KeepVolume, AClosedMeshKeepsItsVolume) {
  const TriangleMesh sphere = gauss_test::icosphere(3);
  const double rest = volume(sphere.V, sphere.F);
  // Measured: the cube style shrinks the sphere to 0.77 of its volume.
  EXPECT_LT(volume(converged(sphere, false), sphere.F), 0.9 * rest);
  EXPECT_NEAR(volume(converged(sphere, true), sphere.F), rest, 1e-9 * rest);
}

TEST(KeepVolume, AnOpenMeshKeepsItsArea) {
  const TriangleMesh cap = cut_below(gauss_test::icosphere(3), 0.3);
  const double rest = area(cap.V, cap.F);
  EXPECT_LT(area(converged(cap, false), cap.F), 0.98 * rest);  // measured 0.963
  EXPECT_NEAR(area(converged(cap, true), cap.F), rest, 1e-9 * rest);
}

TEST(KeepVolume, PinnedComponentsAreLeftAlone) {
  // Two spheres; the second has a pin.
  const TriangleMesh a = gauss_test::icosphere(3);
  const TriangleMesh m = gauss_test::beside(a, a);
  const int offset = a.num_vertices();
  const std::vector<int64_t> pins = {offset};
  const std::vector<double> kept = converged(m, true, pins), plain = converged(m, false, pins);
  const size_t nF = a.F.size() / 3;
  EXPECT_NEAR(volume(kept, m.F, 0, nF), volume(m.V, m.F, 0, nF), 1e-9);
  const double pinned_rest = volume(m.V, m.F, nF);
  EXPECT_LT(volume(kept, m.F, nF), 0.95 * pinned_rest);  // it shrank like without Keep Volume
  EXPECT_LT(volume(plain, m.F, nF), 0.95 * pinned_rest);
}

TEST(KeepVolume, TheKeeperScalesBackButLeavesDegenerateAndBrokenComponentsAlone) {
  // Component 0: a tetrahedron; component 1: two triangles back to back (closed, no volume).
  std::vector<Vector3d> rest = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {3, 0, 0}, {4, 0, 0}, {3, 1, 0}};
  const int64_t F[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 4, 5, 6, 4, 6, 5};
  const gauss::MeshTopology topo = gauss::build_mesh_topology(7, F, 6);
  gauss::VolumeKeeper keeper(topo, rest, {});
  EXPECT_EQ(keeper.num_kept(), 1);
  EXPECT_EQ(keeper.num_closed(), 1);
  const Vector3d centroid(0.25, 0.25, 0.25);
  std::vector<Vector3d> X = rest;
  for (int v = 0; v < 4; ++v) X[v] = centroid + 0.5 * (rest[v] - centroid);  // an eighth of the volume
  X[5] = Vector3d(4, 0, 0.5);                                                // the flat pair moved
  std::vector<Vector3d> restored = X;
  keeper.restore(topo, restored);
  for (int v = 0; v < 4; ++v) EXPECT_LT((restored[v] - rest[v]).norm(), 1e-12) << v;
  for (int v = 4; v < 7; ++v) EXPECT_EQ(restored[v], X[v]) << v;
  // Turned inside out, or shrunk beyond kMaxRatio: not corrected (no division by ~0, no blow-up).
  for (double s : {-1.0, 0.4 / std::cbrt(gauss::VolumeKeeper::kMaxRatio)}) {
    std::vector<Vector3d> Y = rest;
    for (int v = 0; v < 4; ++v) Y[v] = centroid + s * (rest[v] - centroid);
    std::vector<Vector3d> before = Y;
    keeper.restore(topo, Y);
    EXPECT_EQ(Y, before) << "scale " << s;
  }
  // A pinned component is not kept.
  EXPECT_EQ(gauss::VolumeKeeper(topo, rest, {2}).num_kept(), 0);
}

TEST(KeepVolume, ATurnOnOrOffIsAnEditAndACubeStaysACube) {
  const TriangleMesh cube = gauss_test::grid_cube(4);
  GaussSolver s(cube.V.data(), cube.num_vertices(), cube.F.data(), cube.num_faces());
  s.set_keep_volume(true);
  EXPECT_EQ(s.step_until(1e-3, 100), 1);
  std::vector<double> out(cube.V.size());
  s.copy_vertices(out.data());
  for (size_t i = 0; i < out.size(); ++i) EXPECT_NEAR(out[i], cube.V[i], 1e-9);
  s.set_keep_volume(false);
  EXPECT_FALSE(s.converged());
}

}  // namespace test_volume_keeper
