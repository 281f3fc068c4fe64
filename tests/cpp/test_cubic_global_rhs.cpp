// The cubic method's global-step right-hand side folded per vertex (CubicLocalStep::global_rhs) against
// its per-face definition, sum over the faces f of v of R_f (w d^_prev - w d^_next) with R_f the mean of
// f's three vertex rotations and w the face's cotangent weights (cubic_local_step.h).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <random>
#include <vector>

#include "gauss/mesh/mesh_topology.h"
#include "gauss/solver/cotangent_weights.h"
#include "gauss/solver/cubic_local_step.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_cubic_global_rhs {

namespace {

using Eigen::Matrix3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

Quaterniond random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  return Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
}

// Largest |folded - per-face| over the vertices, relative to the largest |per-face|.
double relative_rhs_difference(const gauss::TriangleMesh& m, unsigned seed) {
  std::vector<int64_t> F(m.F.begin(), m.F.end());
  const gauss::MeshTopology topo = gauss::build_mesh_topology(m.num_vertices(), F.data(), m.num_faces());
  const int nV = m.num_vertices();
  std::vector<Vector3d> rest(nV);
  for (int v = 0; v < nV; ++v) rest[v] = Vector3d(m.V[3 * v], m.V[3 * v + 1], m.V[3 * v + 2]);
  std::vector<double> edge_weight(topo.edges.size(), 0.0);
  std::vector<std::array<double, 3>> slot_weight(topo.faces.size());
  std::vector<Vector3d> expected(nV, Vector3d::Zero());
  std::mt19937 rng(seed);
  std::vector<Matrix3d> rotation(nV);
  for (auto& R : rotation) R = random_rotation(rng).toRotationMatrix();
  for (size_t f = 0; f < topo.faces.size(); ++f) {
    const auto& t = topo.faces[f];
    Vector3d e[3];
    for (int k = 0; k < 3; ++k) e[k] = rest[t[(k + 1) % 3]] - rest[t[k]];
    const gauss::TriangleWeights w = gauss::cotangent_weights(e);
    for (int k = 0; k < 3; ++k) edge_weight[topo.face_edge[f][k]] += w.w[k], slot_weight[f][k] = w.w[k];
    const Matrix3d Rf = (rotation[t[0]] + rotation[t[1]] + rotation[t[2]]) / 3.0;
    // Vertex t[k] is the head of slot k-1 and the tail of slot k.
    for (int k = 0; k < 3; ++k) expected[t[k]] += Rf * (w.w[(k + 2) % 3] * e[(k + 2) % 3] - w.w[k] * e[k]);
  }
  const gauss::CubicLocalStep cubic(topo, rest, edge_weight, slot_weight);
  double largest = 0, difference = 0;
  for (int v = 0; v < nV; ++v) {
    largest = std::max(largest, expected[v].cwiseAbs().maxCoeff());
    difference = std::max(difference, (cubic.global_rhs(v, rotation) - expected[v]).cwiseAbs().maxCoeff());
  }
  EXPECT_GT(largest, 0.0);
  return difference / largest;
}

TEST(CubicGlobalRhs, FoldedPerVertexEqualsThePerFaceSum) {
  EXPECT_LT(relative_rhs_difference(gauss_test::icosphere(2), 1), 1e-13);
  EXPECT_LT(relative_rhs_difference(gauss_test::grid_cube(4), 2), 1e-13);  // flat stars: rest Laplacian zero inside a side
}

TEST(CubicGlobalRhs, UnreferencedVertexGetsZero) {
  gauss::TriangleMesh m = gauss_test::icosphere(1);
  m.V.insert(m.V.end(), {5.0, 5.0, 5.0});  // a vertex no face uses
  const int nV = m.num_vertices();
  std::vector<int64_t> F(m.F.begin(), m.F.end());
  const gauss::MeshTopology topo = gauss::build_mesh_topology(nV, F.data(), m.num_faces());
  std::vector<Vector3d> rest(nV);
  for (int v = 0; v < nV; ++v) rest[v] = Vector3d(m.V[3 * v], m.V[3 * v + 1], m.V[3 * v + 2]);
  const gauss::CubicLocalStep cubic(topo, rest, std::vector<double>(topo.edges.size(), 1.0),
                                    std::vector<std::array<double, 3>>(topo.faces.size(), {0.5, 0.5, 0.5}));
  const std::vector<Matrix3d> rotation(nV, Matrix3d::Identity());
  EXPECT_EQ(cubic.global_rhs(nV - 1, rotation), Vector3d::Zero());
}

}  // namespace

}  // namespace test_cubic_global_rhs
