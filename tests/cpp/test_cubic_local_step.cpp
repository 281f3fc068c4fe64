// The cubic method's local step on its own (cubic_local_step.h): at lambda 0 (or zero strength) it is
// ARAP's rotation fit; with lambda > 0 the fitted rotations lower the cubic term; it turns with the
// mesh and the style frame; reset() restarts from scratch; and it is the same for any thread count.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "gauss/solver/cotangent_weights.h"
#include "gauss/solver/cubic_local_step.h"
#include "gauss/mesh/mesh_topology.h"
#include "gauss/util/parallel.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_cubic_local_step {

namespace {

using Eigen::Matrix3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

// A mesh as the solver holds it: topology, rest positions, whole cotangent weights per edge.
struct RestMesh {
  gauss::MeshTopology topo;
  std::vector<Vector3d> rest;
  std::vector<double> edge_weight;
  std::vector<std::array<double, 3>> slot_weight;
};

RestMesh rest_mesh(const gauss::TriangleMesh& m, const Matrix3d& turn = Matrix3d::Identity()) {
  RestMesh s;
  std::vector<int64_t> F(m.F.begin(), m.F.end());
  s.topo = gauss::build_mesh_topology(m.num_vertices(), F.data(), m.num_faces());
  for (int v = 0; v < m.num_vertices(); ++v)
    s.rest.push_back(turn * (0.5 * Vector3d(m.V[3 * v], m.V[3 * v + 1], m.V[3 * v + 2])));
  s.edge_weight.assign(s.topo.edges.size(), 0.0);
  s.slot_weight.resize(s.topo.faces.size());
  for (size_t f = 0; f < s.topo.faces.size(); ++f) {
    const auto& t = s.topo.faces[f];
    Vector3d e[3];
    for (int k = 0; k < 3; ++k) e[k] = s.rest[t[(k + 1) % 3]] - s.rest[t[k]];
    const gauss::TriangleWeights w = gauss::cotangent_weights(e);
    for (int k = 0; k < 3; ++k) s.edge_weight[s.topo.face_edge[f][k]] += w.w[k], s.slot_weight[f][k] = w.w[k];
  }
  return s;
}

struct Fit {
  std::vector<Matrix3d> rotation;
  long long admm_iterations = 0;
  double cubic_energy = 0;
};

// One local step at the current positions X with every vertex's style (strength, frame Q).
Fit fit(gauss::CubicLocalStep& cubic, const RestMesh& s, const std::vector<Vector3d>& X, double lambda) {
  const int nV = static_cast<int>(s.rest.size());
  std::vector<Matrix3d> cov(s.topo.faces.size());
  Fit out;
  out.rotation.assign(nV, Matrix3d::Identity());
  std::vector<Quaterniond> q(nV, Quaterniond::Identity());
  cubic.covariances(s.topo, X, cov);
  cubic.fit(s.topo, cov, lambda, false, out.rotation, q);
  out.admm_iterations = cubic.last_admm_iterations();
  out.cubic_energy = cubic.cubic_energy(lambda, out.rotation);
  return out;
}

gauss::CubicLocalStep styled(const RestMesh& s, double strength, const Matrix3d& frame) {
  gauss::CubicLocalStep cubic(s.topo, s.rest, s.edge_weight, s.slot_weight);
  cubic.set_vertex_styles(std::vector<double>(s.rest.size(), strength), std::vector<int>(s.rest.size(), 0), {frame});
  return cubic;
}

double distance(const Matrix3d& a, const Matrix3d& b) { return (a - b).cwiseAbs().maxCoeff(); }

const Matrix3d kTurn = Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix();

}  // namespace

TEST(CubicLocalStep, AtLambdaZeroItIsArapsRotationFit) {
  const RestMesh s = rest_mesh(gauss_test::icosphere(2));
  // Current positions: the rest pose turned as a whole, so ARAP's best rotation is that turn.
  std::vector<Vector3d> X;
  for (const Vector3d& p : s.rest) X.push_back(kTurn * p);
  for (double strength : {0.0, 1.0}) {
    for (double lambda : {0.0, 0.3}) {
      if (strength == 1.0 && lambda == 0.3) continue;  // the styled case, below
      SCOPED_TRACE("strength " + std::to_string(strength) + ", lambda " + std::to_string(lambda));
      gauss::CubicLocalStep cubic = styled(s, strength, Matrix3d::Identity());
      const Fit r = fit(cubic, s, X, lambda);
      EXPECT_EQ(r.admm_iterations, 0);
      for (const Matrix3d& R : r.rotation) ASSERT_LT(distance(R, kTurn), 1e-9);
    }
  }
}

TEST(CubicLocalStep, StyledFitIsARotationThatLowersTheCubicTerm) {
  const RestMesh s = rest_mesh(gauss_test::icosphere(2));
  // At the rest pose ARAP's term is 0 for R = I, so a minimizer of ARAP + cubic has a cubic term below
  // I's, and the more so the larger lambda (measured per unit lambda).
  gauss::CubicLocalStep cubic = styled(s, 1.0, Matrix3d::Identity());
  const double at_rest = cubic.cubic_energy(1.0, std::vector<Matrix3d>(s.rest.size(), Matrix3d::Identity()));
  double previous = at_rest;
  for (double lambda : {0.3, 3.0}) {
    gauss::CubicLocalStep fresh = styled(s, 1.0, Matrix3d::Identity());
    const Fit r = fit(fresh, s, s.rest, lambda);
    EXPECT_GT(r.admm_iterations, 0);
    for (const Matrix3d& R : r.rotation) {
      ASSERT_LT(distance(R.transpose() * R, Matrix3d::Identity()), 1e-9);
      ASSERT_NEAR(R.determinant(), 1.0, 1e-9);
    }
    const double per_lambda = fresh.cubic_energy(1.0, r.rotation);
    EXPECT_NEAR(r.cubic_energy, lambda * per_lambda, 1e-12 * r.cubic_energy);
    EXPECT_LT(per_lambda, previous) << "lambda " << lambda << " (at rest " << at_rest << ")";
    previous = per_lambda;
  }
  // Normals are unit, barycentric areas add up to the surface's area (a sphere of radius 0.5, inscribed).
  double area = 0;
  for (double a : cubic.vertex_areas()) area += a;
  EXPECT_NEAR(area, M_PI, 0.05 * M_PI);
  for (const Vector3d& n : cubic.vertex_normals()) ASSERT_NEAR(n.norm(), 1.0, 1e-12);
}

TEST(CubicLocalStep, TurnsWithTheMeshAndItsStyleFrame) {
  // Mesh, current positions and cube orientation all turned by G: the rotations become G R G^T.
  const RestMesh plain = rest_mesh(gauss_test::icosphere(2)), turned = rest_mesh(gauss_test::icosphere(2), kTurn);
  std::vector<Vector3d> X, GX;
  for (size_t v = 0; v < plain.rest.size(); ++v) {
    X.push_back(plain.rest[v] + 0.05 * Vector3d(std::sin(3.0 * v), std::cos(5.0 * v), std::sin(7.0 * v)));
    GX.push_back(kTurn * X.back());
  }
  const Matrix3d Q = Eigen::AngleAxisd(0.3, Vector3d::UnitZ()).toRotationMatrix();
  gauss::CubicLocalStep a = styled(plain, 1.0, Q), b = styled(turned, 1.0, kTurn * Q);
  const Fit ra = fit(a, plain, X, 0.3), rb = fit(b, turned, GX, 0.3);
  for (size_t v = 0; v < ra.rotation.size(); ++v)
    ASSERT_LT(distance(rb.rotation[v], kTurn * ra.rotation[v] * kTurn.transpose()), 1e-6) << "vertex " << v;
  EXPECT_NEAR(ra.cubic_energy, rb.cubic_energy, 1e-9);
}

TEST(CubicLocalStep, ResetRestartsAndThreadCountDoesNotMatter) {
  const RestMesh s = rest_mesh(gauss_test::icosphere(5));  // 10242 vertices: above the loops' parallel threshold
  std::vector<Vector3d> X;
  for (size_t v = 0; v < s.rest.size(); ++v) X.push_back(1.1 * s.rest[v]);
  gauss::CubicLocalStep one = styled(s, 1.0, Matrix3d::Identity()), two = styled(s, 1.0, Matrix3d::Identity());
  Fit r1, r2;
  {
    gauss::parallel::ScopedThreads threads(1);
    r1 = fit(one, s, X, 0.2);
  }
  {
    gauss::parallel::ScopedThreads threads(2);
    r2 = fit(two, s, X, 0.2);
  }
  EXPECT_EQ(r1.admm_iterations, r2.admm_iterations);
  for (size_t v = 0; v < s.rest.size(); ++v)
    ASSERT_EQ(std::memcmp(r1.rotation[v].data(), r2.rotation[v].data(), sizeof(Matrix3d)), 0) << "vertex " << v;
  // A second step starts warm (fewer iterations); after reset() it repeats the first exactly.
  const Fit warm = fit(one, s, X, 0.2);
  EXPECT_LT(warm.admm_iterations, r1.admm_iterations);
  one.reset();
  const Fit again = fit(one, s, X, 0.2);
  EXPECT_EQ(again.admm_iterations, r1.admm_iterations);
  for (size_t v = 0; v < s.rest.size(); ++v)
    ASSERT_EQ(std::memcmp(r1.rotation[v].data(), again.rotation[v].data(), sizeof(Matrix3d)), 0) << "vertex " << v;
}

}  // namespace test_cubic_local_step
