#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "gauss/solver/closest_rotation.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_closest_rotation {

using Eigen::Matrix3d;

namespace {

// Reference: SVD-based Procrustes with the reflection fix.
Matrix3d reference_rotation(const Matrix3d& M) {
  Eigen::JacobiSVD<Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Matrix3d D = Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1 : 1;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

bool is_rotation(const Matrix3d& R) {
  return (R.transpose() * R - Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-12 && R.determinant() > 0;
}

}  // namespace

TEST(ClosestRotation, MatchesSvdOnGeneralRankDeficientAndReflectedMatrices) {
  std::mt19937 rng(7);
  std::normal_distribution<double> nd;
  for (int i = 0; i < 2000; ++i) {
    Matrix3d M;
    for (int k = 0; k < 9; ++k) M.data()[k] = nd(rng);
    if (i % 4 == 1) M.col(2) = M.col(0) * 0.3 + M.col(1) * 0.7;  // rank two (flat neighbourhood)
    if (i % 4 == 2) M.col(0) *= -1;                              // may flip the determinant
    const Matrix3d R = gauss::closest_rotation(M);
    ASSERT_TRUE(is_rotation(R));
    EXPECT_LT((R - reference_rotation(M)).cwiseAbs().maxCoeff(), 1e-8) << M;
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
    const Matrix3d Rw = gauss::closest_rotation_warm(M, q);
    ASSERT_TRUE(is_rotation(Rw));
    // Both maximize tr(R^T M); compare objective values (the rotation is not unique at ties).
    EXPECT_NEAR((Rw.transpose() * M).trace(), (R.transpose() * M).trace(), 1e-9 * (1 + M.norm()));
  }
}

TEST(ClosestRotation, IdentityForSymmetricPositiveAndZeroMatrices) {
  Matrix3d S;
  S << 2, 0.5, 0, 0.5, 1, 0, 0, 0, 0;  // rank two, like a flat vertex neighbourhood at rest
  EXPECT_LT((gauss::closest_rotation(S) - Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-14);
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  EXPECT_LT((gauss::closest_rotation_warm(S, q) - Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_TRUE(gauss::closest_rotation(Matrix3d::Zero()).isIdentity());
  Matrix3d nan = Matrix3d::Constant(NAN);
  EXPECT_TRUE(is_rotation(gauss::closest_rotation_warm(nan, q)));
}

TEST(ClosestRotation, WarmStartFollowsASlowlyTurningFrame) {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  Matrix3d P;
  P << 3, 0.2, 0.1, 0.2, 2, 0.3, 0.1, 0.3, 0.5;
  for (int i = 0; i < 200; ++i) {
    const Matrix3d R = Eigen::AngleAxisd(0.05 * i, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
    const Matrix3d got = gauss::closest_rotation_warm(R * P, q);
    EXPECT_LT((got - R).cwiseAbs().maxCoeff(), 1e-9) << i;
  }
}

}  // namespace test_closest_rotation
