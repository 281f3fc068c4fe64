// The proxy of a large mesh (proxy_mesh.h) and the transfer of its deformation (proxy_transfer.h).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>

#include <Eigen/Geometry>

#include "gauss/proxy/proxy_mesh.h"
#include "gauss/proxy/proxy_transfer.h"
#include "gauss/util/parallel.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_proxy {

namespace {

using Eigen::Vector3d;
constexpr double kPi = 3.14159265358979323846;

// An open n x n grid on [-1, 1]^2 with bumps of height `bump` (the sculpted detail), z up.
gauss::TriangleMesh bumpy_grid(int n, double bump) {
  gauss::TriangleMesh m;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double x = -1 + 2.0 * i / n, y = -1 + 2.0 * j / n;
      m.V.insert(m.V.end(), {x, y, bump * std::sin(23 * x) * std::cos(19 * y)});
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j, b = a + n + 1;
      m.F.insert(m.F.end(), {a, b, b + 1, a, b + 1, a + 1});
    }
  return m;
}

gauss::ProxyMesh make(const gauss::TriangleMesh& m, int target) {
  return gauss::proxy_mesh(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), target);
}

// Undirected edge -> how many proxy faces use it.
std::map<std::pair<int, int>, int> edge_use(const gauss::ProxyMesh& p) {
  std::map<std::pair<int, int>, int> use;
  for (const auto& t : p.faces)
    for (int k = 0; k < 3; ++k) ++use[std::minmax(t[k], t[(k + 1) % 3])];
  return use;
}

std::vector<float> transfer(gauss::ProxyTransfer& d, const std::vector<Vector3d>& P) {
  std::vector<double> flat;
  for (const auto& p : P) flat.insert(flat.end(), {p.x(), p.y(), p.z()});
  std::vector<float> out(3 * d.num_fine_vertices());
  gauss::proxy_transfer(d, flat.data(), out.data());
  return out;
}

double max_error(const std::vector<float>& out, const gauss::TriangleMesh& m,
                 const std::function<Vector3d(const Vector3d&)>& map) {
  double worst = 0;
  for (int i = 0; i < m.num_vertices(); ++i) {
    const Vector3d want = map(Vector3d(m.V[3 * i], m.V[3 * i + 1], m.V[3 * i + 2]));
    worst = std::max(worst, (Vector3d(out[3 * i], out[3 * i + 1], out[3 * i + 2]) - want).norm());
  }
  return worst;
}

}  // namespace

TEST(Proxy, ClosedMeshStaysAClosedManifoldOfTheTargetSize) {
  const gauss::TriangleMesh m = gauss_test::icosphere(5);  // 10,242 vertices
  const gauss::ProxyMesh p = make(m, 1000);
  EXPECT_LE(p.vertices.size(), 1000u);
  EXPECT_GE(p.vertices.size(), 900u);
  const auto use = edge_use(p);
  for (const auto& [edge, count] : use) ASSERT_EQ(count, 2) << "edge " << edge.first << "-" << edge.second;
  // A sphere still: Euler characteristic 2, every face with area and facing out.
  EXPECT_EQ(static_cast<long>(p.vertices.size()) - static_cast<long>(use.size()) + static_cast<long>(p.faces.size()), 2);
  for (const auto& t : p.faces) {
    const Vector3d n = (p.vertices[t[1]] - p.vertices[t[0]]).cross(p.vertices[t[2]] - p.vertices[t[0]]);
    EXPECT_GT(n.dot(p.vertices[t[0]]), 0.0);
  }
  // Proxy vertices are fine vertices; every fine vertex lies close to the proxy (its edges are ~0.12
  // long on the unit sphere, a sagitta of ~0.002).
  for (size_t i = 0; i < p.vertices.size(); ++i) {
    const int f = p.fine_of_proxy[i];
    EXPECT_EQ(p.vertices[i], Vector3d(m.V[3 * f], m.V[3 * f + 1], m.V[3 * f + 2]));
  }
  double sum = 0, worst = 0;
  for (const auto& d : p.fine_offset) {
    sum += Vector3d(d[0], d[1], d[2]).norm();
    worst = std::max(worst, Vector3d(d[0], d[1], d[2]).norm());
  }
  EXPECT_LT(sum / m.num_vertices(), 0.003);
  EXPECT_LT(worst, 0.02);
}

TEST(Proxy, SameForAnyThreadCount) {
  // Large enough that chunks of space collapse in parallel (proxy_mesh.cpp, kChunks).
  const gauss::TriangleMesh m = gauss_test::icosphere(6);  // 40,962 vertices
  gauss::ProxyMesh one, two;
  {
    gauss::parallel::ScopedThreads threads(1);
    one = make(m, 4000);
  }
  {
    gauss::parallel::ScopedThreads threads(2);
    two = make(m, 4000);
  }
  EXPECT_EQ(one.faces, two.faces);
  EXPECT_EQ(one.fine_of_proxy, two.fine_of_proxy);
  EXPECT_EQ(one.fine_face, two.fine_face);
  EXPECT_LE(one.vertices.size(), 4000u);
  for (const auto& [edge, count] : edge_use(one)) ASSERT_EQ(count, 2);
}

TEST(Proxy, BoundaryKeepsItsOutline) {
  const gauss::TriangleMesh m = bumpy_grid(60, 0.0);  // flat: the boundary is all there is to keep
  const gauss::ProxyMesh p = make(m, 300);
  EXPECT_LE(p.vertices.size(), 300u);
  int boundary_edges = 0;
  for (const auto& [edge, count] : edge_use(p)) {
    ASSERT_LE(count, 2);
    if (count == 1) {
      ++boundary_edges;
      // Both ends on the square's outline.
      for (int v : {edge.first, edge.second})
        EXPECT_NEAR(std::max(std::abs(p.vertices[v].x()), std::abs(p.vertices[v].y())), 1.0, 1e-12);
    }
  }
  EXPECT_GE(boundary_edges, 4);
  // The four corners stay.
  std::set<std::pair<int, int>> corners;
  for (const auto& v : p.vertices)
    if (std::abs(std::abs(v.x()) - 1) < 1e-12 && std::abs(std::abs(v.y()) - 1) < 1e-12)
      corners.insert({static_cast<int>(v.x()), static_cast<int>(v.y())});
  EXPECT_EQ(corners.size(), 4u);
}

TEST(Proxy, SmallMeshComesBackWhole) {
  const gauss::TriangleMesh m = gauss_test::icosphere(1);  // 42 vertices
  const gauss::ProxyMesh p = make(m, 100);
  EXPECT_EQ(p.vertices.size(), 42u);
  EXPECT_EQ(p.faces.size(), 80u);
  for (const auto& d : p.fine_offset) EXPECT_LT(Vector3d(d[0], d[1], d[2]).norm(), 1e-12);
}

TEST(Proxy, TetrahedronIsTheSmallestPart) {
  const gauss::TriangleMesh m = gauss_test::icosphere(2);
  const gauss::ProxyMesh p = make(m, 4);
  EXPECT_GE(p.vertices.size(), 4u);
  for (const auto& [edge, count] : edge_use(p)) EXPECT_EQ(count, 2);
}

TEST(Proxy, BadInputIsRefused) {
  gauss::TriangleMesh m = gauss_test::icosphere(1);
  EXPECT_THROW(make(m, 3), std::invalid_argument);
  gauss::TriangleMesh bad_index = m;
  bad_index.F[4] = 42;
  EXPECT_THROW(make(bad_index, 10), std::invalid_argument);
  gauss::TriangleMesh nan = m;
  nan.V[7] = std::nan("");
  EXPECT_THROW(make(nan, 10), std::invalid_argument);
  gauss::TriangleMesh no_faces = m;
  no_faces.F = {0, 0, 1};
  EXPECT_THROW(make(no_faces, 10), std::invalid_argument);
}

TEST(Proxy, NonManifoldAndLooseVerticesAreKept) {
  // Three triangles on one edge (vertices 0-1), a loose vertex, and a sphere beside them.
  gauss::TriangleMesh m = gauss_test::icosphere(3);
  const int64_t o = m.num_vertices();
  m.V.insert(m.V.end(), {5, 0, 0, 5, 1, 0, 6, 0, 0, 5, 0, 1, 4, 0, 0, 9, 9, 9});
  m.F.insert(m.F.end(), {o, o + 1, o + 2, o, o + 1, o + 3, o, o + 1, o + 4});
  const gauss::ProxyMesh p = make(m, 100);
  EXPECT_EQ(p.fine_face[o + 5], -1);  // the loose vertex: in no face, it stays put
  EXPECT_EQ(p.fine_offset[o + 5][0], 9.f);
  bool fin = false;
  for (const auto& t : p.faces) fin |= p.fine_of_proxy[t[0]] >= o || p.fine_of_proxy[t[1]] >= o;
  EXPECT_TRUE(fin);  // the fin's faces are still there
  for (int i = 0; i < 5; ++i) EXPECT_GE(p.fine_face[o + i], 0);
}

TEST(ProxyTransfer, RestShapeAndRigidMotionsComeBackExactly) {
  const gauss::TriangleMesh m = bumpy_grid(80, 0.02);
  const gauss::ProxyMesh p = make(m, 800);
  gauss::ProxyTransfer d = gauss::proxy_transfer_precomputation(p);
  EXPECT_LT(max_error(transfer(d, p.vertices), m, [](const Vector3d& x) { return x; }), 1e-6);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(1.1, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Vector3d t(0.3, -2, 5);
  std::vector<Vector3d> moved;
  for (const auto& v : p.vertices) moved.push_back(R * v + t);
  EXPECT_LT(max_error(transfer(d, moved), m, [&](const Vector3d& x) { return Vector3d(R * x + t); }), 1e-5);
}

TEST(ProxyTransfer, DetailTurnsWithTheSurfaceItRidesOn) {
  // The bumpy grid bent by 90 degrees about the line x = 0.2 (z up): the part beyond x = 0.4 moves
  // rigidly, so its bumps must come out exactly turned; translated without turning (smeared) they
  // would be off by up to their height.
  const double bump = 0.02;
  const gauss::TriangleMesh m = bumpy_grid(100, bump);
  const gauss::ProxyMesh p = make(m, 1500);
  gauss::ProxyTransfer d = gauss::proxy_transfer_precomputation(p);
  const auto bend = [](const Vector3d& x) {
    // Arc between x = 0.2 and 0.4 of radius 0.2 / (pi/2), rigid beyond.
    const double start = 0.2, length = 0.2, radius = length / (kPi / 2);
    if (x.x() <= start) return x;
    const double s = std::min(x.x() - start, length), angle = s / length * (kPi / 2);
    const double r = radius - x.z();
    Vector3d y(start + r * std::sin(angle), x.y(), radius - r * std::cos(angle));
    if (x.x() > start + length) {
      const double beyond = x.x() - start - length;
      y += beyond * Vector3d(std::cos(kPi / 2), 0, std::sin(kPi / 2));
    }
    return y;
  };
  std::vector<Vector3d> bent;
  for (const auto& v : p.vertices) bent.push_back(bend(v));
  const std::vector<float> out = transfer(d, bent);
  double worst_far = 0, worst_all = 0;
  for (int i = 0; i < m.num_vertices(); ++i) {
    const Vector3d x(m.V[3 * i], m.V[3 * i + 1], m.V[3 * i + 2]);
    const double e = (Vector3d(out[3 * i], out[3 * i + 1], out[3 * i + 2]) - bend(x)).norm();
    worst_all = std::max(worst_all, e);
    if (x.x() > 0.55) worst_far = std::max(worst_far, e);
  }
  EXPECT_LT(worst_far, 1e-5);
  EXPECT_LT(worst_all, bump);  // in the arc the proxy's flat faces only approximate the bend
}

TEST(ProxyTransfer, InconsistentMapIsRefused) {
  gauss::ProxyMesh p = make(gauss_test::icosphere(2), 50);
  p.fine_face[3] = static_cast<int>(p.faces.size());
  EXPECT_THROW(gauss::proxy_transfer_precomputation(p), std::invalid_argument);
}

}  // namespace test_proxy
