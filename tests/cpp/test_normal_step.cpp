// The normal update of the ADMM round (Eqs. 17-22) and the 3x3 solve, on their own.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <string>

#include "gauss/solver/normal_step.h"
#include "gauss/style/presets.h"
#include "gauss/settings.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_normal_step {

using gauss::newton_normal;
using gauss::PreferenceFunction;
using gauss::solve_symmetric3;
using gauss::trust_region_normal;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

double angle(const Vector3d& a, const Vector3d& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

// One face's local problem: L_n(x) = -g(x) + sum_k lw_k / 2 (u_k + x . es_k)^2 (Eq. 18), defined on
// all of R^3 (g extends there), so its gradient and Hessian can be taken by finite differences.
struct LocalProblem {
  PreferenceFunction g;
  Vector3d es[3];
  double lw[3];
  double u[3];

  double objective(const Vector3d& x) const {
    double L = -g.value(x);
    for (int k = 0; k < 3; ++k) L += 0.5 * lw[k] * std::pow(u[k] + x.dot(es[k]), 2);
    return L;
  }
  Vector3d step(const Vector3d& n) const { return newton_normal(g, n, es, lw, u); }

  Vector3d gradient_fd(const Vector3d& x, double h = 1e-5) const {
    Vector3d d;
    for (int i = 0; i < 3; ++i) {
      const Vector3d e = h * Vector3d::Unit(i);
      d[i] = (objective(x + e) - objective(x - e)) / (2 * h);
    }
    return d;
  }
  Matrix3d hessian_fd(const Vector3d& x, double h = 1e-4) const {
    Matrix3d H;
    for (int i = 0; i < 3; ++i) {
      const Vector3d e = h * Vector3d::Unit(i);
      H.col(i) = (gradient_fd(x + e) - gradient_fd(x - e)) / (2 * h);
    }
    return 0.5 * (H + H.transpose());
  }

  // The minimizer over unit vectors within `radius` of `center`, by brute force: ~20000 evenly spread
  // directions of that cap (a Fibonacci spiral), then a 0.0005 rad grid around the best of them.
  Vector3d brute_force_minimizer(const Vector3d& center, double radius) const {
    const Vector3d a = center.unitOrthogonal(), b = center.cross(a);
    const int N = 20000;
    const double golden = M_PI * (3.0 - std::sqrt(5.0)), min_z = std::cos(radius);
    Vector3d best = center;
    double best_value = objective(center);
    auto consider = [&](const Vector3d& n) {
      const double value = objective(n);
      if (value < best_value) best_value = value, best = n;
    };
    for (int i = 0; i < N; ++i) {
      const double z = 1.0 - (1.0 - min_z) * (i + 0.5) / N, r = std::sqrt(1.0 - z * z);
      consider(z * center + r * std::cos(golden * i) * a + r * std::sin(golden * i) * b);
    }
    const Vector3d coarse = best, ca = coarse.unitOrthogonal(), cb = coarse.cross(ca);
    for (int i = -40; i <= 40; ++i)
      for (int j = -40; j <= 40; ++j) consider((coarse + 0.0005 * (i * ca + j * cb)).normalized());
    return best;
  }
};

// A face whose normal is `normal`, with edges of length ~`size` in its plane, cotangent weights around
// 0.5 at lambda 4, and scaled duals of the size the dual update gives them (Eq. 25).
LocalProblem face_problem(const PreferenceFunction& g, const Vector3d& normal, double size, std::mt19937& rng) {
  std::uniform_real_distribution<double> uniform(0, 1);
  LocalProblem lp{g, {}, {}, {}};
  const Vector3d a = normal.unitOrthogonal(), b = normal.cross(a);
  const Vector3d corners[3] = {Vector3d::Zero(), size * (a + 0.3 * (uniform(rng) - 0.5) * b),
                               size * ((0.2 + 0.4 * uniform(rng)) * a + (0.7 + 0.4 * uniform(rng)) * b)};
  for (int k = 0; k < 3; ++k) {
    lp.es[k] = corners[(k + 1) % 3] - corners[k];
    lp.lw[k] = 4 * (0.2 + 0.6 * uniform(rng));
    lp.u[k] = 0.3 * size * (uniform(rng) - 0.5);
  }
  return lp;
}

// A face's local problem far outside a mesh's range: edges from 1e-6 to 1e2 long, couplings up to 1e4,
// random duals; `trial` picks the scales.
struct WildFace {
  Vector3d es[3];
  double lw[3], u[3];
};
WildFace wild_face(std::mt19937& rng, int trial) {
  std::normal_distribution<double> normal;
  WildFace face;
  for (int k = 0; k < 3; ++k) {
    face.es[k] = Vector3d(normal(rng), normal(rng), normal(rng)) * std::pow(10.0, trial % 9 - 6);
    face.lw[k] = std::abs(normal(rng)) * std::pow(10.0, trial % 5);
    face.u[k] = normal(rng);
  }
  return face;
}

PreferenceFunction style(const std::string& preset, double sigma) {
  gauss::StyleParams p = gauss::preset_style(preset);
  p.sigma = sigma;
  return PreferenceFunction(p);
}

}  // namespace

TEST(SolveSymmetric3, AgreesWithEigen) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 200; ++trial) {
    Matrix3d A;
    for (int i = 0; i < 9; ++i) A(i / 3, i % 3) = normal(rng);
    // Alternately positive definite and indefinite, at scales far from 1.
    Matrix3d H = trial % 2 ? Matrix3d(A * A.transpose() + 0.1 * Matrix3d::Identity()) : Matrix3d(A + A.transpose());
    H *= std::pow(10.0, trial % 7 - 3);
    const Vector3d b(normal(rng), normal(rng), normal(rng));
    Vector3d x;
    ASSERT_TRUE(solve_symmetric3(H, b, x)) << H;
    const Vector3d expected = H.fullPivLu().solve(b);
    const double cond = H.jacobiSvd().singularValues()(0) / H.jacobiSvd().singularValues()(2);
    EXPECT_LE((x - expected).norm(), 1e-13 * cond * expected.norm()) << "trial " << trial;
  }
}

TEST(SolveSymmetric3, RefusesSingularAndNonFiniteSystems) {
  const Vector3d b(1, 2, 3), e(0.3, -1, 2);
  Vector3d x;
  EXPECT_FALSE(solve_symmetric3(Matrix3d::Zero(), b, x));
  EXPECT_FALSE(solve_symmetric3(e * e.transpose(), b, x));                         // rank 1
  EXPECT_FALSE(solve_symmetric3(Vector3d(1, 1, 0).asDiagonal(), b, x));            // rank 2
  EXPECT_FALSE(solve_symmetric3(Vector3d(1, 1, 1e-14).asDiagonal(), b, x));        // numerically
  const Vector3d f(1, 0.5, 0.25);
  EXPECT_FALSE(solve_symmetric3(e * e.transpose() + f * f.transpose(), b, x));     // rank 2, dense
  Matrix3d H = Matrix3d::Identity();
  H(1, 2) = H(2, 1) = NAN;
  EXPECT_FALSE(solve_symmetric3(H, b, x));
  H(1, 2) = H(2, 1) = INFINITY;
  EXPECT_FALSE(solve_symmetric3(H, b, x));
  EXPECT_FALSE(solve_symmetric3(Matrix3d::Identity(), Vector3d(1, NAN, 0), x));
  // Well-posed systems at large and small scales still pass.
  EXPECT_TRUE(solve_symmetric3(1e3 * Matrix3d::Identity(), b, x));
  EXPECT_TRUE(x.isApprox(b / 1e3));
  EXPECT_TRUE(solve_symmetric3(Vector3d(1e-4, 2, 3).asDiagonal(), b, x));
  EXPECT_TRUE(x.isApprox(Vector3d(1e4, 1, 1)));
}

TEST(NewtonNormal, FollowsEquations19To22) {
  // The update computed independently: gradient and Hessian of L_n by finite differences, the Newton
  // direction of Eq. 21, projected and normalized (Eq. 22), or the paper's fallback, a projected
  // gradient step of size 0.1, where that direction points uphill.
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  int newton = 0, fallback = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const char* preset = trial % 3 == 0 ? "cube" : trial % 3 == 1 ? "tetrahedron" : "cone";
    const Vector3d n = Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    const LocalProblem lp = face_problem(style(preset, 2.0 + trial % 5), n, 0.3 + 0.1 * (trial % 7), rng);
    const Vector3d grad = lp.gradient_fd(n);
    const Matrix3d H = lp.hessian_fd(n);
    const Eigen::JacobiSVD<Matrix3d> svd(H);
    if (svd.singularValues()(0) > 1e3 * svd.singularValues()(2)) continue;  // finite differences too coarse
    const Matrix3d P = Matrix3d::Identity() - n * n.transpose();
    const Vector3d d = P * H.fullPivLu().solve(-grad), pg = P * grad;
    // Skip where finite-difference error could flip the choice of branch.
    if (std::abs(d.dot(grad)) < 1e-3 * d.norm() * pg.norm()) continue;
    const bool downhill = d.dot(grad) < 0;
    const Vector3d expected = downhill ? Vector3d((n + d).normalized()) : Vector3d((n - 0.1 * pg).normalized());
    (downhill ? newton : fallback)++;
    EXPECT_LT(angle(lp.step(n), expected), 1e-5) << preset << " trial " << trial << (downhill ? " newton" : " fallback");
  }
  EXPECT_GT(newton, 50);    // both branches were checked
  EXPECT_GT(fallback, 20);
}

TEST(NewtonNormal, LowersLnAndConvergesToTheBruteForceMinimizer) {
  // Faces near a preferred normal with mesh-sized edges, at the default sigma and below: the situation
  // of most faces once a run is under way. The first step (Algorithm 1 takes one per ADMM round)
  // lowers L_n; repeated, the steps settle at the minimizer of L_n that brute force finds nearby.
  // Repeated steps may rise by rounding-sized amounts near the end: the fixed point of the projected
  // Newton step (Eq. 21 uses the Hessian in R^3, not on the sphere) sits a hair off the minimizer.
  // Above the default sigma the Newton system turns singular (each bump's Hessian has rank one) and
  // the fixed 0.1 gradient step overshoots, so single steps can rise there: not tested.
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0, 1);
  for (const char* preset : {"cube", "tetrahedron", "octahedron", "dodecahedron"}) {
    for (double sigma : {2.0, gauss::settings::sigma.default_value}) {
      if (std::string(preset) == "dodecahedron" && sigma < 4) continue;  // its bumps merge into a plateau
      const PreferenceFunction g = style(preset, sigma);
      for (int trial = 0; trial < 12; ++trial) {
        const Vector3d preferred = g.normals()[trial % g.normals().size()];
        const Vector3d axis = Vector3d(normal(rng), normal(rng), normal(rng)).cross(preferred).normalized();
        const Vector3d start = Eigen::AngleAxisd(10 * M_PI / 180 * uniform(rng), axis) * preferred;
        const LocalProblem lp = face_problem(g, start, 0.01, rng);
        const std::string where = std::string(preset) + " sigma " + std::to_string(sigma) + " trial " + std::to_string(trial);
        Vector3d n = lp.step(start);
        EXPECT_LT(lp.objective(n), lp.objective(start)) << where;
        double value = lp.objective(n);
        for (int it = 0; it < 40; ++it) {
          const Vector3d next = lp.step(n);
          ASSERT_NEAR(next.norm(), 1.0, 1e-14);
          EXPECT_LE(lp.objective(next), value + 1e-6) << where << " step " << it;
          n = next;
          value = lp.objective(n);
        }
        const Vector3d best = lp.brute_force_minimizer(preferred, 40 * M_PI / 180);
        EXPECT_LT(angle(n, best), 2e-3) << where;
        EXPECT_LE(value, lp.objective(best) + 1e-6) << where;
      }
    }
  }
}

TEST(NewtonNormal, WithoutCouplingGoesToTheNearestPreferredNormal) {
  // lambda = 0: L_n = -g, whose minimizers are the preferred normals themselves (Eq. 10: g = 1 there).
  const PreferenceFunction g(gauss::preset_style("octahedron"));
  const Vector3d es[3] = {Vector3d::UnitX(), Vector3d::UnitY(), Vector3d::UnitZ()};
  const double lw[3] = {0, 0, 0}, u[3] = {0, 0, 0};
  const Vector3d target = Vector3d(1, 1, 1).normalized();
  Vector3d n = Vector3d(1.0, 0.6, 0.9).normalized();
  for (int it = 0; it < 30; ++it) n = newton_normal(g, n, es, lw, u);
  EXPECT_LT(angle(n, target), 1e-6);
}

TEST(NewtonNormal, AlwaysReturnsAUnitVector) {
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  const PreferenceFunction g(gauss::preset_style("dodecahedron"));
  for (int trial = 0; trial < 1000; ++trial) {
    const Vector3d n = Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    const WildFace face = wild_face(rng, trial);
    const Vector3d m = newton_normal(g, n, face.es, face.lw, face.u);
    ASSERT_TRUE(m.allFinite());
    ASSERT_NEAR(m.norm(), 1.0, 1e-14);
  }
}

TEST(TrustRegionNormal, NeverRaisesLnAndReachesTheBruteForceMinimizerAtAnySigma) {
  // Above settings::paper_step_max_sigma, faces anywhere between the bumps: each call lowers L_n or
  // keeps n, and a few calls (a run makes one per step) settle at the minimizer brute force finds
  // within one bump's width, where the Riemannian gradient vanishes.
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0, 1);
  for (const char* preset : {"cube", "tetrahedron", "octahedron"}) {
    for (double sigma : {9.0, 12.0, 20.0, 60.0}) {
      const PreferenceFunction g = style(preset, sigma);
      for (int trial = 0; trial < 12; ++trial) {
        const Vector3d preferred = g.normals()[trial % g.normals().size()];
        const Vector3d axis = Vector3d(normal(rng), normal(rng), normal(rng)).cross(preferred).normalized();
        const Vector3d start = Eigen::AngleAxisd(25 * M_PI / 180 * uniform(rng), axis) * preferred;
        const LocalProblem lp = face_problem(g, start, 0.01, rng);
        const std::string where = std::string(preset) + " sigma " + std::to_string(sigma) + " trial " + std::to_string(trial);
        Vector3d n = start;
        double value = lp.objective(n);
        for (int call = 0; call < 10; ++call) {
          const Vector3d next = trust_region_normal(lp.g, n, lp.es, lp.lw, lp.u);
          ASSERT_NEAR(next.norm(), 1.0, 1e-14) << where;
          ASSERT_LE(lp.objective(next), value) << where << " call " << call;
          n = next;
          value = lp.objective(n);
        }
        const Vector3d grad = lp.gradient_fd(n, 1e-7);
        EXPECT_LT((grad - grad.dot(n) * n).norm(), 1e-5 * sigma) << where;
        // The start may lie outside every bump's reach (g ~ 0 there at sigma 60): then n stays nearby.
        if (g.value(start) > 1e-3) {
          const Vector3d best = lp.brute_force_minimizer(preferred, 40 * M_PI / 180);
          EXPECT_LT(angle(n, best), 2e-3) << where;
        }
      }
    }
  }
}

TEST(TrustRegionNormal, IsAFixedPointWhereLnIsStationary) {
  // Started at its own result, the step stays put: a run whose normals settled does not move them.
  std::mt19937 rng(12);
  const PreferenceFunction g = style("cube", 20.0);
  for (int trial = 0; trial < 20; ++trial) {
    const LocalProblem lp = face_problem(g, Vector3d(1, 0.2, 0.1 * trial).normalized(), 0.02, rng);
    Vector3d n = Vector3d(1, 0.2, 0.1 * trial).normalized();
    for (int call = 0; call < 20; ++call) n = trust_region_normal(lp.g, n, lp.es, lp.lw, lp.u);
    EXPECT_LT(angle(trust_region_normal(lp.g, n, lp.es, lp.lw, lp.u), n), 1e-9) << trial;
  }
}

TEST(TrustRegionNormal, AlwaysReturnsAUnitVector) {
  std::mt19937 rng(4);
  std::normal_distribution<double> normal;
  for (double sigma : {9.0, 100.0, 1000.0}) {
    const PreferenceFunction g = style("dodecahedron", sigma);
    for (int trial = 0; trial < 500; ++trial) {
      const Vector3d n = Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
      const WildFace face = wild_face(rng, trial);
      const Vector3d m = trust_region_normal(g, n, face.es, face.lw, face.u);
      ASSERT_TRUE(m.allFinite());
      ASSERT_NEAR(m.norm(), 1.0, 1e-14);
    }
  }
}

}  // namespace test_normal_step
