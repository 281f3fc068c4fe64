// Runaway steps: where enough cotangent weights are negative (obtuse, non-Delaunay patches), the Gauss
// method's edge pull stops being a contraction and can grow the iterate from step to step. Such a step is
// redone as plain ARAP (gauss_solver.cpp, kRunawayReach), so every run stays bounded; meshes that never
// run away never take that path, so their results are unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "gauss/mesh/mesh_io.h"
#include "gauss/solver/gauss_solver.h"
#include "gauss/style/presets.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_runaway {

namespace {

using Mesh = gauss::TriangleMesh;

// A unit cube whose corner 0 is pulled 3.78 sizes down: the edges from it to corners 5 and 6 get
// cotangent weight -1.89. Found by the fuzzer (tests/fuzz/regressions/spiked_cube_admm4_edge_pull_runs_away).
Mesh spiked_cube() {
  Mesh m;
  for (int i = 0; i < 8; ++i) m.V.insert(m.V.end(), {double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  m.V[2] = -3.78125;
  m.F = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
  return m;
}

// The largest distance of a vertex from the rest box's centre, in rest sizes, after `steps` steps.
double spread_after(gauss::GaussSolver& s, const Mesh& m, int steps) {
  for (int i = 0; i < steps; ++i) s.step();
  std::vector<double> out(m.V.size());
  s.copy_vertices(out.data());
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < m.V.size(); ++i) lo[i % 3] = std::min(lo[i % 3], m.V[i]), hi[i % 3] = std::max(hi[i % 3], m.V[i]);
  const double size = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  double worst = 0;
  for (size_t i = 0; i < out.size(); ++i) worst = std::max(worst, std::abs(out[i] - 0.5 * (lo[i % 3] + hi[i % 3])) / size);
  return worst;
}

TEST(Runaway, ASpikedCubeStaysBoundedWithAnyAdmmCount) {
  const Mesh m = spiked_cube();
  for (int admm : {1, 4, 20})
    for (bool acceleration : {true, false}) {
      gauss::GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
      s.set_styles({gauss::PreferenceFunction(gauss::preset_style("cube"))});
      s.set_admm_iterations(admm);
      s.set_acceleration(acceleration);
      const double spread = spread_after(s, m, 300);
      // Without the fallback, ADMM 4 and 20 grew past 1e5 sizes within 10 steps.
      EXPECT_TRUE(std::isfinite(spread) && spread <= 5.0) << "admm " << admm << ": " << spread << " sizes";
      EXPECT_TRUE(std::isfinite(s.arap_energy()) && std::isfinite(s.g_energy()));
      if (admm >= 4) EXPECT_GT(s.runaway_steps(), 0) << "admm " << admm << ": the fallback was not needed";
      s.reset();
      EXPECT_EQ(s.runaway_steps(), 0);
    }
}

// The same mesh inflated by set_vertices (a warm start five times its size) is not a runaway: the
// caller's vertices widen the reach.
TEST(Runaway, AWideWarmStartIsNotARunaway) {
  const Mesh m = spiked_cube();
  gauss::GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
  std::vector<double> wide(m.V);
  for (double& x : wide) x *= 5.0;
  s.set_vertices(wide.data(), m.num_vertices());
  s.step();
  EXPECT_EQ(s.runaway_steps(), 0);
}

// The camel head (edge weights down to -20) at lambda 20 with 4 ADMM iterations: without the fallback
// it grew to 1e5 sizes by step 120, and with it it took the fallback. Its edges below kMinEdgeWeight
// now get the small positive weight (cotangent_weights.h), and it stays bounded by ordinary steps
// (the spiked cube above still takes the fallback).
TEST(Runaway, TheCamelHeadAtLambda20StaysBoundedWithoutTheFallback) {
  const std::string path = gauss_test::shared_mesh("boundary/camelhead_11381.obj");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent";
  const Mesh m = gauss::read_mesh(path);
  gauss::GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), {}, nullptr, 20.0);
  s.set_styles({gauss::PreferenceFunction(gauss::preset_style("cube"))});
  s.set_admm_iterations(4);
  const double spread = spread_after(s, m, 160);
  EXPECT_TRUE(std::isfinite(spread) && spread <= 2.0) << spread << " sizes";
  EXPECT_EQ(s.runaway_steps(), 0);
}

// Real meshes have negative edge weights too (2-14% of the edges); these never run away, at the
// default ADMM count or a higher one, so their runs take the ordinary step only.
TEST(Runaway, SharedMeshesNeverTakeTheFallback) {
  for (const char* rel : {"small/spot_triangulated_2930.obj", "boundary/cat_head_131.obj", "bunny/bunny_npm_1839.obj"}) {
    const std::string path = gauss_test::shared_mesh(rel);
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent";
    const Mesh m = gauss::read_mesh(path);
    for (int admm : {1, 8}) {
      gauss::GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
      s.set_styles({gauss::PreferenceFunction(gauss::preset_style("cube"))});
      s.set_admm_iterations(admm);
      spread_after(s, m, 100);
      EXPECT_EQ(s.runaway_steps(), 0) << rel << " admm " << admm;
    }
  }
}

}  // namespace

}  // namespace test_runaway
