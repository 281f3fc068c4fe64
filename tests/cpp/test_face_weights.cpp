// Painted strength (GaussSolver::set_face_weights): per-face weights that scale a style's mu, blends of
// overlapping styles, the cubic method's per-vertex weights, and bad weights refused.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "gauss/mesh/alignment_share.h"
#include "gauss/solver/gauss_solver.h"
#include "gauss/style/presets.h"
#include "test_expect.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_face_weights {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using gauss::GaussSolver;
using gauss::Method;
using gauss::PreferenceFunction;
using Mesh = gauss::TriangleMesh;

// Plain steps: the acceleration's global restart sums over all vertices, which would couple the
// separate spheres the gradient tests compare.
std::unique_ptr<GaussSolver> solver(const Mesh& m, Method method) {
  auto s = std::make_unique<GaussSolver>(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
  s->set_method(method);
  s->set_acceleration(false);
  return s;
}

std::vector<double> run(GaussSolver& s, int steps) {
  for (int i = 0; i < steps; ++i) s.step();
  std::vector<double> out(3 * static_cast<size_t>(s.num_vertices()));
  s.copy_vertices(out.data());
  return out;
}

PreferenceFunction cube(double mu = 1.0, const Matrix3d& rotation = Matrix3d::Identity()) {
  gauss::StyleParams p = gauss::preset_style("cube");
  p.mu = mu;
  p.rotation = rotation;
  return PreferenceFunction(p);
}

const Matrix3d kTurn = Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitZ()).toRotationMatrix();

std::vector<Vector3d> cube_normals(const Matrix3d& Q = Matrix3d::Identity()) {
  std::vector<Vector3d> a;
  for (int k = 0; k < 3; ++k) a.push_back(Q.col(k)), a.push_back(-Q.col(k));
  return a;
}

// The share of faces [first, first + count) of m within 10 degrees of a cube's normals.
double share(const Mesh& m, const std::vector<double>& V, int first, int count,
             const Matrix3d& Q = Matrix3d::Identity()) {
  return gauss::alignment_share(V.data(), m.F.data() + 3 * static_cast<size_t>(first), count, cube_normals(Q), 10.0);
}

// `copies` unit spheres side by side along x (each icosphere(3)).
Mesh row_of_spheres(int copies) {
  const Mesh one = gauss_test::icosphere(3);
  Mesh m = one;
  for (int i = 1; i < copies; ++i) m = gauss_test::beside(m, one);
  return m;
}

TEST(FaceWeights, WeightOneIsBitIdenticalToFaceStyles) {
  // Half the faces in style 0, the others in style 1, through set_face_styles and as one-hot
  // weights of 1: the same steps, bit for bit, with both methods.
  const Mesh sphere = gauss_test::icosphere(3);
  const int nF = sphere.num_faces();
  std::vector<int64_t> styles(nF);
  std::vector<double> weights(2 * static_cast<size_t>(nF), 0.0);
  for (int f = 0; f < nF; ++f) {
    styles[f] = f % 3 == 0 ? -1 : f % 3 == 1 ? 0 : 1;  // unstyled faces too
    if (styles[f] >= 0) weights[2 * f + styles[f]] = 1.0;
  }
  for (Method method : {Method::gauss, Method::cubic}) {
    auto a = solver(sphere, method), b = solver(sphere, method);
    for (auto* s : {a.get(), b.get()}) s->set_styles({cube(), cube(2.0, kTurn)});
    a->set_face_styles(styles.data(), nF);
    b->set_face_weights(weights.data(), nF, 2);
    const std::vector<double> expected = run(*a, 20);
    EXPECT_EQ(expected, run(*b, 20)) << "method " << static_cast<int>(method);
    EXPECT_EQ(a->g_energy(), b->g_energy());
    EXPECT_GT(share(sphere, expected, 0, nF), share(sphere, sphere.V, 0, nF) + 0.05);  // it did stylize
  }
}

TEST(FaceWeights, AWeightScalesMu) {
  // Weight 0.5 with mu 1 is mu 0.5 with weight 1, bit for bit; weight 0 is unstyled.
  const Mesh sphere = gauss_test::icosphere(3);
  const int nF = sphere.num_faces();
  for (Method method : {Method::gauss, Method::cubic}) {
    auto half = solver(sphere, method), weighted = solver(sphere, method);
    half->set_styles({cube(0.5)});
    weighted->set_styles({cube(1.0)});
    const std::vector<double> w(nF, 0.5);
    weighted->set_face_weights(w.data(), nF, 1);
    EXPECT_EQ(run(*half, 15), run(*weighted, 15)) << "method " << static_cast<int>(method);

    auto unstyled = solver(sphere, method), zero = solver(sphere, method);
    const std::vector<int64_t> none(nF, -1);
    unstyled->set_face_styles(none.data(), nF);
    const std::vector<double> z(nF, 0.0);
    zero->set_face_weights(z.data(), nF, 1);
    EXPECT_EQ(run(*unstyled, 5), run(*zero, 5));
  }
}

TEST(FaceWeights, AGradientOfWeightsGivesARisingShare) {
  // Five spheres in a row with weights 0, 0.25, 0.5, 0.75, 1 along it: the share of cube-aligned
  // area rises along the row, with both methods (the cubic method from the vertices' own weights).
  const int copies = 5;
  const Mesh m = row_of_spheres(copies);
  const int per_sphere = m.num_faces() / copies, vertices_per_sphere = m.num_vertices() / copies;
  std::vector<double> face_w(m.num_faces()), vertex_w(m.num_vertices());
  for (int f = 0; f < m.num_faces(); ++f) face_w[f] = 0.25 * (f / per_sphere);
  for (int v = 0; v < m.num_vertices(); ++v) vertex_w[v] = 0.25 * (v / vertices_per_sphere);
  for (Method method : {Method::gauss, Method::cubic}) {
    auto s = solver(m, method);
    s->set_cubic_lambda(0.4);
    s->set_face_weights(face_w.data(), m.num_faces(), 1, method == Method::cubic ? vertex_w.data() : nullptr,
                        m.num_vertices());
    const std::vector<double> V = run(*s, 30);
    double previous = -1;
    for (int i = 0; i < copies; ++i) {
      const double now = share(m, V, i * per_sphere, per_sphere);
      EXPECT_GT(now, previous + 0.01) << "sphere " << i << ", method " << static_cast<int>(method);
      previous = now;
    }
  }
}

TEST(FaceWeights, OverlappingStylesBlend) {
  const Mesh sphere = gauss_test::icosphere(3);
  const int nF = sphere.num_faces();
  auto weighted = [&](double a, double b, const PreferenceFunction& second) {
    auto s = solver(sphere, Method::gauss);
    s->set_styles({cube(), second});
    std::vector<double> w;
    for (int f = 0; f < nF; ++f) w.push_back(a), w.push_back(b);
    s->set_face_weights(w.data(), nF, 2);
    return run(*s, 30);
  };
  auto single = [&](const PreferenceFunction& style) {
    auto s = solver(sphere, Method::gauss);
    s->set_styles({style});
    return run(*s, 30);
  };
  // The preference is the weight-scaled sum: a style overlapping itself with weights 1 and 1 is
  // that style with twice its mu, and halves of it make it whole, bit for bit.
  EXPECT_EQ(weighted(1.0, 1.0, cube()), single(cube(2.0)));
  EXPECT_EQ(weighted(0.5, 0.5, cube()), single(cube()));
  // Two different styles: the blend lies between them.
  const std::vector<double> first = single(cube()), second = single(cube(1.0, kTurn));
  const std::vector<double> blend = weighted(1.0, 1.0, cube(1.0, kTurn));
  const double blend_first = share(sphere, blend, 0, nF), blend_second = share(sphere, blend, 0, nF, kTurn);
  EXPECT_LT(blend_first, share(sphere, first, 0, nF) - 0.02);
  EXPECT_GT(blend_first, share(sphere, second, 0, nF) + 0.02);
  EXPECT_LT(blend_second, share(sphere, second, 0, nF, kTurn) - 0.02);
  EXPECT_GT(blend_second, share(sphere, first, 0, nF, kTurn) + 0.02);
}

TEST(FaceWeights, CubicUsesTheVertexsOwnWeight) {
  // Faces weighted 1 but every vertex weighted 0: the cubic method gives no vertex any strength, so
  // the sphere stays as unstyled ARAP leaves it (the rest shape); without vertex weights it is a cube.
  const Mesh sphere = gauss_test::icosphere(3);
  const int nF = sphere.num_faces(), nV = sphere.num_vertices();
  const std::vector<double> faces(nF, 1.0), vertices(nV, 0.0);
  auto own = solver(sphere, Method::cubic), from_faces = solver(sphere, Method::cubic);
  own->set_face_weights(faces.data(), nF, 1, vertices.data(), nV);
  from_faces->set_face_weights(faces.data(), nF, 1);
  auto unstyled = solver(sphere, Method::cubic);
  const std::vector<int64_t> none(nF, -1);
  unstyled->set_face_styles(none.data(), nF);
  EXPECT_EQ(run(*own, 10), run(*unstyled, 10));
  EXPECT_GT(share(sphere, run(*from_faces, 10), 0, nF), share(sphere, sphere.V, 0, nF) + 0.05);
}

TEST(FaceWeights, BadWeightsAreRefusedAndChangeNothing) {
  const Mesh sphere = gauss_test::icosphere(2);
  const int nF = sphere.num_faces(), nV = sphere.num_vertices();
  auto s = solver(sphere, Method::gauss);
  auto reference = solver(sphere, Method::gauss);
  for (auto* x : {s.get(), reference.get()}) x->set_styles({cube(), cube(1.0, kTurn)});
  std::vector<double> w(2 * static_cast<size_t>(nF), 0.25);
  s->set_face_weights(w.data(), nF, 2);
  reference->set_face_weights(w.data(), nF, 2);
  using gauss_test::expect_refused;
  for (double bad : {std::nan(""), -0.1, 1.5, std::numeric_limits<double>::infinity()}) {
    std::vector<double> b = w;
    b[2 * 7 + 1] = bad;
    expect_refused([&] { s->set_face_weights(b.data(), nF, 2); }, "the weight of face 7 for style 1");
    std::vector<double> v(2 * static_cast<size_t>(nV), 1.0);
    v[2 * 3] = bad;
    expect_refused([&] { s->set_face_weights(w.data(), nF, 2, v.data(), nV); }, "the weight of vertex 3 for style 0");
  }
  expect_refused([&] { s->set_face_weights(w.data(), nF - 1, 2); }, "one row per face");
  std::vector<double> three(3 * static_cast<size_t>(nF), 0.0);
  expect_refused([&] { s->set_face_weights(three.data(), nF, 3); }, "at most one column per style (2)");
  std::vector<double> v(2 * static_cast<size_t>(nV), 1.0);
  expect_refused([&] { s->set_face_weights(w.data(), nF, 2, v.data(), nV - 1); }, "one row per vertex");
  // The refused calls changed nothing.
  EXPECT_EQ(run(*s, 5), run(*reference, 5));
  // A shorter style list than the weights use is refused too; fewer columns than styles are fine.
  expect_refused([&] { s->set_styles({cube()}); }, "faces use style 1");
  std::vector<double> one(nF, 1.0);
  s->set_face_weights(one.data(), nF, 1);
  s->set_styles({cube()});
}

}  // namespace

}  // namespace test_face_weights
