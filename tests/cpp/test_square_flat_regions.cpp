// Square Flat Regions (settings::square_flat_regions, flat_regions.h): the regions it finds, the
// squareness it reaches on a capped 32-sided cylinder and on a pot's lid with both methods, and that
// off the solver steps bit for bit as without the setting.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "gauss/mesh/squareness.h"
#include "gauss/settings.h"
#include "gauss/solver/gauss_solver.h"
#include "gauss/style/presets.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_square_flat_regions {

using gauss::GaussSolver;

namespace {

struct Case {
  gauss::Method method;
  double lambda;  // the method's
};

GaussSolver make(const gauss::TriangleMesh& m, const Case& c) {
  GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), {}, nullptr,
                c.method == gauss::Method::gauss ? c.lambda : gauss::settings::lambda.default_value);
  if (c.method == gauss::Method::cubic) s.set_cubic_lambda(c.lambda);
  s.set_method(c.method);
  return s;
}

std::vector<double> result(const GaussSolver& s, int count) {
  std::vector<double> out(3 * static_cast<size_t>(count));
  s.copy_vertices(out.data());
  return out;
}

double cap_squareness(const gauss::TriangleMesh& m, const Case& c, bool on) {
  GaussSolver s = make(m, c);
  s.set_square_flat_regions(on);
  s.step_until(gauss::settings::tolerance.default_value, 300);
  const std::vector<double> out = result(s, m.num_vertices());
  for (double x : out) EXPECT_TRUE(std::isfinite(x));
  return gauss::squareness(out.data(), m.F.data(), m.num_faces(), Eigen::Vector3d::UnitZ());
}

const Case kCases[] = {{gauss::Method::cubic, 0.2}, {gauss::Method::cubic, 0.4}, {gauss::Method::gauss, 1.0}};

}  // namespace

TEST(SquareFlatRegions, FindsTheCapsOfACylinderTheLidOfAPotAndNothingOnASphere) {
  const gauss::TriangleMesh cylinder = gauss_test::capped_cylinder(), pot = gauss_test::pot();
  const gauss::TriangleMesh sphere = gauss_test::icosphere(3), cube = gauss_test::grid_cube(4);
  GaussSolver s(cylinder.V.data(), cylinder.num_vertices(), cylinder.F.data(), cylinder.num_faces());
  EXPECT_TRUE(s.flat_regions().empty());  // off: nothing searched
  s.set_square_flat_regions(true);
  ASSERT_EQ(s.flat_regions().size(), 2u);
  for (const gauss::FlatRegion& r : s.flat_regions()) {
    EXPECT_NEAR(std::abs(r.normal.z()), 1.0, 1e-9);
    // The 32-gon has no clear smallest rectangle: the axes are the object's own, x and y.
    EXPECT_NEAR(std::abs(r.u.x()) + std::abs(r.u.y()), 1.0, 1e-9);
    EXPECT_NEAR(std::abs(r.u.dot(r.v)) + std::abs(r.u.dot(r.normal)), 0.0, 1e-12);
  }
  GaussSolver p(pot.V.data(), pot.num_vertices(), pot.F.data(), pot.num_faces());
  p.set_square_flat_regions(true);
  ASSERT_EQ(p.flat_regions().size(), 1u);
  EXPECT_NEAR(p.flat_regions()[0].normal.z(), 1.0, 1e-9);
  GaussSolver b(sphere.V.data(), sphere.num_vertices(), sphere.F.data(), sphere.num_faces());
  b.set_square_flat_regions(true);
  EXPECT_TRUE(b.flat_regions().empty());
  GaussSolver k(cube.V.data(), cube.num_vertices(), cube.F.data(), cube.num_faces());
  k.set_square_flat_regions(true);
  EXPECT_EQ(k.flat_regions().size(), 6u);
}

TEST(SquareFlatRegions, SquaresTheCapOfACylinderWithEitherMethod) {
  // Measured and the table: docs/styles.md#square-flat-regions.
  const gauss::TriangleMesh m = gauss_test::capped_cylinder();
  for (const Case& c : kCases) {
    const double off = cap_squareness(m, c, false), on = cap_squareness(m, c, true);
    EXPECT_LT(off, 0.9) << static_cast<int>(c.method) << " " << c.lambda;  // the starting point
    EXPECT_GE(on, 0.9) << static_cast<int>(c.method) << " " << c.lambda;
  }
}

TEST(SquareFlatRegions, SquaresTheLidOfAPot) {
  const gauss::TriangleMesh m = gauss_test::pot();
  for (const Case& c : kCases) {
    const double on = cap_squareness(m, c, true);
    EXPECT_GE(on, 0.9) << static_cast<int>(c.method) << " " << c.lambda;
  }
}

TEST(SquareFlatRegions, LeavesACubeAndASphereAlone) {
  // A cube's faces are its flat regions and already square: on moves it by a hair at most. A sphere has
  // none: on steps bit for bit as off.
  const gauss::TriangleMesh cube = gauss_test::grid_cube(4), sphere = gauss_test::icosphere(3);
  for (const Case& c : kCases)
    for (const gauss::TriangleMesh* m : {&cube, &sphere}) {
      GaussSolver a = make(*m, c), b = make(*m, c);
      b.set_square_flat_regions(true);
      for (int i = 0; i < 20; ++i) a.step(), b.step();
      const std::vector<double> x = result(a, m->num_vertices()), y = result(b, m->num_vertices());
      double d = 0;
      for (size_t i = 0; i < x.size(); ++i) d = std::max(d, std::abs(x[i] - y[i]));
      if (m == &sphere) EXPECT_EQ(d, 0.0) << static_cast<int>(c.method);
      else EXPECT_LT(d, 0.01) << static_cast<int>(c.method);  // the cube's side is 2
    }
}

TEST(SquareFlatRegions, OffStepsBitForBitAsWithoutIt) {
  const gauss::TriangleMesh m = gauss_test::capped_cylinder();
  for (const Case& c : kCases)
    for (bool resolution_independent : {false, true}) {
      GaussSolver plain = make(m, c), toggled = make(m, c), explicit_off = make(m, c);
      plain.set_resolution_independent(resolution_independent);
      toggled.set_resolution_independent(resolution_independent);
      explicit_off.set_resolution_independent(resolution_independent);
      explicit_off.set_square_flat_regions(false);
      toggled.set_square_flat_regions(true);
      toggled.step();
      toggled.set_square_flat_regions(false);
      toggled.reset();
      for (int i = 0; i < 15; ++i) plain.step(), toggled.step(), explicit_off.step();
      EXPECT_EQ(result(plain, m.num_vertices()), result(toggled, m.num_vertices()));
      EXPECT_EQ(result(plain, m.num_vertices()), result(explicit_off, m.num_vertices()));
    }
}

TEST(SquareFlatRegions, FollowsTheFacesStrength) {
  // Unstyled faces (mu 0) get no pull: a cylinder without a style steps as plain ARAP, on or off.
  const gauss::TriangleMesh m = gauss_test::capped_cylinder();
  GaussSolver a(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
  GaussSolver b(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
  const std::vector<int64_t> none(m.num_faces(), -1);
  a.set_face_styles(none.data(), m.num_faces());
  b.set_face_styles(none.data(), m.num_faces());
  b.set_square_flat_regions(true);
  for (int i = 0; i < 5; ++i) a.step(), b.step();
  const std::vector<double> x = result(a, m.num_vertices()), y = result(b, m.num_vertices());
  double d = 0;
  for (size_t i = 0; i < x.size(); ++i) d = std::max(d, std::abs(x[i] - y[i]));
  EXPECT_LT(d, 1e-12);
}

}  // namespace test_square_flat_regions
