// Contact springs (contact_springs.h), the global step's side of Avoid Self-Intersections: the solve
// against a direct one, no trace without a contact, and parts pressed together that the guard alone
// stalled.
#include <algorithm>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "gauss/collision/self_intersection.h"
#include "gauss/mesh/alignment_share.h"
#include "gauss/mesh/mesh_topology.h"
#include "gauss/solver/constrained_laplacian.h"
#include "gauss/solver/contact_springs.h"
#include "gauss/solver/gauss_solver.h"
#include "gauss/style/presets.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_contact_springs {

using Eigen::Vector3d;
using gauss::GaussSolver;
using gauss_test::faces_of;
using gauss_test::points_of;

namespace {

struct Outcome {
  double share;
  int64_t crossings;
  int springs_max;
};

// Cube style at lambda 10 until reldV < 1e-3 (at most 400 steps).
Outcome stylize(const gauss::TriangleMesh& m, bool avoid, double stiffness) {
  GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), {}, nullptr, 10.0);
  const gauss::PreferenceFunction g(gauss::preset_style("cube"));
  s.set_styles({g});
  s.set_avoid_self_intersections(avoid);
  s.set_contact_stiffness(stiffness);
  s.set_tolerance(1e-3);
  int springs_max = 0;
  for (int i = 0; i < 400 && s.last_reldv() >= 1e-3; ++i) {
    s.step();
    springs_max = std::max(springs_max, s.contact_springs());
  }
  std::vector<double> out(m.V.size());
  s.copy_vertices(out.data());
  for (double c : out) EXPECT_TRUE(std::isfinite(c));
  return {gauss::alignment_share(out.data(), m.F.data(), m.num_faces(), g.normals()),
          gauss::count_self_intersections(faces_of(m), points_of(out)), springs_max};
}

}  // namespace

TEST(ContactSprings, TheSolveIsTheDenseSolveOfTheSystemWithPlaneSprings) {
  // An icosphere with one pin (no free component: no translation after the solve), unit edge
  // weights, random right-hand sides and held vertices whose anchors are moved off the sphere: x must
  // minimize x^T L x / 2 - b^T x + sum w (n . (x - p))^2 / 2. A small patch of a finer sphere (the
  // iterations solve on the plan above its springs) and nearly every vertex of a coarser one (they
  // solve whole, and the solution is summed up from their solves).
  std::vector<bool> whole;
  for (const auto& [level, above] : {std::pair<int, double>{5, 0.97}, {3, -0.9}}) {
    SCOPED_TRACE("icosphere " + std::to_string(level) + ", held above z = " + std::to_string(above));
    const gauss::TriangleMesh m = gauss_test::icosphere(level);
    const int nV = m.num_vertices();
    const gauss::MeshTopology topo = gauss::build_mesh_topology(nV, m.F.data(), m.num_faces());
    std::vector<Vector3d> rest(nV);
    for (int v = 0; v < nV; ++v) rest[v] = Vector3d(&m.V[3 * v]);
    const std::vector<double> weight(topo.edges.size(), 1.0);
    gauss::ConstrainedLaplacian L(topo, weight, rest, {0}, {rest[0]});
    const int n = L.num_unknowns();
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    std::vector<Vector3d> b(n);
    for (Vector3d& r : b) r = Vector3d(uniform(rng), uniform(rng), uniform(rng));
    std::vector<Vector3d> X = rest;
    std::vector<int> held;
    for (int v = 1; v < nV; ++v)
      if (rest[v].z() > above) held.push_back(v), X[v] *= 1.2;
    ASSERT_GT(held.size(), 5u);
    gauss::ContactSprings springs;
    springs.set_stiffness(2.0);
    springs.note_held(held, X, L, topo);
    ASSERT_TRUE(springs.active());

    // Directly: (L_ff (x) I3 + sum_i w_i n_i n_i^T) x = b + sum_i w_i n_i n_i^T p_i.
    std::vector<Eigen::Triplet<double>> entries;
    Eigen::VectorXd rhs(3 * n);
    for (int u = 0; u < n; ++u) rhs.segment<3>(3 * u) = b[u] + L.constant_rhs(u);
    for (size_t e = 0; e < topo.edges.size(); ++e) {
      const int a = L.unknown_of_vertex(topo.edges[e][0]), c = L.unknown_of_vertex(topo.edges[e][1]);
      for (int k = 0; k < 3; ++k) {
        if (a >= 0) entries.emplace_back(3 * a + k, 3 * a + k, 1.0);
        if (c >= 0) entries.emplace_back(3 * c + k, 3 * c + k, 1.0);
        if (a >= 0 && c >= 0) entries.emplace_back(3 * a + k, 3 * c + k, -1.0), entries.emplace_back(3 * c + k, 3 * a + k, -1.0);
      }
    }
    for (int v : held) {
      const int u = L.unknown_of_vertex(v);
      Vector3d normal = Vector3d::Zero();
      for (int i = topo.vertex_corner_start[v]; i < topo.vertex_corner_start[v + 1]; ++i) {
        const auto& f = topo.faces[topo.vertex_corners[i] / 3];
        normal += (X[f[1]] - X[f[0]]).cross(X[f[2]] - X[f[0]]);
      }
      normal.normalize();
      const Eigen::Matrix3d K = 2.0 * L.diagonal(u) * normal * normal.transpose();
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) entries.emplace_back(3 * u + i, 3 * u + j, K(i, j));
      rhs.segment<3>(3 * u) += K * X[v];
    }
    Eigen::SparseMatrix<double> A(3 * n, 3 * n);
    A.setFromTriplets(entries.begin(), entries.end());
    const Eigen::VectorXd exact = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>(A).solve(rhs);

    // Without springs, for the scale of their effect.
    for (int u = 0; u < n; ++u) L.set_rhs(u, L.constant_rhs(u) + b[u]);
    std::vector<Vector3d> plain = rest;
    L.solve(plain);
    for (int u = 0; u < n; ++u) L.set_rhs(u, L.constant_rhs(u) + b[u]);
    std::vector<Vector3d> solved = rest;
    springs.solve(L, solved);
    EXPECT_GT(springs.last_iterations(), 0);
    whole.push_back(springs.last_solved_whole());
    double error = 0, effect = 0;
    for (int u = 0; u < n; ++u) {
      const int v = L.vertex_of_unknown(u);
      error = std::max(error, (solved[v] - exact.segment<3>(3 * u)).cwiseAbs().maxCoeff());
      effect = std::max(effect, (plain[v] - exact.segment<3>(3 * u)).cwiseAbs().maxCoeff());
    }
    EXPECT_GT(effect, 1e-2);  // the springs change the solve
    EXPECT_LT(error, 0.02 * effect);  // the conjugate gradients stop at a residual of 1e-2
  }
  EXPECT_EQ(whole, (std::vector<bool>{false, true})) << "the patch solves on its plan, nearly every vertex whole";
}

TEST(ContactSprings, WithoutAContactTheyLeaveNoTrace) {
  // The icosphere under the cube style touches nowhere: no spring, and the guarded steps are bit for
  // bit those of the guard alone (stiffness 0). Compared with the guard alone rather than without the
  // guard: a long first step is checked in stages, whose sums round on their own.
  const gauss::TriangleMesh m = gauss_test::icosphere(3);
  GaussSolver alone(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
  GaussSolver springs(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
  for (GaussSolver* s : {&alone, &springs}) {
    s->set_styles({gauss::PreferenceFunction(gauss::preset_style("cube"))});
    s->set_avoid_self_intersections(true);
  }
  alone.set_contact_stiffness(0.0);
  ASSERT_GT(springs.contact_stiffness(), 0.0);
  for (int i = 0; i < 20; ++i) {
    alone.step();
    springs.step();
    ASSERT_EQ(springs.held_vertices(), 0);
    ASSERT_EQ(springs.contact_springs(), 0);
  }
  std::vector<double> a(m.V.size()), b(m.V.size());
  alone.copy_vertices(a.data());
  springs.copy_vertices(b.data());
  EXPECT_EQ(a, b);
}

TEST(ContactSprings, PlatesPressedTogetherGoOnTurningFlat) {
  // Without the guard the plates pass through each other and turn flat (share 1.0). The guard alone
  // holds the pressed ends and with them both plates (share about 0.52); with the springs the global
  // step knows of the contact, and the plates turn flat but for the contact (about 0.9). Where the
  // plates press together the run is chaotic: scaling the input by 1 + 3e-5 took one run from 0.92 to
  // 0.61, and the Windows build's maths library took another to 0.39. So the case is run on seven
  // inputs scaled by a few millionths, and their medians are compared (on 24 such inputs, 3 runs with
  // springs ended below the guard alone's best plus 0.2, none of the guard alone's above 0.6).
  std::vector<double> alone, springs;
  for (int k = 0; k < 7; ++k) {
    gauss::TriangleMesh m = gauss_test::leaning_plates(4);
    for (double& c : m.V) c *= 1.0 + 1e-6 * k;
    if (k == 0) {
      ASSERT_EQ(gauss::count_self_intersections(faces_of(m), points_of(m.V)), 0);
      const Outcome through = stylize(m, false, gauss::ContactSprings::kDefaultStiffness);
      EXPECT_GT(through.crossings, 0) << "the case does not press the plates together";
      EXPECT_GT(through.share, 0.95);
    }
    const Outcome held = stylize(m, true, 0.0);
    EXPECT_EQ(held.crossings, 0);
    EXPECT_EQ(held.springs_max, 0);
    const Outcome sprung = stylize(m, true, gauss::ContactSprings::kDefaultStiffness);
    EXPECT_EQ(sprung.crossings, 0);
    EXPECT_GT(sprung.springs_max, 0);
    alone.push_back(held.share);
    springs.push_back(sprung.share);
  }
  const auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  EXPECT_LT(median(alone), 0.75) << "the guard alone does not stall here: the case tests nothing";
  EXPECT_GT(median(springs), median(alone) + 0.2);
}

}  // namespace test_contact_springs
