// GaussSolver::set_vertices: a warm start for the next step (animation bakes), without touching the
// rest shape or the factorization.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "gauss/settings.h"
#include "gauss/solver/gauss_solver.h"
#include "test_expect.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_set_vertices {

using gauss::GaussSolver;

namespace {

std::vector<double> vertices(const GaussSolver& s) {
  std::vector<double> out(3 * static_cast<size_t>(s.num_vertices()));
  s.copy_vertices(out.data());
  return out;
}

GaussSolver make(const gauss::TriangleMesh& m, const std::vector<int64_t>& pins = {}, const double* targets = nullptr) {
  return GaussSolver(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), pins, targets);
}

}  // namespace

TEST(SetVertices, TheStepsThatFollowDependOnTheVerticesAlone) {
  const gauss::TriangleMesh m = gauss_test::icosphere(3);
  GaussSolver a = make(m);
  for (int i = 0; i < 15; ++i) a.step();
  const std::vector<double> midway = vertices(a);
  a.set_vertices(midway.data(), m.num_vertices());
  EXPECT_EQ(vertices(a), midway);
  EXPECT_EQ(a.step_count(), 15);  // kept
  GaussSolver b = make(m);
  b.set_vertices(midway.data(), m.num_vertices());
  for (int i = 0; i < 10; ++i) a.step(), b.step();
  EXPECT_EQ(vertices(a), vertices(b));  // bit for bit, whatever a did before
  EXPECT_EQ(a.factorization_count(), 1);
  // The rest shape stays: reset() goes back to it, and the input as a warm start is a fresh run.
  a.reset();
  EXPECT_EQ(a.step_count(), 0);
  for (size_t i = 0; i < m.V.size(); ++i) EXPECT_NEAR(vertices(a)[i], m.V[i], 1e-12);
  GaussSolver fresh = make(m), from_input = make(m);
  from_input.set_vertices(m.V.data(), m.num_vertices());
  for (int i = 0; i < 10; ++i) fresh.step(), from_input.step();
  EXPECT_EQ(vertices(fresh), vertices(from_input));
}

TEST(SetVertices, TheCubicMethodsStepsDependOnTheVerticesAloneToo) {
  // Its per-vertex ADMM carries state from step to step; set_vertices drops it as reset() does.
  const gauss::TriangleMesh m = gauss_test::icosphere(3);
  GaussSolver a = make(m), b = make(m);
  a.set_method(gauss::Method::cubic);
  b.set_method(gauss::Method::cubic);
  for (int i = 0; i < 15; ++i) a.step();
  const std::vector<double> midway = vertices(a);
  a.set_vertices(midway.data(), m.num_vertices());
  b.set_vertices(midway.data(), m.num_vertices());
  for (int i = 0; i < 10; ++i) a.step(), b.step();
  EXPECT_EQ(vertices(a), vertices(b));
}

TEST(SetVertices, AConvergedResultAsWarmStartIsAlmostConverged) {
  const gauss::TriangleMesh m = gauss_test::icosphere(3);
  GaussSolver a = make(m);
  const int cold = a.step_until(1e-3, 2000);
  const std::vector<double> result = vertices(a);
  GaussSolver b = make(m);
  b.set_vertices(result.data(), m.num_vertices());
  const int warm = b.step_until(1e-3, 2000);
  EXPECT_LT(warm, cold / 4) << "cold " << cold << ", warm " << warm;
}

TEST(SetVertices, AWarmStartKeepsItsLookWithResolutionIndependent) {
  // The bending term reads the last step's rotations. On a mesh much finer than the reference face
  // area (here a reference 40 times the faces' area) it outweighs each vertex's own fit, and a warm
  // start left with the rest shape's identity rotations drifted 17% of its displacement back towards
  // the rest shape within a few steps (ARAP's own fit of the shape alone: 9%; with 15 sweeps of the fit
  // with the bending term: 1.8%, with 30: 0.6%).
  const gauss::TriangleMesh m = gauss_test::icosphere(4);
  const auto fine = [&] {
    GaussSolver s = make(m);
    s.set_resolution_independent(true);
    s.set_reference_face_area(40 * gauss::settings::reference_face_area);
    return s;
  };
  GaussSolver a = fine();
  a.step_until(1e-4, 3000);
  const std::vector<double> result = vertices(a);
  const auto apart = [](const std::vector<double>& x, const std::vector<double>& y) {  // summed distance
    double sum = 0;
    for (size_t i = 0; i < x.size(); i += 3) sum += std::hypot(x[i] - y[i], x[i + 1] - y[i + 1], x[i + 2] - y[i + 2]);
    return sum;
  };
  const double displaced = apart(result, m.V);
  GaussSolver b = fine();
  b.set_vertices(result.data(), m.num_vertices());
  for (int k = 0; k < 10; ++k) {
    b.step();
    EXPECT_LT(apart(vertices(b), result), 0.03 * displaced) << "step " << k + 1 << " from the converged result";
  }
}

TEST(SetVertices, PinsStayAtTheirTargetsAndUnusedVerticesAsGiven) {
  gauss::TriangleMesh m = gauss_test::icosphere(2);
  m.V.insert(m.V.end(), {5.0, 6.0, 7.0});  // no face uses it
  const std::vector<int64_t> pins = {0, 3};
  const double targets[6] = {0.1, 1.1, 0.2, -0.3, 0.4, 1.2};
  GaussSolver s = make(m, pins, targets);
  std::vector<double> moved = m.V;
  for (size_t i = 0; i < moved.size(); ++i) moved[i] = 2.0 * moved[i] + 0.25;
  s.set_vertices(moved.data(), m.num_vertices());
  const std::vector<double> out = vertices(s);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(out[k], targets[k]);
    EXPECT_EQ(out[9 + k], targets[3 + k]);
    EXPECT_EQ(out[out.size() - 3 + k], m.V[m.V.size() - 3 + k]);
  }
  EXPECT_NEAR(out[6], moved[6], 1e-12);  // a free vertex is where it was put
  s.step();
  EXPECT_EQ(vertices(s)[0], targets[0]);
}

TEST(SetVertices, BadVerticesAreRefusedWithoutEffect) {
  const gauss::TriangleMesh m = gauss_test::icosphere(2);
  GaussSolver s = make(m);
  s.step();
  const std::vector<double> before = vertices(s);
  std::vector<double> bad = m.V;
  gauss_test::expect_refused([&] { s.set_vertices(bad.data(), m.num_vertices() - 1); }, "one row per vertex");
  gauss_test::expect_refused([&] { s.set_vertices(nullptr, m.num_vertices()); }, "one row per vertex");
  bad[3 * 7 + 1] = NAN;
  gauss_test::expect_refused([&] { s.set_vertices(bad.data(), m.num_vertices()); }, "vertex 7 has a NaN");
  bad[3 * 7 + 1] = INFINITY;
  gauss_test::expect_refused([&] { s.set_vertices(bad.data(), m.num_vertices()); }, "vertex 7 has a NaN");
  bad[3 * 7 + 1] = 1e20;
  gauss_test::expect_refused([&] { s.set_vertices(bad.data(), m.num_vertices()); }, "vertex 7 is too far");
  EXPECT_EQ(vertices(s), before);
  EXPECT_LT(s.last_reldv(), INFINITY);  // not even the convergence state changed
}

}  // namespace test_set_vertices
