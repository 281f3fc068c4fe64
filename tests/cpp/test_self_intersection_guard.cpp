// The self-intersection guard in the solver (avoid_self_intersections): under the cubic method, the
// start it takes after reset() and set_vertices(), and the same result on one thread and two.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "gauss/collision/self_intersection.h"
#include "gauss/solver/gauss_solver.h"
#include "gauss/style/presets.h"
#include "gauss/util/parallel.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_self_intersection_guard {

using Eigen::Vector3d;
using gauss::GaussSolver;
using gauss_test::faces_of;
using gauss_test::points_of;

namespace {

int64_t crossings(const gauss::TriangleMesh& m, const std::vector<double>& V) {
  return gauss::count_self_intersections(faces_of(m), points_of(V));
}

std::vector<double> vertices(const GaussSolver& s) {
  std::vector<double> out(3 * static_cast<size_t>(s.num_vertices()));
  s.copy_vertices(out.data());
  return out;
}

// Steps the solver, returning the most vertices one step held back.
int run(GaussSolver& s, int steps) {
  int held = 0;
  for (int i = 0; i < steps; ++i) {
    s.step();
    held = std::max(held, s.held_vertices());
  }
  return held;
}

}  // namespace

TEST(SelfIntersectionGuard, TheCubicMethodMakesNoNewCrossing) {
  // Cubic Stylization turns the plates flat as well: without the guard they pass through each other,
  // with it they end as clean as they began, and it did hold vertices back.
  const gauss::TriangleMesh m = gauss_test::leaning_plates(2);
  ASSERT_EQ(crossings(m, m.V), 0);
  for (const bool avoid : {false, true}) {
    SCOPED_TRACE(avoid ? "guarded" : "free");
    GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
    s.set_cubic_lambda(1.0);
    s.set_method(gauss::Method::cubic);
    s.set_avoid_self_intersections(avoid);
    const int held = run(s, 60);
    const std::vector<double> out = vertices(s);
    for (double c : out) ASSERT_TRUE(std::isfinite(c));
    if (avoid) {
      EXPECT_EQ(crossings(m, out), 0);
      EXPECT_GT(held, 0);
      EXPECT_LT(held, m.num_vertices());
    } else {
      EXPECT_GT(crossings(m, out), 0) << "the case does not test the guard";
    }
  }
}

TEST(SelfIntersectionGuard, ResetStartsTheGuardFromTheRestMeshAgain) {
  // Set to crossing vertices, the guard allows those crossings; reset() takes the run back to the
  // clean rest mesh, where they are new again: the run after it is the first run, bit for bit, clean.
  const gauss::TriangleMesh m = gauss_test::leaning_plates(2);
  const auto solver = [&m] {
    auto s = std::make_unique<GaussSolver>(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), std::vector<int64_t>{},
                                           nullptr, 10.0);
    s->set_styles({gauss::PreferenceFunction(gauss::preset_style("cube"))});
    return s;
  };
  auto free_run = solver();
  run(*free_run, 60);
  const std::vector<double> crossed = vertices(*free_run);
  ASSERT_GT(crossings(m, crossed), 0);
  for (const gauss::Method method : {gauss::Method::gauss, gauss::Method::cubic}) {
    SCOPED_TRACE(gauss::settings::method_names[static_cast<int>(method)]);
    auto first = solver(), again = solver();
    for (auto* s : {first.get(), again.get()}) s->set_method(method), s->set_avoid_self_intersections(true);
    run(*first, 40);
    again->set_vertices(crossed.data(), m.num_vertices());
    run(*again, 5);
    again->reset();
    run(*again, 40);
    const std::vector<double> a = vertices(*first), b = vertices(*again);
    EXPECT_EQ(crossings(m, b), 0);
    for (size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << i;
  }
}

TEST(SelfIntersectionGuard, SetVerticesIsTheNewStartAsItIs) {
  // Crossing vertices set while the guard is on are taken as they are: the run from them is the run
  // of a solver that was set to them with the guard off and had it switched on there (start_from), bit
  // for bit. Were the old start kept, their crossings would be new, and their corners held.
  const gauss::TriangleMesh m = gauss_test::leaning_plates(2);
  GaussSolver free_run(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), {}, nullptr, 10.0);
  free_run.set_styles({gauss::PreferenceFunction(gauss::preset_style("cube"))});
  run(free_run, 60);
  const std::vector<double> crossed = vertices(free_run);
  ASSERT_GT(crossings(m, crossed), 0);
  GaussSolver on(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), {}, nullptr, 10.0);
  GaussSolver later(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), {}, nullptr, 10.0);
  on.set_avoid_self_intersections(true);
  run(on, 10);  // its guard has a history: the clean start, and holds
  on.set_vertices(crossed.data(), m.num_vertices());
  later.set_vertices(crossed.data(), m.num_vertices());
  later.set_avoid_self_intersections(true);
  // Back towards the rest shape (ARAP): the plates pull apart, the crossing pairs move.
  run(on, 20);
  run(later, 20);
  const std::vector<double> a = vertices(on), b = vertices(later);
  for (size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << i;
  EXPECT_NE(a, crossed) << "held where it was set";
}

TEST(SelfIntersectionGuard, OneAndTwoThreadsAreBitIdentical) {
  // Plates of 4332 faces each (above the sizes where the pair search and the flat stars go parallel)
  // under the cube style, which folds their thin rims from the third step on (the guard holds about a
  // thousand vertices a step there): the same vertices bit for bit. (The solver picks one thread or
  // both per step by timing; the guard alone on one and two is in test_self_intersection_shortcuts.)
  const gauss::TriangleMesh m = gauss_test::leaning_plates(19);
  ASSERT_GT(m.num_faces(), 8192);
  ASSERT_GT(m.num_vertices(), gauss::parallel::kMinParallelItems);
  const int saved = gauss::parallel::max_threads();
  std::vector<std::vector<double>> result;
  std::vector<int> held;
  for (const int threads : {1, 2}) {
    gauss::parallel::set_max_threads(threads);
    GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), {}, nullptr, 10.0);
    s.set_styles({gauss::PreferenceFunction(gauss::preset_style("cube"))});
    s.set_avoid_self_intersections(true);
    held.push_back(run(s, 3));
    result.push_back(vertices(s));
  }
  gauss::parallel::set_max_threads(saved);
  EXPECT_GT(held[0], 0) << "the guard had nothing to do";
  EXPECT_EQ(held[0], held[1]);
  for (size_t i = 0; i < result[0].size(); ++i) ASSERT_EQ(result[0][i], result[1][i]) << i;
}

}  // namespace test_self_intersection_guard
