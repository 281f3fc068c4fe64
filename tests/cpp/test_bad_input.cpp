#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gauss/solver/gauss_solver.h"
#include "test_expect.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_bad_input {

using gauss::GaussSolver;

using gauss_test::expect_refused;

TEST(BadInput, EveryProblemHasItsOwnMessage) {
  gauss::TriangleMesh m = gauss_test::icosphere(1);
  const int nV = m.num_vertices(), nF = m.num_faces();
  expect_refused([&] { GaussSolver(m.V.data(), 0, m.F.data(), nF); }, "no vertices");
  expect_refused([&] { GaussSolver(m.V.data(), nV, m.F.data(), 0); }, "no faces");
  auto F = m.F;
  F[7] = nV;
  expect_refused([&] { GaussSolver(m.V.data(), nV, F.data(), nF); }, "refers to vertex");
  F[7] = -1;
  expect_refused([&] { GaussSolver(m.V.data(), nV, F.data(), nF); }, "refers to vertex");
  auto V = m.V;
  V[5] = NAN;
  expect_refused([&] { GaussSolver(V.data(), nV, m.F.data(), nF); }, "NaN");
  V[5] = INFINITY;
  expect_refused([&] { GaussSolver(V.data(), nV, m.F.data(), nF); }, "NaN or infinite");
  std::vector<double> same(m.V.size(), 1.0);
  expect_refused([&] { GaussSolver(same.data(), nV, m.F.data(), nF); }, "extent");
  std::vector<int64_t> degenerate = {0, 0, 1, 2, 2, 2};
  expect_refused([&] { GaussSolver(m.V.data(), nV, degenerate.data(), 2); }, "no usable triangle");
  expect_refused([&] { GaussSolver(m.V.data(), nV, m.F.data(), nF, {nV}); }, "out of range");
  expect_refused([&] { GaussSolver(m.V.data(), nV, m.F.data(), nF, {3, 3}); }, "more than once");
  std::vector<double> target = {NAN, 0, 0};
  expect_refused([&] { GaussSolver(m.V.data(), nV, m.F.data(), nF, {3}, target.data()); }, "NaN");
  expect_refused([&] { GaussSolver(m.V.data(), nV, m.F.data(), nF, {}, nullptr, -1); }, "lambda");
  expect_refused([&] { GaussSolver(m.V.data(), nV, m.F.data(), nF, {}, nullptr, NAN); }, "lambda");

  GaussSolver s(m.V.data(), nV, m.F.data(), nF);
  expect_refused([&] { s.set_lambda(-2); }, "lambda");
  expect_refused([&] { s.set_admm_iterations(0); }, "ADMM");
  std::vector<int64_t> styles(nF, 1);
  expect_refused([&] { s.set_face_styles(styles.data(), nF); }, "valid: -1");
  expect_refused([&] { s.set_face_styles(styles.data(), nF - 1); }, "one entry per face");
  expect_refused([&] { s.set_style(3, gauss::PreferenceFunction(gauss::StyleParams{{Eigen::Vector3d::UnitX()}})); },
                 "out of range");
  expect_refused([&] { s.set_styles({}); }, "styles were given");
  // The solver is untouched by the rejected calls.
  s.step();
  std::vector<double> out(m.V.size());
  s.copy_vertices(out.data());
  for (double x : out) EXPECT_TRUE(std::isfinite(x));
}

}  // namespace test_bad_input
