// Running until converged: reldV (fixed_point_iteration.h), step_until, converged, and edits that
// make a converged run step again.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "gauss/solver/fixed_point_iteration.h"
#include "gauss/solver/gauss_solver.h"
#include "gauss/style/presets.h"
#include "gauss/settings.h"
#include "test_expect.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_convergence {

using Eigen::Vector3d;
using gauss::GaussSolver;

namespace {

GaussSolver sphere_solver(const gauss::TriangleMesh& m) {
  return GaussSolver(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
}

}  // namespace

TEST(RelativeChange, IsTheLargestCoordinateChangeOverTheLargestDisplacement) {
  const std::vector<Vector3d> rest = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<Vector3d> previous = {{0, 0, 0.5}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<Vector3d> current = {{0, 0, 0.4}, {1, -0.2, 0}, {0, 1, 0}};
  // Largest change: 0.2 (vertex 1, y); largest displacement: 0.4 (vertex 0, z).
  EXPECT_DOUBLE_EQ(gauss::relative_change(previous, current, rest, 1.0), 0.2 / 0.4);
  // Scale-invariant: the caller's frame and the solver's normalized frame agree.
  auto scaled = [](std::vector<Vector3d> x) {
    for (Vector3d& p : x) p = 3.5 * p + Vector3d(1, 2, 3);
    return x;
  };
  EXPECT_NEAR(gauss::relative_change(scaled(previous), scaled(current), scaled(rest), 3.5), 0.5, 1e-12);
  EXPECT_EQ(gauss::relative_change(current, current, rest, 1.0), 0.0);
  // A mesh that barely left its rest shape: the displacement counts as kStillDisplacement * size.
  const std::vector<Vector3d> nudged = {{0, 0, 1e-14}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_NEAR(gauss::relative_change(rest, nudged, rest, 2.0), 1e-14 / (gauss::kStillDisplacement * 2.0), 1e-12);
}

TEST(StepUntil, StopsAtTheFirstStepBelowTheTolerance) {
  const gauss::TriangleMesh m = gauss_test::icosphere(3);
  GaussSolver s = sphere_solver(m);
  EXPECT_EQ(s.last_reldv(), INFINITY);
  EXPECT_FALSE(s.converged());
  const int taken = s.step_until(1e-3, 1000);
  EXPECT_GT(taken, 5);
  EXPECT_LT(taken, 1000);
  EXPECT_EQ(s.step_count(), taken);
  EXPECT_LT(s.last_reldv(), 1e-3);
  EXPECT_TRUE(s.converged());
  EXPECT_EQ(s.tolerance(), 1e-3);
  // The step before was not below it: a plain run of taken - 1 steps has not converged.
  GaussSolver plain = sphere_solver(m);
  for (int i = 0; i < taken - 1; ++i) plain.step();
  EXPECT_GE(plain.last_reldv(), 1e-3);
  plain.step();
  EXPECT_EQ(plain.last_reldv(), s.last_reldv());  // the same iteration, bit for bit
  // Converged: nothing left to do at this tolerance; a tighter one goes on.
  EXPECT_EQ(s.step_until(1e-3, 1000), 0);
  EXPECT_GT(s.step_until(1e-4, 1000), 0);
  EXPECT_LT(s.last_reldv(), 1e-4);
}

TEST(StepUntil, RespectsTheCap) {
  const gauss::TriangleMesh m = gauss_test::icosphere(3);
  GaussSolver s = sphere_solver(m);
  EXPECT_EQ(s.step_until(1e-4, 7), 7);
  EXPECT_EQ(s.step_count(), 7);
  EXPECT_FALSE(s.converged());
  EXPECT_GT(s.last_reldv(), 1e-4);
  EXPECT_EQ(s.step_until(1e-4, 0), 0);
  EXPECT_EQ(s.step_count(), 7);
}

TEST(StepUntil, EditsMakeAConvergedRunStepAgain) {
  const gauss::TriangleMesh m = gauss_test::icosphere(2);
  GaussSolver s = sphere_solver(m);
  const std::vector<int64_t> pins = {0};
  const double target[3] = {m.V[0] + 0.05, m.V[1], m.V[2]};
  const std::vector<std::function<void()>> edits = {
      [&] { s.set_lambda(s.lambda()); },
      [&] { s.set_styles({gauss::PreferenceFunction(gauss::preset_style("cube"))}); },
      [&] { s.set_style(0, gauss::PreferenceFunction(gauss::preset_style("octahedron"))); },
      [&] {
        std::vector<int64_t> fs(m.num_faces(), 0);
        s.set_face_styles(fs.data(), m.num_faces());
      },
      [&] { s.set_admm_iterations(1); },
      [&] { s.set_pins(pins); },
      [&] { s.set_pin_positions(target, 1); },
      [&] { s.set_method(gauss::Method::cubic); },
      [&] { s.set_cubic_lambda(0.3); },
      [&] { s.set_method(gauss::Method::gauss); },
      [&] { s.reset(); },
  };
  for (size_t i = 0; i < edits.size(); ++i) {
    s.step_until(1e-3, 2000);
    ASSERT_TRUE(s.converged()) << i;
    edits[i]();
    EXPECT_FALSE(s.converged()) << "edit " << i;
    EXPECT_EQ(s.last_reldv(), INFINITY) << "edit " << i;
    EXPECT_GE(s.step_until(1e-3, 2000), 1) << "edit " << i;
  }
  // The tolerance only changes what converged() says.
  const double reldv = s.last_reldv();
  s.set_tolerance(reldv * 0.5);
  EXPECT_FALSE(s.converged());
  s.set_tolerance(gauss::settings::tolerance.max);
  EXPECT_TRUE(s.converged());
  EXPECT_EQ(s.last_reldv(), reldv);
}

TEST(StepUntil, RefusesBadArgumentsWithoutStepping) {
  const gauss::TriangleMesh m = gauss_test::icosphere(1);
  GaussSolver s = sphere_solver(m);
  gauss_test::expect_refused([&] { s.step_until(1e-3, -1); }, "steps must be >= 0");
  gauss_test::expect_refused([&] { s.step_until(0.0, 10); }, "tolerance must be");
  gauss_test::expect_refused([&] { s.step_until(NAN, 10); }, "tolerance must be");
  gauss_test::expect_refused([&] { s.step_until(2.0, 10); }, "tolerance must be");
  gauss_test::expect_refused([&] { s.set_tolerance(-1.0); }, "tolerance must be");
  EXPECT_EQ(s.step_count(), 0);
  EXPECT_EQ(s.tolerance(), gauss::settings::tolerance.default_value);
}

TEST(StepUntil, ACubeUnderTheCubeStyleConvergesAtOnce) {
  // It does not move (rounding only): the rounding floor of reldV keeps that from reading as motion.
  const gauss::TriangleMesh cube = gauss_test::grid_cube(6);
  GaussSolver s(cube.V.data(), cube.num_vertices(), cube.F.data(), cube.num_faces());
  EXPECT_EQ(s.step_until(gauss::settings::tolerance.min, 100), 1);
}

}  // namespace test_convergence
