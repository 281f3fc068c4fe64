// The Sheet Metal style (a developable style, preference_function.h, developable_normals.h): each face
// prefers its own normal turned onto its neighbourhood's great circle, so the surface unbends into
// pieces that bend one way at a time; and the two measures of that (developability.h,
// flat_vertex_share.h).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "gauss/mesh/developability.h"
#include "gauss/mesh/flat_vertex_share.h"
#include "gauss/mesh/mesh_io.h"
#include "gauss/mesh/mesh_topology.h"
#include "gauss/solver/developable_normals.h"
#include "gauss/solver/gauss_solver.h"
#include "gauss/settings.h"
#include "gauss/style/presets.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_sheet_metal {

namespace {

const double kPi = 3.14159265358979323846;

// An open tube of `around` by `along` quads (two triangles each), radius 1, length 2: developable.
gauss::TriangleMesh tube(int around, int along) {
  gauss::TriangleMesh m;
  for (int j = 0; j <= along; ++j)
    for (int i = 0; i < around; ++i) {
      const double a = 2 * kPi * i / around;
      m.V.insert(m.V.end(), {std::cos(a), std::sin(a), 2.0 * j / along});
    }
  for (int j = 0; j < along; ++j)
    for (int i = 0; i < around; ++i) {
      const int64_t a = j * around + i, b = j * around + (i + 1) % around, c = a + around, d = b + around;
      m.F.insert(m.F.end(), {a, b, d, a, d, c});
    }
  return m;
}

struct Result {
  double developability_in, developability_out, flat_in, flat_out;
};

// Sheet Metal at its defaults (the preset's sigma, settings::sheet_metal_lambda) for `steps` steps.
Result stylize(const gauss::TriangleMesh& m, int steps) {
  gauss::GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), {}, nullptr,
                       gauss::settings::sheet_metal_lambda);
  s.set_styles({gauss::PreferenceFunction(gauss::preset_style("sheet_metal"))});
  for (int i = 0; i < steps; ++i) s.step();
  std::vector<double> out(m.V.size());
  s.copy_vertices(out.data());
  for (double x : out) EXPECT_TRUE(std::isfinite(x));
  const int nV = m.num_vertices(), nF = m.num_faces();
  return {gauss::developability(m.V.data(), nV, m.F.data(), nF), gauss::developability(out.data(), nV, m.F.data(), nF),
          gauss::flat_vertex_share(m.V.data(), nV, m.F.data(), nF),
          gauss::flat_vertex_share(out.data(), nV, m.F.data(), nF)};
}

}  // namespace

TEST(SheetMetal, DevelopabilityIsZeroOnARolledSheetAndNotOnASphere) {
  const gauss::TriangleMesh t = tube(24, 6);
  EXPECT_LT(gauss::developability(t.V.data(), t.num_vertices(), t.F.data(), t.num_faces()), 1e-12);
  const gauss::TriangleMesh s = gauss_test::icosphere(3);
  EXPECT_GT(gauss::developability(s.V.data(), s.num_vertices(), s.F.data(), s.num_faces()), 1e-3);
  // A cube's corners: three directions, each with a good share of the area (1/3 each is the most there is).
  const gauss::TriangleMesh c = gauss_test::grid_cube(1);
  const double cube = gauss::developability(c.V.data(), c.num_vertices(), c.F.data(), c.num_faces());
  EXPECT_GT(cube, 0.1);
  EXPECT_LE(cube, 1.0 / 3 + 1e-12);
}

TEST(SheetMetal, FlatVertexShareCountsInteriorVerticesWithoutAngleDefect) {
  // The tube's vertices are flat (defect 0) but its two rims are boundary and not counted.
  const gauss::TriangleMesh t = tube(24, 6);
  EXPECT_DOUBLE_EQ(gauss::flat_vertex_share(t.V.data(), t.num_vertices(), t.F.data(), t.num_faces()), 1.0);
  // An icosphere: every vertex has a positive defect (4 pi spread over 642 vertices, ~0.02 rad).
  const gauss::TriangleMesh s = gauss_test::icosphere(3);
  EXPECT_DOUBLE_EQ(gauss::flat_vertex_share(s.V.data(), s.num_vertices(), s.F.data(), s.num_faces()), 0.0);
}

TEST(SheetMetal, AFaceOnARolledSheetPrefersItsOwnNormal) {
  const gauss::TriangleMesh t = tube(24, 6);
  const gauss::MeshTopology topo = gauss::build_mesh_topology(t.num_vertices(), t.F.data(), t.num_faces());
  std::vector<Eigen::Vector3d> X(t.num_vertices());
  for (int v = 0; v < t.num_vertices(); ++v) X[v] = Eigen::Vector3d(t.V[3 * v], t.V[3 * v + 1], t.V[3 * v + 2]);
  std::vector<Eigen::Matrix3d> moment(t.num_vertices());
  std::vector<Eigen::Vector3d> ruling(t.num_vertices());
  std::vector<Eigen::Vector3d> preferred(topo.faces.size());
  gauss::developable_normals(topo, X, moment, ruling, preferred);
  for (size_t f = 0; f < topo.faces.size(); ++f) {
    const auto& tri = topo.faces[f];
    const Eigen::Vector3d n = (X[tri[1]] - X[tri[0]]).cross(X[tri[2]] - X[tri[0]]).normalized();
    EXPECT_GT(preferred[f].dot(n), 1.0 - 1e-9) << "face " << f;
  }
}

TEST(SheetMetal, TheStyleTakesNoDirections) {
  gauss::StyleParams p = gauss::preset_style("sheet_metal");
  EXPECT_TRUE(gauss::PreferenceFunction(p).developable());
  p.normals = {Eigen::Vector3d::UnitZ()};
  EXPECT_THROW(gauss::PreferenceFunction{p}, std::invalid_argument);
}

TEST(SheetMetal, UnbendsASphere) {
  // At the defaults the developability falls about fivefold in 100 steps and most vertices end flat;
  // without the style's pull neither would move (a sphere is ARAP's rest).
  const Result r = stylize(gauss_test::icosphere(3), 100);
  EXPECT_LT(r.developability_out, r.developability_in / 4) << r.developability_in << " -> " << r.developability_out;
  EXPECT_GT(r.flat_out, 0.5) << r.flat_in << " -> " << r.flat_out;
}

TEST(SheetMetal, UnbendsSpot) {
  // Tenfold less developability is the style's target on Spot; what it reaches there is measured in
  // docs/styles.md#sheet-metal.
  const std::string spot = gauss_test::shared_mesh("small/spot_triangulated_2930.obj");
  if (!std::ifstream(spot).good()) GTEST_SKIP() << "../shared/meshes not present";
  const Result r = stylize(gauss::read_mesh(spot), 200);
  EXPECT_LT(r.developability_out, r.developability_in / 10) << r.developability_in << " -> " << r.developability_out;
  EXPECT_GT(r.flat_out, 1.8 * r.flat_in) << r.flat_in << " -> " << r.flat_out;
}

}  // namespace test_sheet_metal
