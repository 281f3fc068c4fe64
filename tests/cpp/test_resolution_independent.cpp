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

std::vector<double> run(const gauss::TriangleMesh& m, bool on, double reference_area, int steps = 12) {
  GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
  s.set_resolution_independent(on);
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

}  // namespace test_resolution_independent
