// The Gauss Map style (StyleKind::gauss_map, example_normals.h): an example's face normals with their
// areas; each face prefers the example normal nearest to its own, pulled by that normal's area density.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "gauss/solver/gauss_solver.h"
#include "gauss/style/example_normals.h"
#include "gauss/style/preference_function.h"
#include "gauss/style/presets.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_gauss_map_style {

namespace {

using Eigen::Vector3d;

std::vector<Vector3d> random_units(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::vector<Vector3d> out;
  while (static_cast<int>(out.size()) < count) {
    const Vector3d v(normal(rng), normal(rng), normal(rng));
    if (v.norm() > 1e-3) out.push_back(v.normalized());
  }
  return out;
}

int brute_nearest(const std::vector<Vector3d>& normals, const Vector3d& x) {
  int best = 0;
  for (int k = 1; k < static_cast<int>(normals.size()); ++k)
    if ((normals[k] - x).squaredNorm() < (normals[best] - x).squaredNorm()) best = k;
  return best;
}

TEST(ExampleNormals, NearestIsTheBruteForceNearest) {
  for (int count : {1, 2, 7, 100, 3000}) {
    const std::vector<Vector3d> normals = random_units(count, 5u + count);
    const gauss::ExampleNormals example(normals, {});
    for (const Vector3d& x : random_units(500, 99u)) {
      const int k = example.nearest(x * 3.0);  // any length
      EXPECT_DOUBLE_EQ((normals[k] - x).squaredNorm(), (normals[brute_nearest(normals, x)] - x).squaredNorm())
          << count;
    }
  }
}

TEST(ExampleNormals, AreasAreSharesAndRareDirectionsPullLess) {
  // Four axis directions with much area and one lone direction with little.
  const std::vector<Vector3d> normals = {Vector3d::UnitX(), -Vector3d::UnitX(), Vector3d::UnitY(), -Vector3d::UnitY(),
                                         Vector3d(0, 0.6, 0.8)};
  const gauss::ExampleNormals example(normals, {1, 1, 1, 1, 0.01});
  double sum = 0;
  for (double a : example.areas()) sum += a;
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(example.pull()[0], 1.0);
  EXPECT_NEAR(example.pull()[4], 0.1, 1e-9);  // (0.01 / 1) ^ 0.5
  EXPECT_THROW(gauss::ExampleNormals(normals, {1, 1, 1, -1, 1}), std::invalid_argument);
  EXPECT_THROW(gauss::ExampleNormals(normals, {0, 0, 0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(gauss::ExampleNormals(normals, {1, 1}), std::invalid_argument);
  EXPECT_THROW(gauss::ExampleNormals({}, {}), std::invalid_argument);
}

TEST(ExampleNormals, TheNearestFewAreTheBruteForceNearestInOrder) {
  const std::vector<Vector3d> normals = random_units(400, 17u);
  const gauss::ExampleNormals example(normals, {});
  for (const Vector3d& x : random_units(200, 23u)) {
    int index[8];
    ASSERT_EQ(example.nearest(x, 8, index), 8);
    std::vector<double> d2(normals.size());
    for (size_t k = 0; k < normals.size(); ++k) d2[k] = (normals[k] - x).squaredNorm();
    std::vector<double> sorted = d2;
    std::sort(sorted.begin(), sorted.end());
    for (int i = 0; i < 8; ++i) EXPECT_DOUBLE_EQ(d2[index[i]], sorted[i]);
  }
  int index[8];
  EXPECT_EQ(gauss::ExampleNormals({Vector3d::UnitX(), Vector3d::UnitY()}, {}).nearest(Vector3d::UnitX(), 8, index), 2);
}

TEST(GaussMapStyle, ACubesGaussMapIsTheCubePreset) {
  gauss::StyleParams p;
  p.kind = gauss::StyleKind::gauss_map;
  p.normals = {Vector3d::UnitX(), -Vector3d::UnitX(), Vector3d::UnitY(), -Vector3d::UnitY(),
               Vector3d::UnitZ(), -Vector3d::UnitZ()};
  const gauss::PreferenceFunction g(p), cube(gauss::preset_style("cube"));
  ASSERT_NE(g.example(), nullptr);
  for (const Vector3d& x : random_units(50, 8u)) {
    double v, w;
    Vector3d grad, grad_cube;
    Eigen::Matrix3d hess, hess_cube;
    g.evaluate(x, Vector3d(x + Vector3d(0.1, 0.2, 0.0)), v, grad, hess);  // all six are summed, whatever the anchor
    cube.evaluate(x, w, grad_cube, hess_cube);
    EXPECT_NEAR(v, w, 1e-12);
    EXPECT_LT((grad - grad_cube).norm(), 1e-10);
    EXPECT_LT((hess - hess_cube).norm(), 1e-9);
  }
  p.ring_offsets = {0.5};
  EXPECT_THROW(gauss::PreferenceFunction{p}, std::invalid_argument);
  p.ring_offsets.clear();
  p.normals.clear();
  EXPECT_THROW(gauss::PreferenceFunction{p}, std::invalid_argument);
}

TEST(GaussMapStyle, ACubesGaussMapStylizesAsTheCubeStyle) {
  // The example is a cube's six face directions with equal areas: its g is the Cube preset's, so the
  // runs agree up to rounding.
  const gauss::TriangleMesh m = gauss_test::icosphere(3);
  gauss::StyleParams p;
  p.kind = gauss::StyleKind::gauss_map;
  p.normals = {Vector3d::UnitX(), -Vector3d::UnitX(), Vector3d::UnitY(), -Vector3d::UnitY(),
               Vector3d::UnitZ(), -Vector3d::UnitZ()};
  p.areas = {2, 2, 2, 2, 2, 2};
  std::vector<double> a(m.V.size()), b(m.V.size());
  for (int run = 0; run < 2; ++run) {
    gauss::GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
    s.set_styles({run == 0 ? gauss::PreferenceFunction(gauss::preset_style("cube")) : gauss::PreferenceFunction(p)});
    for (int i = 0; i < 60; ++i) s.step();
    s.copy_vertices(run == 0 ? a.data() : b.data());
  }
  double worst = 0;
  for (size_t i = 0; i < a.size(); i += 3)
    worst = std::max(worst, Vector3d(a[i] - b[i], a[i + 1] - b[i + 1], a[i + 2] - b[i + 2]).norm());
  EXPECT_LT(worst, 1e-6);
}

}  // namespace

}  // namespace test_gauss_map_style
