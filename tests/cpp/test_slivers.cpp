// Slivers: meshes with angles near 0 or 180 degrees (n-gon caps with collinear
// sides fanned into zero-area and long thin triangles, filled holes, near-collinear points next to good
// triangles) stylize to bounded results however long the run, and well-shaped meshes keep their exact
// cotangent weights (so their results are unchanged).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "../fuzz/fuzz_harness.h"
#include "gauss/mesh/alignment_share.h"
#include "gauss/solver/cotangent_weights.h"
#include "gauss/solver/gauss_solver.h"
#include "gauss/mesh/mesh_io.h"
#include "gauss/mesh/mesh_topology.h"
#include "gauss/style/presets.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_slivers {

namespace {

using Eigen::Vector3d;
using Mesh = gauss::TriangleMesh;
constexpr double kPi = 3.14159265358979323846;

// Results must stay within this many bounding-box sizes of the box's centre (the fuzz harness
// allows 10 for arbitrary inputs; these meshes have no pins and shrink rather than grow).
constexpr double kGrowth = 2.0;

Mesh ngon_cylinder(int sides, int cuts) {
  gauss_fuzz::Mesh m;
  gauss_fuzz::add_ngon_prism(m, sides, cuts, 2.0);
  return Mesh{m.V, m.F};
}

// An icosphere with the cap around +z cut off and the hole filled by a fan from one rim vertex: long
// thin triangles, as a hole filler makes them.
Mesh hole_filled_by_fan() {
  const Mesh s = gauss_test::icosphere(3);
  Mesh m{s.V, {}};
  auto z = [&](int64_t v) { return s.V[3 * v + 2]; };
  for (int f = 0; f < s.num_faces(); ++f)
    if (z(s.F[3 * f]) < 0.8 || z(s.F[3 * f + 1]) < 0.8 || z(s.F[3 * f + 2]) < 0.8)
      m.F.insert(m.F.end(), {s.F[3 * f], s.F[3 * f + 1], s.F[3 * f + 2]});
  // The rim: vertices with z >= 0.8 of the remaining faces, ordered by angle around z.
  std::vector<int64_t> rim;
  std::vector<uint8_t> seen(s.num_vertices(), 0);
  for (int64_t v : m.F)
    if (z(v) >= 0.8 && !seen[v]++) rim.push_back(v);
  auto angle = [&](int64_t v) { return std::atan2(s.V[3 * v + 1], s.V[3 * v]); };
  std::sort(rim.begin(), rim.end(), [&](int64_t a, int64_t b) { return angle(a) < angle(b); });
  for (size_t i = 1; i + 1 < rim.size(); ++i) m.F.insert(m.F.end(), {rim[0], rim[i], rim[i + 1]});
  return m;
}

// A grid of good triangles whose middle row of vertices sits 1e-7 off the straight line between its
// neighbours, with that row's triangles split so that slivers of ~180 degrees sit between good ones.
Mesh slivers_in_grid(int n) {
  Mesh m;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) m.V.insert(m.V.end(), {double(i), double(j), 0.3 * std::sin(0.7 * i + 0.4 * j)});
  auto id = [&](int i, int j) { return static_cast<int64_t>(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (i == n / 2) {
        // A point almost on the quad's diagonal: two good triangles and two slivers.
        const int64_t c = m.num_vertices();
        const Vector3d a(m.V[3 * id(i, j)], m.V[3 * id(i, j) + 1], m.V[3 * id(i, j) + 2]);
        const Vector3d b(m.V[3 * id(i + 1, j + 1)], m.V[3 * id(i + 1, j + 1) + 1], m.V[3 * id(i + 1, j + 1) + 2]);
        const Vector3d p = 0.5 * (a + b) + Vector3d(1e-7, -1e-7, 0);
        m.V.insert(m.V.end(), {p.x(), p.y(), p.z()});
        m.F.insert(m.F.end(), {id(i, j), id(i + 1, j), c, c, id(i + 1, j), id(i + 1, j + 1)});
        m.F.insert(m.F.end(), {id(i, j), c, id(i, j + 1), c, id(i + 1, j + 1), id(i, j + 1)});
      } else {
        m.F.insert(m.F.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  return m;
}

struct Box {
  Vector3d centre;
  double size;
};
Box box(const std::vector<double>& V) {
  Vector3d lo = Vector3d::Constant(INFINITY), hi = -lo;
  for (size_t v = 0; v < V.size() / 3; ++v) {
    const Vector3d p(V[3 * v], V[3 * v + 1], V[3 * v + 2]);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {0.5 * (lo + hi), (hi - lo).maxCoeff()};
}

// Runs `steps` steps and checks, at each checkpoint, that coordinates and energies are finite and the
// mesh stays within kGrowth sizes of its rest box's centre. Returns the final vertices.
// With Method::cubic, lambda is the cubic method's.
std::vector<double> run_bounded(const Mesh& m, double lambda, int steps, const std::string& what,
                                gauss::Method method = gauss::Method::gauss) {
  const bool cubic = method == gauss::Method::cubic;
  gauss::GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), {}, nullptr,
                       cubic ? gauss::settings::lambda.default_value : lambda);
  if (cubic) s.set_cubic_lambda(lambda);
  s.set_method(method);
  const Box rest = box(m.V);
  std::vector<double> out(m.V.size());
  for (int done = 0; done < steps;) {
    const int next = std::min(steps, done == 0 ? 50 : 2 * done);
    while (done < next) s.step(), ++done;
    s.copy_vertices(out.data());
    double worst = 0;
    for (size_t v = 0; v < out.size() / 3; ++v)
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(out[3 * v + k] - rest.centre[k]) / rest.size);
    EXPECT_TRUE(std::isfinite(worst) && worst <= kGrowth)
        << what << " lambda " << lambda << ": after " << done << " steps a vertex is " << worst
        << " sizes from the centre";
    EXPECT_TRUE(std::isfinite(s.arap_energy()) && std::isfinite(s.g_energy()) && std::isfinite(s.cubic_energy()))
        << what << " after " << done;
    if (::testing::Test::HasFailure()) break;
  }
  return out;
}

TEST(Slivers, CotangentWeightsOfWellShapedTrianglesAreExact) {
  const Vector3d e[3] = {{1, 0, 0}, {-0.3, 0.9, 0.1}, {-0.7, -0.9, -0.1}};
  const gauss::TriangleWeights tw = gauss::cotangent_weights(e);
  ASSERT_TRUE(tw.well_shaped);
  const double twice_area = e[0].cross(e[1]).norm();
  for (int k = 0; k < 3; ++k) EXPECT_EQ(tw.w[k], 0.5 * (-e[(k + 2) % 3].dot(e[(k + 1) % 3]) / twice_area));
}

TEST(Slivers, CotangentWeightsOfSliversAreTheSmallPositiveOnes) {
  for (double offset : {0.0, 1e-12, 1e-7, 1e-3}) {  // angle at the apex ~180 degrees
    const Vector3d a(0, 0, 0), b(1, 0, 0), c(0.5, offset, 0);
    const Vector3d e[3] = {b - a, c - b, a - c};
    const gauss::TriangleWeights tw = gauss::cotangent_weights(e);
    EXPECT_FALSE(tw.well_shaped) << offset;
    for (double w : tw.w) EXPECT_EQ(w, gauss::kIllShapedWeight);
  }
  // Just inside the limit: kept.
  const double angle = std::atan(1.0 / (0.99 * gauss::kMaxCotangent));  // cot = 0.99 * limit
  const Vector3d e[3] = {{1, 0, 0}, {std::cos(angle) - 1, std::sin(angle), 0}, {-std::cos(angle), -std::sin(angle), 0}};
  EXPECT_TRUE(gauss::cotangent_weights(e).well_shaped);
}

TEST(Slivers, SubdividedCylinderCapsStayBoundedFor1000Steps) {
  for (int cuts : {4, 8})
    for (double lambda : {1.0, 4.0, 20.0}) run_bounded(ngon_cylinder(16, cuts), lambda, 1000, "cylinder, cuts " + std::to_string(cuts));
}

TEST(Slivers, HoleFilledByAFanStaysBoundedFor1000Steps) {
  for (double lambda : {1.0, 4.0, 20.0}) run_bounded(hole_filled_by_fan(), lambda, 1000, "hole filled by a fan");
}

TEST(Slivers, SliversNextToGoodTrianglesStayBoundedFor1000Steps) {
  for (double lambda : {1.0, 4.0, 20.0}) run_bounded(slivers_in_grid(12), lambda, 1000, "slivers in a grid");
}

TEST(Slivers, TheCubicMethodStaysBoundedFor1000StepsToo) {
  for (double lambda : {0.2, gauss::settings::cubic_lambda.max}) {
    run_bounded(ngon_cylinder(16, 8), lambda, 1000, "cubic: cylinder", gauss::Method::cubic);
    run_bounded(hole_filled_by_fan(), lambda, 1000, "cubic: hole filled by a fan", gauss::Method::cubic);
    run_bounded(slivers_in_grid(12), lambda, 1000, "cubic: slivers in a grid", gauss::Method::cubic);
  }
}

// The raw cotangent weights of a mesh (before either floor) over the solver's topology: slot[f][k]
// (cot / 2 of the angle opposite the edge from corner k to k + 1), edge[e] the sum of its slots, and
// the number of faces cotangent_weights calls ill-shaped.
struct RawWeights {
  std::vector<std::array<double, 3>> slot;
  std::vector<double> edge;
  int ill_shaped = 0;
};
RawWeights raw_weights(const Mesh& m, const gauss::MeshTopology& topo) {
  RawWeights out{std::vector<std::array<double, 3>>(topo.faces.size()), std::vector<double>(topo.edges.size(), 0.0)};
  for (size_t f = 0; f < topo.faces.size(); ++f) {
    Vector3d e[3];
    for (int k = 0; k < 3; ++k)
      e[k] = Vector3d(&m.V[3 * topo.faces[f][(k + 1) % 3]]) - Vector3d(&m.V[3 * topo.faces[f][k]]);
    const gauss::TriangleWeights tw = gauss::cotangent_weights(e);
    out.ill_shaped += !tw.well_shaped;
    for (int k = 0; k < 3; ++k) out.slot[f][k] = tw.w[k], out.edge[topo.face_edge[f][k]] += tw.w[k];
  }
  return out;
}

// Two triangles over one edge of length 2, the apex of each `apex` off the edge's midpoint: for a small
// apex the two opposite angles approach 180 degrees, and the edge's weight is (apex^2 - 1) / (2 apex).
Mesh kite(double apex) { return Mesh{{0, 0, 0, 2, 0, 0, 1, apex, 0, 1, -apex, 0}, {0, 1, 2, 1, 0, 3}}; }

TEST(Slivers, StronglyNegativeEdgesGetTheSmallPositiveWeight) {
  for (double apex : {0.08, 0.15}) {  // edge weights -6.21 and -3.26
    const Mesh m = kite(apex);
    const gauss::MeshTopology topo = gauss::build_mesh_topology(m.num_vertices(), m.F.data(), m.num_faces());
    RawWeights raw = raw_weights(m, topo);
    ASSERT_EQ(raw.ill_shaped, 0);
    std::vector<std::array<double, 3>>& slot = raw.slot;
    std::vector<double>& edge = raw.edge;
    const std::vector<double> before = edge;
    const std::vector<std::array<double, 3>> slot_before = slot;
    const int changed = gauss::floor_negative_edge_weights(topo, slot, edge);
    for (size_t e = 0; e < edge.size(); ++e) {
      double sum = 0;
      for (int i = topo.edge_slot_start[e]; i < topo.edge_slot_start[e + 1]; ++i)
        sum += slot[topo.edge_slots[i] / 3][topo.edge_slots[i] % 3];
      EXPECT_DOUBLE_EQ(sum, edge[e]) << apex;
      if (before[e] < gauss::kMinEdgeWeight) {
        EXPECT_EQ(edge[e], gauss::kIllShapedWeight) << apex;
      } else {
        EXPECT_EQ(edge[e], before[e]) << apex;  // bit for bit
        for (int i = topo.edge_slot_start[e]; i < topo.edge_slot_start[e + 1]; ++i)
          EXPECT_EQ(slot[topo.edge_slots[i] / 3][topo.edge_slots[i] % 3],
                    slot_before[topo.edge_slots[i] / 3][topo.edge_slots[i] % 3]);
      }
    }
    EXPECT_EQ(changed, apex < 0.1 ? 1 : 0) << apex;
  }
}

// Every term of the global step takes the floored weights, the Laplacian's: the cubic method's
// right-hand side once took the raw cotangents, and with no style at all a step then moved the rest
// shape around a floored edge.
TEST(Slivers, ARestShapeWithAFlooredEdgeStaysPutWithoutAStyle) {
  const Mesh m = kite(0.08);  // its middle edge weighs -6.2: floored
  for (gauss::Method method : {gauss::Method::gauss, gauss::Method::cubic}) {
    gauss::GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
    s.set_method(method);
    if (method == gauss::Method::cubic) s.set_cubic_lambda(0.0);
    else s.set_lambda(0.0);
    for (int i = 0; i < 3; ++i) s.step();
    std::vector<double> out(m.V.size());
    s.copy_vertices(out.data());
    for (size_t i = 0; i < out.size(); ++i) EXPECT_NEAR(out[i], m.V[i], 1e-12) << (method == gauss::Method::cubic ? "cubic" : "gauss") << " coordinate " << i;
  }
}

// The hole-filled bunny (smallest angle 0.002 degrees) stylized well for 100 steps, then fell apart
// (the sliver weights fixed that); the few edges of its fill below kMinEdgeWeight (down to -37) then
// kept it from settling: its fill moved up to a tenth of its size at every step for 400 steps. The
// camel head's (down to -20) never settled either, under Cube or Cylinder.
TEST(Slivers, MeshesWithStronglyNegativeEdgesSettle) {
  const std::pair<const char*, const char*> runs[] = {{"bunny/bunny_watertight_34834.obj", "cube"},
                                                       {"boundary/camelhead_11381.obj", "cylinder"}};
  for (const auto& [rel, style] : runs) {
    const std::string path = gauss_test::shared_mesh(rel);
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent";
    const Mesh m = gauss::read_mesh(path);
    gauss::GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), {}, nullptr, 4.0);
    const gauss::PreferenceFunction g(gauss::preset_style(style));
    s.set_styles({g});
    int steps = 0;
    while (steps < 300 && !(s.last_reldv() < 1e-3)) s.step(), ++steps;
    EXPECT_LT(s.last_reldv(), 1e-3) << rel << " after " << steps << " steps";
    std::vector<double> out(m.V.size());
    s.copy_vertices(out.data());
    const Box rest = box(m.V), now = box(out);
    EXPECT_LE((now.centre - rest.centre).norm(), rest.size) << rel;
    EXPECT_LE(now.size, kGrowth * rest.size) << rel;
    if (std::string(style) == "cube")
      EXPECT_GE(gauss::alignment_share(out.data(), m.F.data(), m.num_faces(), g.normals(), 10.0), 0.85) << rel;
  }
}

// Meshes without slivers or strongly negative edges keep every cotangent weight, so neither floor can
// change their results.
TEST(Slivers, WellShapedSharedMeshesKeepTheirCotangentWeights) {
  for (const char* rel : {"bunny/bunny_cubicstylization_6172.obj", "armadillo/armadillo_libigl_43243.obj",
                          "small/spot_triangulated_2930.obj"}) {
    const std::string path = gauss_test::shared_mesh(rel);
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent";
    const Mesh m = gauss::read_mesh(path);
    const RawWeights raw = raw_weights(m, gauss::build_mesh_topology(m.num_vertices(), m.F.data(), m.num_faces()));
    EXPECT_EQ(raw.ill_shaped, 0) << rel;
    EXPECT_EQ(std::count_if(raw.edge.begin(), raw.edge.end(), [](double w) { return w < gauss::kMinEdgeWeight; }), 0)
        << rel;
  }
}

}  // namespace

}  // namespace test_slivers
