// Styles with many preferred normals: merging near-parallel directions, NormalField's tolerance at the
// input normals over the input families below and the whole sigma range, its truncation bound and the
// dense solution, its thread-independence, and the size limit.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <numeric>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "gauss/style/direction_merge.h"
#include "gauss/mesh/mesh_io.h"
#include "gauss/style/normal_field.h"
#include "gauss/util/parallel.h"
#include "gauss/style/preference_function.h"
#include "gauss/settings.h"
#include "test_directions.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_many_normals {

namespace {

using Eigen::Vector3d;

using gauss_test::random_directions;

// Nearly evenly spread directions (a Fibonacci sphere).
std::vector<Vector3d> spread_directions(int n) {
  std::vector<Vector3d> out(n);
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z);
    out[i] = Vector3d(r * std::cos(golden * i), r * std::sin(golden * i), z);
  }
  return out;
}

TEST(MergeDirections, ClustersAreTightSeparatedAndOrderIndependent) {
  std::vector<Vector3d> D = random_directions(20000, 1);
  std::vector<double> w(D.size());
  for (size_t i = 0; i < w.size(); ++i) w[i] = 1.0 + (i % 7);
  const double angle = 5.0 * M_PI / 180.0;
  const gauss::MergedDirections a = gauss::merge_directions(D, w, angle);
  ASSERT_EQ(a.cluster_of.size(), D.size());
  double total = 0;
  for (double x : a.weights) total += x;
  EXPECT_NEAR(total, std::accumulate(w.begin(), w.end(), 0.0), 1e-6);
  // Every input within the angle of its cluster's seed, hence within twice of its mean direction.
  for (size_t i = 0; i < D.size(); ++i)
    EXPECT_GE(D[i].dot(a.directions[a.cluster_of[i]]), std::cos(2 * angle) - 1e-12);
  // The same set in another order gives the same clusters, bit for bit.
  std::vector<int> perm(D.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937(7));
  std::vector<Vector3d> D2(D.size());
  std::vector<double> w2(D.size());
  for (size_t i = 0; i < D.size(); ++i) D2[i] = D[perm[i]], w2[i] = w[perm[i]];
  const gauss::MergedDirections b = gauss::merge_directions(D2, w2, angle);
  ASSERT_EQ(a.directions.size(), b.directions.size());
  for (size_t c = 0; c < a.directions.size(); ++c) {
    EXPECT_EQ(a.directions[c], b.directions[c]);
    EXPECT_EQ(a.weights[c], b.weights[c]);
  }
}

TEST(MergeDirections, ZeroAngleMergesOnlyIdenticalDirectionsAndBadInputIsRefused) {
  std::vector<Vector3d> D = {{1, 0, 0}, {0, 1, 0}, {1, 0, 0}, Vector3d(1, 1e-9, 0).normalized()};
  const gauss::MergedDirections m = gauss::merge_directions(D, {}, 0.0);
  EXPECT_EQ(m.directions.size(), 3u);
  EXPECT_EQ(m.cluster_of[0], m.cluster_of[2]);
  EXPECT_THROW(gauss::merge_directions(D, {}, 2.0), std::invalid_argument);
  EXPECT_THROW(gauss::merge_directions(D, {1, 1, -1, 1}, 0.1), std::invalid_argument);
  EXPECT_THROW(gauss::merge_directions({{2, 0, 0}}, {}, 0.1), std::invalid_argument);
}

// The input families a style's normals come in: spread, clustered (noisy copies of a few directions), a
// mesh's face normals, degenerate sets. Meshes come from ../shared/meshes; a missing one skips its family.
std::vector<Vector3d> noisy_copies(int n, int directions, double noise, unsigned seed) {
  const std::vector<Vector3d> base = random_directions(directions, seed);
  std::mt19937_64 rng(seed + 1);
  std::normal_distribution<double> normal;
  std::vector<Vector3d> out(n);
  for (int i = 0; i < n; ++i)
    out[i] = (base[i % directions] + noise * Vector3d(normal(rng), normal(rng), normal(rng))).normalized();
  return out;
}

std::vector<Vector3d> face_normals(const std::string& relative) {
  gauss::TriangleMesh m;
  try {
    m = gauss::read_mesh(std::string(GAUSS_MESH_DIR) + "/" + relative);
  } catch (const std::runtime_error&) {
    return {};
  }
  std::vector<Vector3d> out;
  for (int f = 0; f < m.num_faces(); ++f) {
    Vector3d p[3];
    for (int c = 0; c < 3; ++c) p[c] = Vector3d(m.V.data() + 3 * m.F[3 * f + c]);
    const Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
    if (n.norm() > 1e-300) out.push_back(n.normalized());
  }
  return out;
}

std::vector<Vector3d> family(const std::string& name) {
  if (name == "random") return random_directions(100000, 3);
  if (name == "clustered") return noisy_copies(100000, 6, 0.02, 5);
  if (name == "clustered_wide") return noisy_copies(100000, 20, 0.1, 6);
  if (name == "spot") return face_normals("small/spot_triangulated_2930.obj");
  if (name == "bunny") return face_normals("bunny/bun_zipper_35947.obj");
  if (name == "identical") return std::vector<Vector3d>(100000, Vector3d(0, 0.6, 0.8));
  std::vector<Vector3d> pairs;  // "antipodal": 50,000 random directions and their opposites
  for (const Vector3d& d : random_directions(50000, 8)) pairs.push_back(d), pairs.push_back(-d);
  return pairs;
}

class NormalFieldFamily : public testing::TestWithParam<const char*> {};

// The stated tolerance holds at every input normal over the whole sigma range, and max_input_error()
// is what evaluating g there gives. Set-up times are printed (re-measured on an idle machine, not
// asserted).
TEST_P(NormalFieldFamily, ReachesTheToleranceAtEveryInputNormalForEverySigma) {
  const std::vector<Vector3d> D = family(GetParam());
  if (D.empty()) GTEST_SKIP() << "mesh not found under " << GAUSS_MESH_DIR;
  for (double sigma : {1e-3, 1.0, 4.0, 16.0, 100.0, 1000.0}) {
    const auto t0 = std::chrono::steady_clock::now();
    const gauss::NormalField field(D, sigma);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    double worst = 0;
    for (const Vector3d& n : D) worst = std::max(worst, std::abs(field.value(n) - 1.0));
    const auto& st = field.stats();
    std::printf("%s (%zu) sigma %g: set-up %.0f ms, %d nodes (%d lattice), %d refinements, max |g(n_k) - 1| %.1e\n",
                GetParam(), D.size(), sigma, ms, field.num_nodes(), st.lattice_nodes, st.refinements, worst);
    EXPECT_LE(worst, gauss::NormalField::kTolerance) << GetParam() << " sigma " << sigma;
    EXPECT_NEAR(worst, field.max_input_error(), 1e-12) << GetParam() << " sigma " << sigma;
    EXPECT_LE(field.truncation_bound(), 1e-5) << GetParam() << " sigma " << sigma;
  }
}

INSTANTIATE_TEST_SUITE_P(All, NormalFieldFamily,
                         testing::Values("random", "clustered", "clustered_wide", "spot", "bunny", "identical",
                                         "antipodal"));

// A set of identical normals is one node with weight 1; opposite pairs are two: g = 1 there exactly
// up to the ridge.
TEST(NormalField, DegenerateSetsAreOneNodePerDistinctDirection) {
  for (double sigma : {1e-3, 4.0, 1000.0}) {
    const gauss::NormalField same(std::vector<Vector3d>(5000, Vector3d(0, 0.6, 0.8)), sigma);
    EXPECT_EQ(same.num_nodes(), 1);
    EXPECT_NEAR(same.value(Vector3d(0, 0.6, 0.8)), 1.0, gauss::NormalField::kRidge);
    std::vector<Vector3d> pair;
    for (int i = 0; i < 2000; ++i) pair.push_back(i % 2 ? Vector3d(1, 0, 0) : Vector3d(-1, 0, 0));
    const gauss::NormalField opposite(pair, sigma);
    EXPECT_EQ(opposite.num_nodes(), 2);
    EXPECT_NEAR(opposite.value(Vector3d(1, 0, 0)), 1.0, gauss::NormalField::kRidge);
  }
}

// g, its gradient and its Hessian as evaluated (truncated) against the full sums over the same nodes
// and weights: within truncation_bound(), sigma and sigma^2 times it (the stated bounds); and against
// the dense solution of Eq. 10 on a moderate set of spread normals (one node each): within the
// tolerance, sigma and sigma^2 times it.
TEST(NormalField, MatchesDenseSumsAndTheDenseSolution) {
  const std::vector<Vector3d> X = random_directions(2000, 5);
  auto full = [](const gauss::NormalField& f, const Vector3d& x, double sigma, double& g, Vector3d& grad,
                 Eigen::Matrix3d& hess) {
    g = 0, grad.setZero(), hess.setZero();
    for (int j = 0; j < f.num_nodes(); ++j) {
      const Vector3d& m = f.nodes()[j];
      const double e = f.weights()[j] * std::exp(sigma * (x.dot(m) - 1.0));
      g += e, grad += sigma * e * m, hess += sigma * sigma * e * m * m.transpose();
    }
  };
  auto truncated = [](const gauss::NormalField& f, const Vector3d& x, double sigma, double& g, Vector3d& grad,
                      Eigen::Matrix3d& hess) {
    double s[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    f.accumulate(x, s);
    g = s[0], grad = sigma * Vector3d(s[1], s[2], s[3]);
    hess << s[4], s[5], s[6], s[5], s[7], s[8], s[6], s[8], s[9];
    hess *= sigma * sigma;
  };
  // Truncation, on a set with lattice and data nodes (Spot's faces, or noisy copies without them).
  std::vector<Vector3d> mixed = face_normals("small/spot_triangulated_2930.obj");
  if (mixed.empty()) mixed = noisy_copies(6000, 40, 0.05, 11);
  for (double sigma : {16.0, 100.0, 1000.0}) {
    const gauss::NormalField f(mixed, sigma);
    const double bound = f.truncation_bound();
    ASSERT_GT(bound, 0.0);
    for (const Vector3d& x : X) {
      double g, gt;
      Vector3d grad, gradt;
      Eigen::Matrix3d hess, hesst;
      full(f, x, sigma, g, grad, hess);
      truncated(f, x, sigma, gt, gradt, hesst);
      EXPECT_LE(std::abs(g - gt), bound + 1e-14);
      EXPECT_LE((grad - gradt).cwiseAbs().maxCoeff(), sigma * bound + 1e-12);
      EXPECT_LE((hess - hesst).cwiseAbs().maxCoeff(), sigma * sigma * bound + 1e-10);
    }
  }
  // Dense Eq. 10 on 300 spread normals farther apart than a kernel width.
  const std::vector<Vector3d> D = spread_directions(300);
  const double sigma = 60.0;
  const gauss::NormalField field(D, sigma);
  ASSERT_EQ(field.num_nodes(), 300);
  Eigen::MatrixXd A(300, 300);
  for (int i = 0; i < 300; ++i)
    for (int j = 0; j < 300; ++j) A(i, j) = std::exp(sigma * (D[i].dot(D[j]) - 1.0));
  const Eigen::VectorXd dense = A.ldlt().solve(Eigen::VectorXd::Ones(300));
  const double tol = gauss::NormalField::kTolerance;
  for (const Vector3d& x : X) {
    double g = 0, gt;
    Vector3d grad = Vector3d::Zero(), gradt;
    Eigen::Matrix3d hess = Eigen::Matrix3d::Zero(), hesst;
    for (int i = 0; i < 300; ++i) {
      const double e = dense[i] * std::exp(sigma * (x.dot(D[i]) - 1.0));
      g += e, grad += sigma * e * D[i], hess += sigma * sigma * e * D[i] * D[i].transpose();
    }
    truncated(field, x, sigma, gt, gradt, hesst);
    EXPECT_NEAR(gt, g, tol);
    EXPECT_LE((grad - gradt).cwiseAbs().maxCoeff(), sigma * tol);
    EXPECT_LE((hess - hesst).cwiseAbs().maxCoeff(), sigma * sigma * tol);
  }
}

// Set-up runs its loops on the module's threads: the field is the same, bit for bit, on one or two.
TEST(NormalField, IsTheSameOnOneThreadOrTwo) {
  const std::vector<Vector3d> D = noisy_copies(20000, 30, 0.05, 12);
  for (double sigma : {4.0, 300.0}) {
    std::vector<double> w[2];
    std::vector<Vector3d> m[2];
    for (int threads : {1, 2}) {
      gauss::parallel::ScopedThreads scope(threads);
      const gauss::NormalField f(D, sigma);
      w[threads - 1] = f.weights();
      m[threads - 1] = f.nodes();
    }
    EXPECT_EQ(w[0], w[1]);
    EXPECT_EQ(m[0], m[1]);
  }
}

TEST(NormalField, TooManyNormalsAreRefusedWithAMessage) {
  gauss::StyleParams p;
  p.normals = random_directions(gauss::settings::max_style_normals + 1, 9);
  try {
    gauss::PreferenceFunction g(p);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("merge_directions"), std::string::npos) << e.what();
  }
}

}  // namespace

}  // namespace test_many_normals
