// The cubic method (cubic_local_step.h) through GaussSolver: what it does to shapes, how styles scale
// and turn it, pins, determinism, switching methods, bad input. Robustness on broken meshes is covered
// by test_robustness.cpp and test_slivers.cpp, which run every mesh through both methods.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <vector>

#include "gauss/mesh/alignment_share.h"
#include "gauss/solver/gauss_solver.h"
#include "gauss/util/parallel.h"
#include "gauss/style/presets.h"
#include "test_expect.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_cubic {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using gauss::GaussSolver;
using gauss::Method;
using gauss::PreferenceFunction;
using Mesh = gauss::TriangleMesh;

std::unique_ptr<GaussSolver> cubic_solver(const Mesh& m, double lambda, const std::vector<int64_t>& pins = {}) {
  auto s = std::make_unique<GaussSolver>(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), pins);
  s->set_cubic_lambda(lambda);
  s->set_method(Method::cubic);
  return s;
}

std::vector<double> vertices(const GaussSolver& s) {
  std::vector<double> out(3 * static_cast<size_t>(s.num_vertices()));
  s.copy_vertices(out.data());
  return out;
}

std::vector<double> run(GaussSolver& s, int steps) {
  for (int i = 0; i < steps; ++i) s.step();
  return vertices(s);
}

std::vector<Vector3d> axes(const Matrix3d& Q = Matrix3d::Identity()) {
  std::vector<Vector3d> a;
  for (int k = 0; k < 3; ++k) a.push_back(Q.col(k)), a.push_back(-Q.col(k));
  return a;
}

double share(const Mesh& m, const std::vector<double>& V, const Matrix3d& Q = Matrix3d::Identity()) {
  return gauss::alignment_share(V.data(), m.F.data(), m.num_faces(), axes(Q), 10.0);
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0;
  for (size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

Mesh rotated(Mesh m, const Matrix3d& Q) {
  for (size_t v = 0; v < m.V.size() / 3; ++v) {
    const Vector3d p = Q * Vector3d(m.V[3 * v], m.V[3 * v + 1], m.V[3 * v + 2]);
    for (int k = 0; k < 3; ++k) m.V[3 * v + k] = p[k];
  }
  return m;
}

const Matrix3d kTurn = Eigen::AngleAxisd(0.6, Vector3d(1, 2, 3).normalized()).toRotationMatrix();

// Every face normal within `degrees` of its rest normal.
void expect_faces_keep_their_normals(const Mesh& m, const std::vector<double>& V, double degrees) {
  for (int f = 0; f < m.num_faces(); ++f) {
    auto normal = [&](const std::vector<double>& X) {
      Vector3d p[3];
      for (int k = 0; k < 3; ++k) p[k] = Vector3d(&X[3 * m.F[3 * f + k]]);
      return Vector3d((p[1] - p[0]).cross(p[2] - p[0]).normalized());
    };
    ASSERT_GE(normal(V).dot(normal(m.V)), std::cos(degrees * M_PI / 180)) << "face " << f;
  }
}

TEST(Cubic, ACubeStaysACube) {
  // A cube's corner and edge normals are diagonal, where ||R n||_1 is largest, so the energy turns
  // them a little (by the per-vertex ADMM's tolerance, as in the reference): the cube keeps its faces
  // axis-aligned and its size within 0.2%, and then stays put (within 0.01%).
  const Mesh cube = gauss_test::grid_cube(6);  // side 2
  for (const Matrix3d& Q : {Matrix3d(Matrix3d::Identity()), kTurn}) {  // the style turned with the mesh
    const Mesh m = rotated(cube, Q);
    auto s = cubic_solver(m, 0.4);
    gauss::StyleParams p = gauss::preset_style("cube");
    p.rotation = Q;
    s->set_styles({PreferenceFunction(p)});
    const std::vector<double> settled = run(*s, 100);
    EXPECT_LE(max_abs_diff(settled, m.V), 0.004);
    expect_faces_keep_their_normals(m, settled, 1.0);
    EXPECT_LE(max_abs_diff(run(*s, 400), settled), 2e-4);
  }
}

TEST(Cubic, TheShareRisesWithLambdaOnASphere) {
  const Mesh sphere = gauss_test::icosphere(3);
  double previous = share(sphere, sphere.V);
  for (double lambda : {0.05, 0.1, 0.2, 0.4, 0.8}) {
    auto s = cubic_solver(sphere, lambda);
    const double now = share(sphere, run(*s, 150));
    EXPECT_GT(now, previous + 0.02) << "lambda " << lambda;
    previous = now;
  }
  EXPECT_GT(previous, 0.5);
}

TEST(Cubic, TheStylesRotationTurnsTheCube) {
  const Mesh sphere = gauss_test::icosphere(3);
  auto s = cubic_solver(sphere, 0.4);
  gauss::StyleParams p = gauss::preset_style("cube");
  p.rotation = kTurn;
  s->set_styles({PreferenceFunction(p)});
  const std::vector<double> out = run(*s, 150);
  EXPECT_GT(share(sphere, out, kTurn), 0.4);
  EXPECT_LT(share(sphere, out), 0.2);
}

TEST(Cubic, MuScalesLambda) {
  // lambda_i = lambda * a_i * (mean mu): mu 2 at lambda 0.2 is mu 1 at lambda 0.4, bit for bit.
  const Mesh sphere = gauss_test::icosphere(3);
  auto a = cubic_solver(sphere, 0.4);
  auto b = cubic_solver(sphere, 0.2);
  gauss::StyleParams p = gauss::preset_style("cube");
  p.mu = 2.0;
  b->set_styles({PreferenceFunction(p)});
  const std::vector<double> result = run(*a, 30);
  EXPECT_EQ(result, run(*b, 30));
  EXPECT_GT(share(sphere, result), share(sphere, sphere.V) + 0.05);  // both did stylize
}

TEST(Cubic, RegionsWithMuZeroStayArap) {
  // Two separate spheres; the second is dragged by a pin (so that ARAP has something to do) and its
  // faces have a style of mu 0. It must move exactly as in a run without any cubic term (lambda 0),
  // while the first sphere gets cubic.
  const Mesh one = gauss_test::icosphere(3);
  const Mesh m = gauss_test::beside(one, one);
  const int n = one.num_vertices();
  const std::vector<int64_t> pins = {n, n + 1};
  std::vector<double> targets = {m.V[3 * n] + 0.5, m.V[3 * n + 1], m.V[3 * n + 2] + 0.3,
                                 m.V[3 * (n + 1)], m.V[3 * (n + 1) + 1], m.V[3 * (n + 1) + 2]};
  std::vector<int64_t> face_styles(m.num_faces(), 0);
  for (int f = one.num_faces(); f < m.num_faces(); ++f) face_styles[f] = 1;
  gauss::StyleParams off = gauss::preset_style("cube");
  off.mu = 0.0;
  std::vector<std::vector<double>> results;
  for (double lambda : {0.4, 0.0}) {
    auto s = cubic_solver(m, lambda, pins);
    // Plain steps: the acceleration's global restart takes a sum over all vertices, so the cubic
    // sphere's run would change when the other one restarts.
    s->set_acceleration(false);
    s->set_styles({PreferenceFunction(gauss::preset_style("cube")), PreferenceFunction(off)});
    s->set_face_styles(face_styles.data(), m.num_faces());
    s->set_pin_positions(targets.data(), 2);
    results.push_back(run(*s, 40));
  }
  const std::vector<double> second_a(results[0].begin() + 3 * n, results[0].end());
  const std::vector<double> second_b(results[1].begin() + 3 * n, results[1].end());
  EXPECT_EQ(second_a, second_b);
  EXPECT_GT(max_abs_diff(second_a, std::vector<double>(m.V.begin() + 3 * n, m.V.end())), 0.05);
  const std::vector<double> first_a(results[0].begin(), results[0].begin() + 3 * n);
  EXPECT_GT(share(one, first_a), share(one, one.V) + 0.1);
}

TEST(Cubic, PinsHoldAndCanMove) {
  const Mesh sphere = gauss_test::icosphere(3);
  auto s = cubic_solver(sphere, 0.4, {0, 7, 100});
  std::vector<double> out = run(*s, 20);
  for (int64_t p : {0, 7, 100})
    for (int k = 0; k < 3; ++k) EXPECT_EQ(out[3 * p + k], sphere.V[3 * p + k]);
  const int factorizations = s->factorization_count();
  const std::vector<double> targets = {0.1, 0.2, 1.3, sphere.V[21], sphere.V[22], sphere.V[23], 0, 0, -1.2};
  s->set_pin_positions(targets.data(), 3);
  out = run(*s, 20);
  const int64_t pinned[3] = {0, 7, 100};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(out[3 * pinned[i] + k], targets[3 * i + k]);
  EXPECT_EQ(s->factorization_count(), factorizations);
}

TEST(Cubic, SwitchingMethodsKeepsTheSetUpAndResetRepeatsARun) {
  const Mesh sphere = gauss_test::icosphere(3);
  GaussSolver s(sphere.V.data(), sphere.num_vertices(), sphere.F.data(), sphere.num_faces());
  run(s, 5);
  s.set_method(Method::cubic);
  const std::vector<double> mixed = run(s, 5);
  s.set_method(Method::gauss);
  run(s, 2);
  EXPECT_EQ(s.factorization_count(), 1);
  // A run switched to cubic at step 5 differs from a Gauss run and from a cubic run.
  GaussSolver g(sphere.V.data(), sphere.num_vertices(), sphere.F.data(), sphere.num_faces());
  EXPECT_NE(run(g, 10), mixed);
  // reset() restarts the cubic ADMM too: the same run again, bit for bit.
  s.reset();
  s.set_method(Method::cubic);
  const std::vector<double> first = run(s, 10);
  s.reset();
  EXPECT_EQ(run(s, 10), first);
}

TEST(Cubic, TheSameForAnyThreadCount) {
  const Mesh sphere = rotated(gauss_test::icosphere(5), kTurn);  // 10,242 vertices: parallel loops
  std::vector<std::vector<double>> results;
  const int saved = gauss::parallel::max_threads();
  for (int threads : {1, 2, 3}) {
    gauss::parallel::set_max_threads(threads);
    auto s = cubic_solver(sphere, 0.4);
    results.push_back(run(*s, 6));
  }
  gauss::parallel::set_max_threads(saved);
  EXPECT_EQ(results[0], results[1]);
  EXPECT_EQ(results[0], results[2]);
  EXPECT_GT(share(sphere, results[0]), share(sphere, sphere.V) + 0.02);  // it did stylize
}

TEST(Cubic, BadSettingsAreRefusedAndChangeNothing) {
  const Mesh sphere = gauss_test::icosphere(2);
  GaussSolver s(sphere.V.data(), sphere.num_vertices(), sphere.F.data(), sphere.num_faces());
  for (double bad : {-0.1, double(NAN), double(INFINITY), gauss::settings::cubic_lambda.max * 1.01})
    gauss_test::expect_refused([&] { s.set_cubic_lambda(bad); }, "cubic lambda");
  EXPECT_EQ(s.cubic_lambda(), gauss::settings::cubic_lambda.default_value);
  gauss_test::expect_refused([&] { s.set_method(static_cast<Method>(7)); }, "method");
  EXPECT_EQ(s.method(), Method::gauss);
  // The limits themselves are accepted and stay finite.
  for (double lambda : {gauss::settings::cubic_lambda.min, gauss::settings::cubic_lambda.max}) {
    auto c = cubic_solver(sphere, lambda);
    EXPECT_EQ(c->cubic_lambda(), lambda);  // taken as given, not clamped
    for (double x : run(*c, 20)) ASSERT_TRUE(std::isfinite(x));
  }
}

}  // namespace

}  // namespace test_cubic
