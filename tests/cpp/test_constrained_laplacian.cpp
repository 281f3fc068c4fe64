// The global step's system on its own (constrained_laplacian.h), and moving pins through GaussSolver.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cmath>
#include <random>
#include <stdexcept>

#include "gauss/solver/constrained_laplacian.h"
#include "gauss/solver/gauss_solver.h"
#include "gauss/mesh/mesh_topology.h"
#include "gauss/style/presets.h"
#include "test_expect.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_constrained_laplacian {

using gauss::ConstrainedLaplacian;
using gauss::GaussSolver;
using Eigen::Vector3d;

namespace {

// Two spheres (the second one without pins, so it gets an anchor) and an unreferenced vertex.
struct Fixture {
  gauss::TriangleMesh mesh;
  gauss::MeshTopology topo;
  std::vector<double> weight;  // positive, uneven: any SPD Laplacian will do
  std::vector<Vector3d> rest;
  std::vector<int64_t> pinned;
  std::vector<Vector3d> targets;
  int first_sphere_size = 0;

  Fixture() {
    const gauss::TriangleMesh a = gauss_test::icosphere(2), b = gauss_test::icosphere(1);
    mesh = gauss_test::beside(a, b);
    first_sphere_size = a.num_vertices();
    mesh.V.insert(mesh.V.end(), {5.0, 5.0, 5.0});
    topo = gauss::build_mesh_topology(mesh.num_vertices(), mesh.F.data(), mesh.num_faces());
    for (size_t e = 0; e < topo.edges.size(); ++e) weight.push_back(0.5 + 0.1 * static_cast<double>(e % 7));
    for (int v = 0; v < mesh.num_vertices(); ++v) rest.emplace_back(&mesh.V[3 * v]);
    for (int64_t v : {3, 40, 77, 100}) {
      pinned.push_back(v);
      targets.push_back(rest[v] + Vector3d(0.2, -0.1, 0.05 * static_cast<double>(v % 3)));
    }
  }
};

// The same solve with Eigen: the full Laplacian, fixed rows eliminated by hand, SimplicialLDLT.
std::vector<Vector3d> reference_solve(const Fixture& fx, const std::vector<Vector3d>& targets,
                                      const std::vector<Vector3d>& b) {
  const int nV = fx.mesh.num_vertices();
  std::vector<int> fixed(nV, 0);
  std::vector<Vector3d> X = fx.rest;
  for (size_t i = 0; i < fx.pinned.size(); ++i) fixed[fx.pinned[i]] = 1, X[fx.pinned[i]] = targets[i];
  fixed[fx.first_sphere_size] = 1;  // the second sphere's anchor: its first vertex, at rest
  fixed[nV - 1] = 1;                // unreferenced
  std::vector<int> index(nV, -1);
  int n = 0;
  for (int v = 0; v < nV; ++v)
    if (!fixed[v]) index[v] = n++;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs(n, 3);
  for (int v = 0; v < nV; ++v)
    if (index[v] >= 0) rhs.row(index[v]) = b[v].transpose();
  for (size_t e = 0; e < fx.topo.edges.size(); ++e) {
    const int p = fx.topo.edges[e][0], q = fx.topo.edges[e][1];
    const double w = fx.weight[e];
    for (auto [i, j] : {std::make_pair(p, q), std::make_pair(q, p)}) {
      if (index[i] < 0) continue;
      entries.emplace_back(index[i], index[i], w);
      if (index[j] >= 0) entries.emplace_back(index[i], index[j], -w);
      else rhs.row(index[i]) += w * X[j].transpose();
    }
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(L);
  const Eigen::MatrixXd x = ldlt.solve(rhs);
  for (int v = 0; v < nV; ++v)
    if (index[v] >= 0) X[v] = x.row(index[v]).transpose();
  // The free sphere keeps its rest centroid.
  Vector3d now = Vector3d::Zero(), then = Vector3d::Zero();
  for (int v = fx.first_sphere_size; v < nV - 1; ++v) now += X[v], then += fx.rest[v];
  for (int v = fx.first_sphere_size; v < nV - 1; ++v) X[v] += (then - now) / (nV - 1 - fx.first_sphere_size);
  return X;
}

std::vector<Vector3d> solve(ConstrainedLaplacian& L, const std::vector<Vector3d>& rest, const std::vector<Vector3d>& b) {
  std::vector<Vector3d> X = rest;
  L.place_pins(X);
  for (int u = 0; u < L.num_unknowns(); ++u) L.set_rhs(u, L.constant_rhs(u) + b[L.vertex_of_unknown(u)]);
  L.solve(X);
  return X;
}

std::vector<Vector3d> some_rhs(int n) {
  std::mt19937 rng(2);
  std::normal_distribution<double> normal;
  std::vector<Vector3d> b(n);
  for (Vector3d& x : b) x = 0.1 * Vector3d(normal(rng), normal(rng), normal(rng));
  return b;
}

double max_difference(const std::vector<Vector3d>& a, const std::vector<Vector3d>& b) {
  double d = 0;
  for (size_t i = 0; i < a.size(); ++i) d = std::max(d, (a[i] - b[i]).norm());
  return d;
}

}  // namespace

TEST(ConstrainedLaplacian, SolvesLikeEigensLDLTWithPinsAnchorsAndCentring) {
  const Fixture fx;
  ConstrainedLaplacian L(fx.topo, fx.weight, fx.rest, fx.pinned, fx.targets);
  EXPECT_EQ(L.num_unknowns(), fx.mesh.num_vertices() - 4 - 1 - 1);  // pins, one anchor, unreferenced
  const std::vector<Vector3d> b = some_rhs(fx.mesh.num_vertices());
  const std::vector<Vector3d> X = solve(L, fx.rest, b), expected = reference_solve(fx, fx.targets, b);
  EXPECT_LT(max_difference(X, expected), 1e-12);
  for (size_t i = 0; i < fx.pinned.size(); ++i) EXPECT_EQ(X[fx.pinned[i]], fx.targets[i]);
  EXPECT_EQ(X.back(), fx.rest.back());  // the unreferenced vertex is not touched
}

TEST(ConstrainedLaplacian, MovingPinsEqualsRebuildingWithoutRefactoring) {
  const Fixture fx;
  std::vector<Vector3d> moved = fx.targets;
  for (Vector3d& t : moved) t += Vector3d(-0.3, 0.4, 0.1);
  ConstrainedLaplacian L(fx.topo, fx.weight, fx.rest, fx.pinned, fx.targets);
  L.set_pin_positions(moved);
  ConstrainedLaplacian rebuilt(fx.topo, fx.weight, fx.rest, fx.pinned, moved);
  for (int u = 0; u < L.num_unknowns(); ++u) ASSERT_EQ(L.constant_rhs(u), rebuilt.constant_rhs(u)) << u;
  const std::vector<Vector3d> b = some_rhs(fx.mesh.num_vertices());
  const std::vector<Vector3d> X = solve(L, fx.rest, b);
  EXPECT_EQ(max_difference(X, solve(rebuilt, fx.rest, b)), 0.0);  // bit for bit
  EXPECT_LT(max_difference(X, reference_solve(fx, moved, b)), 1e-12);
  EXPECT_THROW(L.set_pin_positions({Vector3d::Zero()}), std::invalid_argument);
}

TEST(ConstrainedLaplacian, RefusesInconsistentSizes) {
  const Fixture fx;
  EXPECT_THROW(ConstrainedLaplacian(fx.topo, fx.weight, fx.rest, fx.pinned, {}), std::invalid_argument);
  EXPECT_THROW(ConstrainedLaplacian(fx.topo, {1.0, 2.0}, fx.rest, {}, {}), std::invalid_argument);
  EXPECT_THROW(ConstrainedLaplacian(fx.topo, fx.weight, {Vector3d::Zero()}, {}, {}), std::invalid_argument);
}

// ---- Through GaussSolver: dragging pins. ----

namespace {

struct PinnedSphere {
  gauss::TriangleMesh m = gauss_test::icosphere(3);
  std::vector<int64_t> pins;
  std::vector<double> targets, moved;
  PinnedSphere() {
    for (int v = 0; v < m.num_vertices(); ++v)
      if (m.V[3 * v + 2] < -0.8 || m.V[3 * v + 2] > 0.9) {
        pins.push_back(v);
        for (int k = 0; k < 3; ++k) {
          targets.push_back(m.V[3 * v + k]);
          moved.push_back(m.V[3 * v + k] + (m.V[3 * v + 2] > 0 && k == 0 ? 0.3 : 0.0));  // drag the top along x
        }
      }
  }
  GaussSolver solver(const std::vector<double>& t) const {
    return GaussSolver(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), pins, t.data());
  }
  int num_pins() const { return static_cast<int>(pins.size()); }
};

std::vector<double> vertices(const GaussSolver& s) {
  std::vector<double> out(3 * static_cast<size_t>(s.num_vertices()));
  s.copy_vertices(out.data());
  return out;
}

}  // namespace

TEST(GaussSolverPins, MovingPinsDoesNotRefactorAndEqualsASolverBuiltWithTheTargets) {
  const PinnedSphere p;
  GaussSolver dragged = p.solver(p.targets), built = p.solver(p.moved);
  dragged.set_pin_positions(p.moved.data(), p.num_pins());
  EXPECT_EQ(dragged.factorization_count(), 1);
  for (int i = 0; i < 20; ++i) {
    dragged.step();
    built.step();
  }
  EXPECT_EQ(vertices(dragged), vertices(built));  // bit for bit
  EXPECT_EQ(dragged.factorization_count(), 1);
  EXPECT_EQ(dragged.pinned(), p.pins);
  for (int i = 0; i < p.num_pins(); ++i) EXPECT_EQ(dragged.pin_positions()[i], Vector3d(&p.moved[3 * i]));
}

TEST(GaussSolverPins, DuringARunThePinsJumpAndTheMeshFollows) {
  const PinnedSphere p;
  GaussSolver s = p.solver(p.targets);
  for (int i = 0; i < 10; ++i) s.step();
  const std::vector<double> before = vertices(s);
  s.set_pin_positions(p.moved.data(), p.num_pins());
  s.step();
  const std::vector<double> after = vertices(s);
  for (int i = 0; i < p.num_pins(); ++i)
    for (int k = 0; k < 3; ++k) ASSERT_EQ(after[3 * p.pins[i] + k], p.moved[3 * i + k]);
  // The free vertices near the dragged top moved along with it.
  double shift = 0;
  int count = 0;
  for (int v = 0; v < p.m.num_vertices(); ++v)
    if (p.m.V[3 * v + 2] > 0.5 && p.m.V[3 * v + 2] <= 0.9) shift += after[3 * v] - before[3 * v], ++count;
  EXPECT_GT(shift / count, 0.01);  // measured: 0.03 after one step (the pins moved 0.3)
  // And moving them back and resetting gives the original run again.
  s.set_pin_positions(p.targets.data(), p.num_pins());
  s.reset();
  GaussSolver fresh = p.solver(p.targets);
  for (int i = 0; i < 10; ++i) s.step(), fresh.step();
  EXPECT_EQ(vertices(s), vertices(fresh));
}

TEST(GaussSolverPins, BadTargetsAreRefusedAndChangeNothing) {
  const PinnedSphere p;
  GaussSolver reference = p.solver(p.targets), s = p.solver(p.targets);
  auto refused = [&](std::vector<double> t, int count, const std::string& words) {
    gauss_test::expect_refused([&] { s.set_pin_positions(t.empty() ? nullptr : t.data(), count); }, words);
  };
  refused(p.moved, p.num_pins() - 1, "one row per pinned vertex");
  refused({}, p.num_pins(), "one row per pinned vertex");
  std::vector<double> bad = p.moved;
  bad[4] = NAN;
  refused(bad, p.num_pins(), "NaN");
  bad[4] = -INFINITY;
  refused(bad, p.num_pins(), "NaN or infinite");
  bad[4] = 1e13;  // the mesh is 2 wide
  refused(bad, p.num_pins(), "too far");
  for (int i = 0; i < 5; ++i) s.step(), reference.step();
  EXPECT_EQ(vertices(s), vertices(reference));
  EXPECT_EQ(s.factorization_count(), 1);
  // No pins: nothing to move, and that is fine.
  GaussSolver unpinned(p.m.V.data(), p.m.num_vertices(), p.m.F.data(), p.m.num_faces());
  unpinned.set_pin_positions(nullptr, 0);
  EXPECT_THROW(unpinned.set_pin_positions(p.moved.data(), 1), std::invalid_argument);
}

}  // namespace test_constrained_laplacian
