// The warm rotation fit's two forms that save time (closest_rotation.h) give the bits of the plain
// call: with its start given as a matrix, and run as two lanes in lockstep, an inactive lane untouched.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "gauss/solver/closest_rotation.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_closest_rotation_lanes {

namespace {

using Eigen::Matrix3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

// A matrix to fit and a start: near (small turn), far (beyond Newton's basin, the Jacobi fallback),
// rank two, reflected, zero or NaN, by trial number.
struct Case {
  Matrix3d M;
  Quaterniond start;
};

Case make_case(std::mt19937& rng, int trial) {
  std::normal_distribution<double> normal;
  const Quaterniond turn = Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
  Matrix3d P;
  for (int i = 0; i < 9; ++i) P(i / 3, i % 3) = 0.3 * normal(rng);
  P = (P * P.transpose()).eval() + Matrix3d::Identity();
  if (trial % 5 == 1) P.col(2).setZero();
  if (trial % 7 == 2) P = -P;
  Case c{turn.toRotationMatrix() * P, Quaterniond::Identity()};
  if (trial % 11 == 3) c.M.setZero();
  if (trial % 13 == 4) c.M(1, 1) = std::nan("");
  const double reach = trial % 3 == 0 ? 2.0 : 0.01;
  const Vector3d w = reach * Vector3d(normal(rng), normal(rng), normal(rng));
  c.start = (turn * Quaterniond(1.0, 0.5 * w.x(), 0.5 * w.y(), 0.5 * w.z())).normalized();
  return c;
}

bool same_bits(const Matrix3d& a, const Matrix3d& b) {
  for (int i = 0; i < 9; ++i)
    if (!(a(i) == b(i) || (std::isnan(a(i)) && std::isnan(b(i))))) return false;
  return true;
}

TEST(ClosestRotationWarm, StartGivenAsAMatrixGivesTheSameBits) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 300; ++trial) {
    const Case c = make_case(rng, trial);
    Quaterniond q1 = c.start, q2 = c.start;
    const Matrix3d R1 = gauss::closest_rotation_warm(c.M, q1);
    Matrix3d R2 = c.start.toRotationMatrix();
    gauss::closest_rotation_warm(c.M, q2, R2);
    EXPECT_TRUE(same_bits(R1, R2)) << "trial " << trial;
    EXPECT_EQ(q1.coeffs(), q2.coeffs()) << "trial " << trial;
  }
}

TEST(ClosestRotationWarm, TwoLanesGiveTheBitsOfOneEach) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 300; ++trial) {
    const Case c[2] = {make_case(rng, trial), make_case(rng, trial / 2 + 5)};
    const bool active[2] = {true, trial % 4 != 0};
    Matrix3d M[2] = {c[0].M, c[1].M};
    Quaterniond q[2] = {c[0].start, c[1].start};
    Matrix3d R[2] = {c[0].start.toRotationMatrix(), c[1].start.toRotationMatrix()};
    const Matrix3d untouched = R[1];
    gauss::closest_rotation_warm_lanes<2>(M, q, R, active);
    for (int l = 0; l < 2; ++l) {
      if (!active[l]) {
        EXPECT_EQ(R[l], untouched);
        EXPECT_EQ(q[l].coeffs(), c[l].start.coeffs());
        continue;
      }
      Quaterniond alone = c[l].start;
      EXPECT_TRUE(same_bits(gauss::closest_rotation_warm(c[l].M, alone), R[l])) << "trial " << trial << " lane " << l;
      EXPECT_EQ(alone.coeffs(), q[l].coeffs()) << "trial " << trial << " lane " << l;
    }
  }
}

}  // namespace

}  // namespace test_closest_rotation_lanes
