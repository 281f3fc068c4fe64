// Self-intersections: the triangle test, the count, and the solver's guard (avoid_self_intersections).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>

#include "gauss/collision/self_intersection.h"
#include "gauss/collision/triangle_intersection.h"
#include "gauss/mesh/mesh_io.h"
#include "gauss/solver/gauss_solver.h"
#include "gauss/style/presets.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_self_intersection {

using Eigen::Vector3d;
using gauss::GaussSolver;
using gauss_test::faces_of;
using gauss_test::points_of;
using gauss::Triangle;

namespace {

Triangle triangle(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  Triangle t;
  t << a, b, c;
  return t;
}

// Every pair, tested without the hierarchy.
int64_t brute_force_count(const std::vector<std::array<int, 3>>& faces, const std::vector<Vector3d>& X) {
  int64_t count = 0;
  for (size_t f = 0; f < faces.size(); ++f)
    for (size_t g = f + 1; g < faces.size(); ++g) {
      int shared = 0;
      std::array<int, 3> a = faces[f], b = faces[g];
      // shared corners first, in the same order
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          if (a[i] == b[j] && i >= shared && j >= shared) {
            std::swap(a[i], a[shared]);
            std::swap(b[j], b[shared]);
            ++shared;
          }
      count += gauss::triangles_cross(triangle(X[a[0]], X[a[1]], X[a[2]]), triangle(X[b[0]], X[b[1]], X[b[2]]), shared);
    }
  return count;
}

// A thin plate (1 long along x, 0.05 thick, 0.3 wide), turned by `degrees` about z, centred at x.
gauss::TriangleMesh plate(double degrees, double x) {
  gauss::TriangleMesh m = gauss_test::grid_cube(2);  // [-1, 1]^3
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(degrees * M_PI / 180, Vector3d::UnitZ()).toRotationMatrix();
  for (int v = 0; v < m.num_vertices(); ++v) {
    const Vector3d p = turn * Vector3d(0.5 * m.V[3 * v], 0.025 * m.V[3 * v + 1], 0.15 * m.V[3 * v + 2]);
    m.V[3 * v] = p.x() + x;
    m.V[3 * v + 1] = p.y();
    m.V[3 * v + 2] = p.z();
  }
  return m;
}

// Two plates leaning towards each other like \ / turned upside down, their near ends 0.08 apart.
// The cube style turns each flat (35 degrees is nearer to flat than to upright), which swings the
// near ends into each other.
gauss::TriangleMesh plates_swinging_together() {
  gauss::TriangleMesh a = plate(35, -0.45), b = plate(-35, 0.45);
  const int64_t offset = a.num_vertices();
  a.V.insert(a.V.end(), b.V.begin(), b.V.end());
  for (int64_t i : b.F) a.F.push_back(i + offset);
  return a;
}

std::vector<double> stylize(const gauss::TriangleMesh& m, bool avoid, int steps, int* held_max = nullptr) {
  GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), {}, nullptr, 10.0);
  s.set_styles({gauss::PreferenceFunction(gauss::preset_style("cube"))});
  s.set_avoid_self_intersections(avoid);
  EXPECT_EQ(s.avoid_self_intersections(), avoid);
  std::vector<double> out(m.V.size());
  for (int i = 0; i < steps; ++i) {
    s.step();
    if (held_max) *held_max = std::max(*held_max, s.held_vertices());
    s.copy_vertices(out.data());
    for (double c : out) EXPECT_TRUE(std::isfinite(c));
  }
  return out;
}

}  // namespace

TEST(TriangleIntersection, CrossingAsBlenderCountsIt) {
  const Triangle flat = triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  // Apart; crossing through the interior; touching an edge only.
  EXPECT_FALSE(gauss::triangles_cross(flat, triangle({0, 0, 1}, {1, 0, 1}, {0, 1, 1}), 0));
  EXPECT_TRUE(gauss::triangles_cross(flat, triangle({0.3, 0.3, -0.5}, {0.3, 0.3, 0.5}, {0.35, 0.2, 0.5}), 0));
  // Sharing a corner: crossing beyond it, or only meeting in it (a bent fan, a flat fan).
  EXPECT_TRUE(gauss::triangles_cross(flat, triangle({0, 0, 0}, {0.4, 0.4, -0.5}, {0.4, 0.4, 0.5}), 1));
  EXPECT_FALSE(gauss::triangles_cross(flat, triangle({0, 0, 0}, {-1, 0, 0.3}, {0, -1, 0.3}), 1));
  EXPECT_FALSE(gauss::triangles_cross(flat, triangle({0, 0, 0}, {-1, 0, 0}, {0, -1, 0}), 1));
  // Sharing an edge never crosses; coplanar overlap is not counted (as in Blender).
  EXPECT_FALSE(gauss::triangles_cross(flat, triangle({0, 0, 0}, {1, 0, 0}, {0.5, 0.8, 0.01}), 2));
  EXPECT_FALSE(gauss::triangles_cross(flat, triangle({0.1, 0.1, 0}, {0.6, 0.1, 0}, {0.1, 0.6, 0}), 0));
}

TEST(TriangleIntersection, DistanceAndMargin) {
  const Triangle flat = triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const Triangle above = triangle({0.2, 0.2, 0.01}, {0.5, 0.2, 0.01}, {0.2, 0.5, 0.01});
  EXPECT_NEAR(gauss::triangle_distance(flat, above), 0.01, 1e-12);
  EXPECT_TRUE(gauss::triangles_closer_than(flat, above, 0, 0.02));
  EXPECT_FALSE(gauss::triangles_closer_than(flat, above, 0, 0.005));
  const Triangle beside = triangle({1.5, 0, 0}, {2, 0, 0}, {1.5, 1, 0});  // coplanar, 0.5 away
  EXPECT_NEAR(gauss::triangle_distance(flat, beside), 0.5, 1e-12);
}

TEST(SelfIntersections, TheCountIsEveryCrossingPairOnce) {
  // Two icospheres overlapping: the count through the hierarchy equals the count over every pair.
  gauss::TriangleMesh a = gauss_test::icosphere(2), b = gauss_test::icosphere(2);
  const int64_t offset = a.num_vertices();
  for (size_t i = 0; i < b.V.size(); ++i) a.V.push_back(b.V[i] + (i % 3 == 0 ? 1.2 : 0.0));
  for (int64_t i : b.F) a.F.push_back(i + offset);
  const auto faces = faces_of(a);
  const auto X = points_of(a.V);
  const int64_t expected = brute_force_count(faces, X);
  EXPECT_GT(expected, 20);
  EXPECT_EQ(gauss::count_self_intersections(faces, X), expected);
  // A clean closed mesh has none.
  const gauss::TriangleMesh sphere = gauss_test::icosphere(3);
  EXPECT_EQ(gauss::count_self_intersections(faces_of(sphere), points_of(sphere.V)), 0);
}

TEST(SelfIntersections, PlatesSwungTogetherPassThroughEachOtherWithoutTheGuardOnly) {
  const gauss::TriangleMesh m = plates_swinging_together();
  const auto faces = faces_of(m);
  ASSERT_EQ(gauss::count_self_intersections(faces, points_of(m.V)), 0);
  const std::vector<double> free = stylize(m, false, 60);
  EXPECT_GT(gauss::count_self_intersections(faces, points_of(free)), 0);
  int held = 0;
  const std::vector<double> guarded = stylize(m, true, 60, &held);
  EXPECT_EQ(gauss::count_self_intersections(faces, points_of(guarded)), 0);
  EXPECT_GT(held, 0);  // the guard did the work, not luck
}

TEST(SelfIntersections, AMeshThatAlreadyIntersectsCrossesNowhereElseAndIsHeldOnlyThere) {
  // The two plates, the second moved into the first: some pairs cross from the start. (Offsets off
  // the grid's round numbers: a corner exactly on another face crosses or not by rounding, in one
  // frame and not in the other.) Their crossing may slide along as the plates move, but no crossing
  // begins away from it, and the guard never holds back every vertex (which would freeze such a mesh
  // whole).
  gauss::TriangleMesh m = plates_swinging_together();
  for (int v = m.num_vertices() / 2; v < m.num_vertices(); ++v) {
    m.V[3 * v] -= 0.1234;
    m.V[3 * v + 1] += 0.0071;
  }
  const auto faces = faces_of(m);
  const std::vector<Vector3d> start = points_of(m.V);
  const auto centroid = [&](int f, const std::vector<Vector3d>& X) {
    return (X[faces[f][0]] + X[faces[f][1]] + X[faces[f][2]]) / 3.0;
  };
  const auto before = gauss::self_intersecting_pairs(faces, start);
  ASSERT_GT(before.size(), 0u);
  int held = 0;
  const std::vector<double> guarded = stylize(m, true, 60, &held);
  EXPECT_GT(held, 0);
  EXPECT_LT(held, m.num_vertices());
  const std::vector<Vector3d> end = points_of(guarded);
  for (const auto& pair : gauss::self_intersecting_pairs(faces, end))
    for (int f : pair) {
      double nearest = INFINITY;  // to a face that crossed at the start, both where they are now
      for (const auto& old : before)
        for (int g : old) nearest = std::min(nearest, (centroid(f, end) - centroid(g, end)).norm());
      EXPECT_LT(nearest, 0.15) << "face " << f << " crosses away from the input's crossing";
    }
}

TEST(SelfIntersections, TheGuardOffIsTheSolverAsBefore) {
  // Switched on and off again, the guard leaves no trace: bit-identical steps.
  const gauss::TriangleMesh m = gauss_test::icosphere(3);
  GaussSolver plain(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
  GaussSolver toggled(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
  toggled.set_avoid_self_intersections(true);
  toggled.set_avoid_self_intersections(false);
  for (int i = 0; i < 10; ++i) {
    plain.step();
    toggled.step();
  }
  std::vector<double> a(m.V.size()), b(m.V.size());
  plain.copy_vertices(a.data());
  toggled.copy_vertices(b.data());
  EXPECT_EQ(a, b);
}

TEST(SelfIntersections, AStagedMoveWithNothingToHoldIsTheStepExactly) {
  // A long move is checked in stages (kStageMove); their sum is the move only up to rounding, so a
  // guard that holds nothing must still hand back the step's own coordinates, bit for bit.
  const gauss::TriangleMesh m = gauss_test::icosphere(2);
  const std::vector<std::array<int, 3>> faces = faces_of(m);
  const std::vector<Vector3d> safe = points_of(m.V);
  const gauss::MeshTopology topo = gauss::build_mesh_topology(m.num_vertices(), m.F.data(), m.num_faces());
  gauss::SelfIntersectionGuard guard(topo, safe);
  guard.start_from(safe);
  std::vector<Vector3d> X(safe.size());
  for (size_t v = 0; v < X.size(); ++v)  // a sphere grown by an odd factor and turned: no contact anywhere
    X[v] = Eigen::AngleAxisd(0.3, Vector3d(1, 2, 3).normalized()) * (1.3719 * safe[v]) + Vector3d(0.0123, -0.071, 0.29);
  const std::vector<Vector3d> step = X;
  EXPECT_EQ(guard.limit(safe, X), 0);
  bool exact = true;
  for (size_t v = 0; v < X.size(); ++v) exact = exact && X[v] == step[v];
  EXPECT_TRUE(exact) << "a vertex never held moved by the stages' rounding";
}

TEST(SelfIntersections, TheGuardHoldingNothingIsTheSolverAsBefore) {
  // On a mesh the style never folds into itself, the guard on is the plain run bit for bit: whether a
  // run is guarded must not change a result it never had to hold back.
  const gauss::TriangleMesh m = gauss_test::icosphere(3);
  int held = 0;
  const std::vector<double> plain = stylize(m, false, 40);
  const std::vector<double> guarded = stylize(m, true, 40, &held);
  EXPECT_EQ(held, 0) << "the case is for a guard with nothing to hold";
  EXPECT_EQ(plain, guarded);
}

TEST(SelfIntersections, PinsDraggedIntoTheMeshStopShort) {
  // The first plate's vertices pinned and dragged in one move 0.2 down and turned by 20 degrees, into
  // the second plate laid flat 0.2 under it (the guard checks so long a move in stages).
  gauss::TriangleMesh m = plate(0, 0);
  const gauss::TriangleMesh below = plate(0, 0);
  const int64_t offset = m.num_vertices();
  for (size_t i = 0; i < below.V.size(); ++i) m.V.push_back(below.V[i] - (i % 3 == 1 ? 0.2 : 0.0));
  for (int64_t i : below.F) m.F.push_back(i + offset);
  std::vector<int64_t> pins;
  std::vector<double> targets;
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(20 * M_PI / 180, Vector3d::UnitZ()).toRotationMatrix();
  for (int v = 0; v < offset; ++v) {
    pins.push_back(v);
    const Vector3d target = turn * Vector3d(m.V[3 * v], m.V[3 * v + 1], m.V[3 * v + 2]) - Vector3d(0, 0.2, 0);
    targets.insert(targets.end(), {target.x(), target.y(), target.z()});
  }
  const auto faces = faces_of(m);
  for (bool avoid : {false, true}) {
    GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), pins, nullptr, 1.0);
    s.set_avoid_self_intersections(avoid);
    s.set_pin_positions(targets.data(), static_cast<int>(pins.size()));
    for (int i = 0; i < 5; ++i) s.step();
    std::vector<double> out(m.V.size());
    s.copy_vertices(out.data());
    // Without the guard the pinned plate cuts through the other one.
    EXPECT_EQ(gauss::count_self_intersections(faces, points_of(out)) > 0, !avoid) << "avoid " << avoid;
  }
}

TEST(SelfIntersections, CleanMeshesThatAStrongStyleFoldsStayClean) {
  // Spot under the Cube style at lambda 20 crosses itself without the guard.
  const std::string spot = gauss_test::shared_mesh("small/spot_triangulated_2930.obj");
  if (!std::ifstream(spot).good()) GTEST_SKIP() << "../shared/meshes not present";
  const gauss::TriangleMesh m = gauss::read_mesh(spot);
  const auto faces = faces_of(m);
  GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), {}, nullptr, 20.0);
  s.set_styles({gauss::PreferenceFunction(gauss::preset_style("cube"))});
  s.set_avoid_self_intersections(true);
  s.step_until(1e-3, 2000);
  std::vector<double> out(m.V.size());
  s.copy_vertices(out.data());
  EXPECT_EQ(gauss::count_self_intersections(faces, points_of(out)), 0);
}

}  // namespace test_self_intersection
