// Resolution Independent's reference density (GaussSolver::set_reference_face_area): checked, in
// effect only while the setting is on, and off the solver steps as if the setting did not exist.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "gauss/settings.h"
#include "gauss/solver/gauss_solver.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_resolution_independent {

using gauss::GaussSolver;

namespace {

// An icosphere squashed along two axes, so its faces are not all of one area.
gauss::TriangleMesh squashed_sphere() {
  gauss::TriangleMesh m = gauss_test::icosphere(3);
  for (int v = 0; v < m.num_vertices(); ++v) m.V[3 * v + 1] *= 0.7, m.V[3 * v + 2] *= 0.5;
  return m;
}

std::vector<double> run(const gauss::TriangleMesh& m, bool on, double reference_area, int steps = 12,
                        bool weigh_finer_faces = false) {
  GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
  s.set_resolution_independent(on);
  s.set_weigh_finer_faces(weigh_finer_faces);
  if (reference_area > 0) s.set_reference_face_area(reference_area);
  for (int i = 0; i < steps; ++i) s.step();
  std::vector<double> out(m.V.size());
  s.copy_vertices(out.data());
  return out;
}

double largest_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0;
  for (size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

}  // namespace

TEST(ReferenceFaceArea, DefaultsToTheSettingAndRefusesNonPositiveOrNonFiniteAreas) {
  const gauss::TriangleMesh m = squashed_sphere();
  GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
  EXPECT_EQ(s.reference_face_area(), gauss::settings::reference_face_area);
  for (double bad : {0.0, -1e-3, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
    EXPECT_THROW(s.set_reference_face_area(bad), std::invalid_argument) << bad;
  EXPECT_EQ(s.reference_face_area(), gauss::settings::reference_face_area);
}

TEST(ReferenceFaceArea, ChangesTheRunOnlyWhileTheSettingIsOn) {
  const gauss::TriangleMesh m = squashed_sphere();
  const double a = gauss::settings::reference_face_area;
  EXPECT_EQ(largest_difference(run(m, false, 4 * a), run(m, false, -1)), 0.0);  // off: bit for bit
  EXPECT_GT(largest_difference(run(m, true, 4 * a), run(m, true, -1)), 1e-4);
  EXPECT_GT(largest_difference(run(m, true, -1), run(m, false, -1)), 1e-4);
}

TEST(ResolutionIndependent, SwitchedOnAndOffBeforeAStepLeavesThePlainRunBitForBit) {
  const gauss::TriangleMesh m = squashed_sphere();
  GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
  s.set_resolution_independent(true);
  s.step();
  s.set_resolution_independent(false);
  s.reset();
  for (int i = 0; i < 12; ++i) s.step();
  std::vector<double> out(m.V.size());
  s.copy_vertices(out.data());
  EXPECT_EQ(largest_difference(out, run(m, false, -1)), 0.0);
}

// The rule before 2026-12-06 (settings::weigh_finer_faces) weighed the finer faces' preference by their
// area too; today's leaves them alone. So the two differ only on faces finer than the reference, and
// only with the setting on.
TEST(WeighFinerFaces, ChangesOnlyTheFacesFinerThanTheReference) {
  const gauss::TriangleMesh m = squashed_sphere();
  EXPECT_FALSE(gauss::settings::weigh_finer_faces.default_value);
  double smallest = INFINITY, largest = 0;
  for (int f = 0; f < m.num_faces(); ++f) {
    // Areas in the solver's frame: the sphere's longest side is 2, scaled to 1.
    const double* p[3] = {&m.V[3 * m.F[3 * f]], &m.V[3 * m.F[3 * f + 1]], &m.V[3 * m.F[3 * f + 2]]};
    const double u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const double v[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const double c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double area = 0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / 4.0;
    smallest = std::min(smallest, area), largest = std::max(largest, area);
  }
  // Every face coarser than the reference: the rules agree bit for bit.
  EXPECT_EQ(largest_difference(run(m, true, 0.5 * smallest, 12, true), run(m, true, 0.5 * smallest, 12, false)), 0.0);
  // Every face finer: they differ.
  EXPECT_GT(largest_difference(run(m, true, 2 * largest, 12, true), run(m, true, 2 * largest, 12, false)), 1e-4);
  // Without the setting the old rule changes nothing, even switched mid-run.
  EXPECT_EQ(largest_difference(run(m, false, -1, 12, true), run(m, false, -1)), 0.0);
  GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
  for (int i = 0; i < 12; ++i) {
    s.set_weigh_finer_faces(i % 2 == 1);
    s.step();
  }
  std::vector<double> out(m.V.size());
  s.copy_vertices(out.data());
  EXPECT_EQ(largest_difference(out, run(m, false, -1)), 0.0);
}

TEST(WeighFinerFaces, SwitchedWithTheSettingOnTheGaussRunStartsAgainTheCubicRunGoesOn) {
  const gauss::TriangleMesh m = squashed_sphere();
  // Twelve steps with Resolution Independent, the old rule switched on after six if `switch_rule`.
  const auto twelve_steps = [&](gauss::Method method, bool switch_rule, bool& unconverged_after_switch) {
    GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
    s.set_method(method);
    s.set_resolution_independent(true);
    s.set_reference_face_area(1.0);  // every face finer: the rules differ where the method reads them
    for (int i = 0; i < 6; ++i) s.step();
    if (switch_rule) s.set_weigh_finer_faces(true);
    unconverged_after_switch = std::isinf(s.last_reldv());
    for (int i = 0; i < 6; ++i) s.step();
    std::vector<double> out(m.V.size());
    s.copy_vertices(out.data());
    return out;
  };
  using gauss::Method;
  bool restarted = false, unused = false;
  const auto gauss_plain = twelve_steps(Method::gauss, false, unused);
  EXPECT_GT(largest_difference(twelve_steps(Method::gauss, true, restarted), gauss_plain), 1e-6);
  EXPECT_TRUE(restarted);  // a settled run is not converged under the other rule until it steps
  // The cubic method has no normal step: the rule changes nothing, bit for bit.
  const auto cubic_plain = twelve_steps(Method::cubic, false, unused);
  EXPECT_EQ(largest_difference(twelve_steps(Method::cubic, true, restarted), cubic_plain), 0.0);
  EXPECT_FALSE(restarted);
}

}  // namespace test_resolution_independent
