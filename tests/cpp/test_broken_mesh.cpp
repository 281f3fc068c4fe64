// Broken meshes (non-manifold, pinched, degenerate, duplicated, non-orientable, open, in pieces) either
// stylize to finite coordinates or are refused with std::invalid_argument; nothing crashes, nothing
// turns NaN, nothing is lost; a refused call leaves the solver as it was. The meshes and checks are in
// robustness_kit.h.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "gauss/solver/gauss_solver.h"
#include "gauss/mesh/mesh_io.h"
#include "gauss/style/preference_function.h"
#include "gauss/style/presets.h"
#include "robustness_kit.h"
#include "test_expect.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_broken_mesh {

namespace {

using namespace robustness_kit;

using gauss_test::expect_refused;

// ---------------------------------------------------------------------------------------------------
// Broken meshes.

TEST(BrokenMesh, NonManifoldEdgeFan) {
  Mesh fan;  // three triangles on one edge
  for (const Vector3d& p : {Vector3d(0, 0, 0), Vector3d(0, 0, 1), Vector3d(1, 0, 0.5), Vector3d(-0.5, 0.8, 0.5),
                            Vector3d(-0.5, -0.8, 0.4)})
    add_vertex(fan, p);
  add_face(fan, 0, 1, 2);
  add_face(fan, 0, 1, 3);
  add_face(fan, 1, 0, 4);
  expect_sane(fan, stylize(fan));

  Mesh fin = cube_sphere(5);  // a closed surface with a fin: three faces on one of its edges
  const int64_t a = fin.F[0], b = fin.F[1];
  const int tip = add_vertex(fin, 0.5 * (point(fin.V, a) + point(fin.V, b)) * 2.0);
  add_face(fin, a, b, tip);
  const std::vector<double> out = stylize(fin);
  expect_sane(fin, out);
  EXPECT_GT(cube_share(fin, out), cube_share(fin, fin.V) + 0.3);
}

TEST(BrokenMesh, PinchedVertex) {
  // Two closed spheres touching at one shared vertex (a non-manifold "bow tie" vertex).
  Mesh m = cube_sphere(5);
  const int n = m.num_vertices();
  int right = 0, left = 0;  // the first sphere's largest-x vertex meets the second's smallest-x one
  for (int v = 0; v < n; ++v) {
    if (m.V[3 * v] > m.V[3 * right]) right = v;
    if (m.V[3 * v] < m.V[3 * left]) left = v;
  }
  Mesh second = m;
  const Vector3d shift = point(m.V, right) - point(m.V, left);
  for (int v = 0; v < n; ++v)
    for (int k = 0; k < 3; ++k) second.V[3 * v + k] += shift[k];
  append(m, second);
  for (int64_t& i : m.F)
    if (i == n + left) i = right;  // weld
  const std::vector<double> out = stylize(m);
  expect_sane(m, out);
  EXPECT_EQ(point(out, n + left), point(m.V, n + left)) << "the welded-away vertex is unreferenced now";
  EXPECT_GT(cube_share(m, out), cube_share(m, m.V) + 0.3);
}

TEST(BrokenMesh, ZeroAreaAndRepeatedIndexTriangles) {
  const Mesh clean = cube_sphere(5);
  Mesh m = clean;
  const int64_t a = m.F[0], b = m.F[1];
  const int mid = add_vertex(m, 0.5 * (point(m.V, a) + point(m.V, b)));
  add_face(m, a, b, mid);  // collinear: zero area
  const int p = add_vertex(m, point(m.V, a)), q = add_vertex(m, point(m.V, a));
  add_face(m, a, p, q);  // three coincident corners: zero area, zero-length edges
  const std::vector<double> out = stylize(m);
  expect_sane(m, out);
  EXPECT_GT(cube_share(m, out), cube_share(m, m.V) + 0.3);

  // Repeated indices: such faces have no normal and are ignored, so they change nothing at all.
  Mesh repeated = clean;
  add_face(repeated, a, a, b);
  add_face(repeated, b, a, b);
  add_face(repeated, a, a, a);
  const std::vector<double> clean_out = stylize(clean), repeated_out = stylize(repeated);
  expect_sane(repeated, repeated_out);
  EXPECT_LE(max_rel_diff(clean_out, repeated_out, extent(clean)), 1e-12);
}

TEST(BrokenMesh, DuplicateFaces) {
  const Mesh clean = cube_sphere(5);
  Mesh same = clean, flipped = clean;
  for (int f = 0; f < clean.num_faces(); ++f) {
    const int64_t a = clean.F[3 * f], b = clean.F[3 * f + 1], c = clean.F[3 * f + 2];
    add_face(same, a, b, c);
    add_face(flipped, a, c, b);
  }
  for (const Mesh* m : {&same, &flipped}) {
    const std::vector<double> out = stylize(*m);
    expect_sane(*m, out);
    EXPECT_GT(cube_share(*m, out), cube_share(*m, m->V) + 0.3);
  }
}

TEST(BrokenMesh, UnreferencedVerticesStayPutAndChangeNothing) {
  const Mesh clean = cube_sphere(5);
  // The same surface with 40 loose vertices far away, interleaved with the used ones.
  Mesh loose;
  std::vector<int64_t> new_index;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> far(-50, 50);
  for (int v = 0; v < clean.num_vertices(); ++v) {
    if (v % 5 == 0 && v / 5 < 40) add_vertex(loose, Vector3d(far(rng), far(rng), far(rng)));
    new_index.push_back(add_vertex(loose, point(clean.V, v)));
  }
  for (int64_t i : clean.F) loose.F.push_back(new_index[i]);
  const std::vector<double> a = stylize(clean), b = stylize(loose);
  expect_sane(loose, b);  // includes: loose vertices come back bit for bit
  double diff = 0;
  for (int v = 0; v < clean.num_vertices(); ++v)
    diff = std::max(diff, (point(a, v) - point(b, new_index[v])).cwiseAbs().maxCoeff());
  EXPECT_LE(diff, 1e-9 * extent(clean)) << "loose vertices changed the result";
}

TEST(BrokenMesh, MoebiusStrip) {
  const Mesh m = moebius(40, 4);
  const std::vector<double> out = stylize(m);
  expect_sane(m, out);
  EXPECT_GT(cube_share(m, out), cube_share(m, m.V) + 0.1);
}

TEST(BrokenMesh, OpenBoundaries) {
  const Mesh patch = open_patch(12);
  std::vector<double> out = stylize(patch);
  expect_sane(patch, out);
  EXPECT_GT(cube_share(patch, out), cube_share(patch, patch.V) + 0.3);

  Mesh holed = cube_sphere(6);  // a sphere with a hole of 8 faces
  holed.F.erase(holed.F.begin() + 3 * 10, holed.F.begin() + 3 * 18);
  out = stylize(holed);
  expect_sane(holed, out);
  EXPECT_GT(cube_share(holed, out), cube_share(holed, holed.V) + 0.3);
}

TEST(BrokenMesh, ManySmallComponents) {
  // 200 copies of one tetrahedron and 200 of one triangle, scattered. Free components keep their
  // centroids, and identical copies come out identical: the result depends on neither the position
  // of a component nor on its neighbours' (they share no vertex).
  Mesh m;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(-20, 20);
  for (int i = 0; i < 200; ++i) append(m, tetrahedron(Vector3d(pos(rng), pos(rng), pos(rng))));
  const int tris_start = m.num_vertices();
  for (int i = 0; i < 200; ++i) {
    Mesh t;
    const Vector3d o(pos(rng), pos(rng), pos(rng));
    add_vertex(t, o);
    add_vertex(t, o + Vector3d(1, 0.2, 0.3));
    add_vertex(t, o + Vector3d(0.1, 0.8, 0.5));
    add_face(t, 0, 1, 2);
    append(m, t);
  }
  const std::vector<double> out = stylize(m, Options{20});
  expect_sane(m, out);
  const double size = extent(m);
  double centroid_drift = 0, copy_diff = 0;
  auto check_copies = [&](int first, int count, int verts) {
    for (int c = 0; c < count; ++c) {
      const int base = first + c * verts;
      Vector3d before = Vector3d::Zero(), after = Vector3d::Zero();
      for (int k = 0; k < verts; ++k) {
        before += point(m.V, base + k) / verts;
        after += point(out, base + k) / verts;
      }
      centroid_drift = std::max(centroid_drift, (after - before).cwiseAbs().maxCoeff());
      for (int k = 0; k < verts; ++k) {
        const Vector3d shape0 = point(out, first + k) - point(out, first);
        const Vector3d shape = point(out, base + k) - point(out, base);
        copy_diff = std::max(copy_diff, (shape - shape0).cwiseAbs().maxCoeff());
      }
    }
  };
  check_copies(0, 200, 4);
  check_copies(tris_start, 200, 3);
  EXPECT_LE(centroid_drift, 1e-9 * size);
  EXPECT_LE(copy_diff, 1e-9 * size);
  // And they did get stylized: the tetrahedron is not what it was.
  EXPECT_GT((point(out, 3) - point(out, 0) - (point(m.V, 3) - point(m.V, 0))).norm(), 1e-3);
}

TEST(BrokenMesh, SingleTriangle) {
  Mesh t;
  add_vertex(t, Vector3d(0, 0, 0));
  add_vertex(t, Vector3d(1, 0.1, 0.3));
  add_vertex(t, Vector3d(0.2, 0.9, 0.5));
  add_face(t, 0, 1, 2);
  std::vector<double> out = stylize(t);
  expect_sane(t, out);
  EXPECT_GT(cube_share(t, out), 0.99) << "one free triangle turns to face a cube normal";

  Options all_pinned;  // nothing left to solve for
  all_pinned.pins = {0, 1, 2};
  out = stylize(t, all_pinned);
  EXPECT_EQ(out, t.V);
}

TEST(BrokenMesh, AllFacesZeroArea) {
  Mesh line;  // every vertex on one line: faces exist but none has an area or a normal
  for (int i = 0; i < 6; ++i) add_vertex(line, Vector3d(i, 2.0 * i, -i));
  for (int i = 0; i + 2 < 6; ++i) add_face(line, i, i + 1, i + 2);
  const std::vector<double> out = stylize(line);
  expect_sane(line, out);
  EXPECT_LE(max_rel_diff(out, line.V, extent(line)), 1e-9) << "nothing to stylize: nothing moves";
}

TEST(BrokenMesh, MeshesWithoutFacesOrVerticesAreRefused) {
  const std::vector<double> V = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::vector<int64_t> none;
  expect_refused([&] { GaussSolver(V.data(), 3, none.data(), 0); }, "no faces");
  const std::vector<int64_t> F = {0, 1, 2};
  expect_refused([&] { GaussSolver(nullptr, 0, F.data(), 1); }, "no vertices");
  const std::vector<int64_t> repeated = {0, 0, 1, 2, 2, 2};
  expect_refused([&] { GaussSolver(V.data(), 3, repeated.data(), 2); }, "no usable triangle");
}

TEST(BrokenMesh, BadArraysAreRefused) {
  const Mesh m = cube_sphere(3);
  const int nv = m.num_vertices(), nf = m.num_faces();
  for (double bad : {NAN, INFINITY, -INFINITY}) {
    std::vector<double> V = m.V;
    V[3 * 5 + 1] = bad;
    expect_refused([&] { GaussSolver(V.data(), nv, m.F.data(), nf); }, "vertex 5");
  }
  for (int64_t bad : {int64_t(-1), int64_t(nv), int64_t(1) << 40, INT64_MIN}) {
    std::vector<int64_t> F = m.F;
    F[3 * 4 + 2] = bad;
    expect_refused([&] { GaussSolver(m.V.data(), nv, F.data(), nf); }, "face 4");
  }
  const std::vector<double> point_cloud(3 * nv, 2.5);  // every vertex at one point
  expect_refused([&] { GaussSolver(point_cloud.data(), nv, m.F.data(), nf); }, "extent");
  std::vector<double> huge = m.V;  // an extent beyond the floating-point range
  for (size_t i = 0; i < huge.size(); ++i) huge[i] = (m.V[i] > 0 ? 1.7e308 : -1.7e308);
  expect_refused([&] { GaussSolver(huge.data(), nv, m.F.data(), nf); }, "extent");
  std::vector<double> near_limit = m.V;  // found by the fuzzer: finite extent, but results overflowed
  near_limit[0] = -1.7976931348623157e308;
  expect_refused([&] { GaussSolver(near_limit.data(), nv, m.F.data(), nf); }, "extent");
  std::vector<double> loose_at_limit = m.V;  // a vertex no face uses may be anywhere
  loose_at_limit.insert(loose_at_limit.end(), {-1.7976931348623157e308, 1e308, 0});
  std::vector<double> out(loose_at_limit.size());
  GaussSolver ok(loose_at_limit.data(), nv + 1, m.F.data(), nf);
  ok.step();
  ok.copy_vertices(out.data());
  EXPECT_EQ(point(out, nv), point(loose_at_limit, nv));
  expect_refused([&] { GaussSolver(m.V.data(), nv, m.F.data(), nf, {}, nullptr, -1.0); }, "lambda");
  expect_refused([&] { GaussSolver(m.V.data(), nv, m.F.data(), nf, {}, nullptr, NAN); }, "lambda");
  expect_refused([&] { GaussSolver(m.V.data(), nv, m.F.data(), nf, {}, nullptr, 1.7e308); }, "lambda");  // NaN once
  expect_refused([&] { GaussSolver(m.V.data(), nv, m.F.data(), nf, {nv}); }, "out of range");
  expect_refused([&] { GaussSolver(m.V.data(), nv, m.F.data(), nf, {-1}); }, "out of range");
  expect_refused([&] { GaussSolver(m.V.data(), nv, m.F.data(), nf, {3, 3}); }, "more than once");
  const std::vector<double> nan_target = {0, NAN, 0};
  expect_refused([&] { GaussSolver(m.V.data(), nv, m.F.data(), nf, {3}, nan_target.data()); }, "NaN");
  const std::vector<double> far_target = {0, -9.8e297, 0};  // found by the fuzzer: E_ARAP turned NaN
  expect_refused([&] { GaussSolver(m.V.data(), nv, m.F.data(), nf, {3}, far_target.data()); }, "too far");
}

TEST(BrokenMesh, FlatMeshFarFromTheOrigin) {
  // Found by the fuzzer: every x equal to -8.27e279. The centroid rounded a few ulps off that plane put
  // the normalized mesh ~1e263 from the origin, and after one step E_ARAP was NaN. (Any magnitude
  // does it, given a mantissa whose multiples round.) Now the result is the one at the origin, moved.
  const Mesh near = open_patch(6);
  Mesh flat = near;
  for (int v = 0; v < flat.num_vertices(); ++v) {  // the patch turned into the y-z plane
    flat.V[3 * v] = 0;
    flat.V[3 * v + 1] = near.V[3 * v];
    flat.V[3 * v + 2] = near.V[3 * v + 1];
  }
  const std::vector<double> expected = stylize(flat, Options{10});
  for (double x : {-8.2683746789697553e+179, 1e15, -3.3e100}) {
    Mesh far = flat;
    for (int v = 0; v < far.num_vertices(); ++v) far.V[3 * v] = x;
    GaussSolver s(far.V.data(), far.num_vertices(), far.F.data(), far.num_faces());
    for (int i = 0; i < 10; ++i) s.step();
    std::vector<double> out(far.V.size());
    s.copy_vertices(out.data());
    EXPECT_TRUE(std::isfinite(s.arap_energy())) << x;
    double diff = 0;
    for (int v = 0; v < far.num_vertices(); ++v) {
      EXPECT_EQ(out[3 * v], x) << "stays in its plane";
      diff = std::max({diff, std::abs(out[3 * v + 1] - expected[3 * v + 1]), std::abs(out[3 * v + 2] - expected[3 * v + 2])});
    }
    EXPECT_LE(diff, 1e-9 * extent(flat)) << x;
  }
}

TEST(BrokenMesh, RefusedCallsLeaveTheSolverAsItWas) {
  const Mesh m = cube_sphere(4);
  const int nv = m.num_vertices(), nf = m.num_faces();
  GaussSolver reference(m.V.data(), nv, m.F.data(), nf), s(m.V.data(), nv, m.F.data(), nf);
  const std::vector<double> nan_target = {0, NAN, 0};
  expect_refused([&] { s.set_pins({nv}); }, "out of range");
  expect_refused([&] { s.set_pins({1}, nan_target.data()); }, "NaN");
  const std::vector<double> far_target = {1e15, 0, 0};
  expect_refused([&] { s.set_pins({1}, far_target.data()); }, "too far");
  expect_refused([&] { s.set_lambda(-2); }, "lambda");
  expect_refused([&] { s.set_lambda(1e9); }, "lambda");
  expect_refused([&] { s.set_admm_iterations(0); }, "ADMM");
  expect_refused([&] { s.set_styles({}); }, "styles");
  expect_refused([&] { s.set_style(1, PreferenceFunction(gauss::preset_style("cone"))); }, "out of range");
  const std::vector<int64_t> too_short(nf - 1, 0), too_big(nf, 1), too_small(nf, -2);
  expect_refused([&] { s.set_face_styles(too_short.data(), nf - 1); }, "one entry per face");
  expect_refused([&] { s.set_face_styles(too_big.data(), nf); }, "style 1");
  expect_refused([&] { s.set_face_styles(too_small.data(), nf); }, "style -2");
  for (int i = 0; i < 10; ++i) {
    reference.step();
    s.step();
  }
  std::vector<double> a(m.V.size()), b(m.V.size());
  reference.copy_vertices(a.data());
  s.copy_vertices(b.data());
  EXPECT_EQ(a, b);
}

TEST(BrokenMesh, BadStylesAreRefused) {
  auto with = [](auto edit) {
    gauss::StyleParams p = gauss::preset_style("cube");
    edit(p);
    return p;
  };
  using P = gauss::StyleParams;
  expect_refused([&] { PreferenceFunction(with([](P& p) { p.sigma = 0; })); }, "sigma");
  expect_refused([&] { PreferenceFunction(with([](P& p) { p.sigma = -1; })); }, "sigma");
  expect_refused([&] { PreferenceFunction(with([](P& p) { p.sigma = NAN; })); }, "sigma");
  expect_refused([&] { PreferenceFunction(with([](P& p) { p.mu = -0.5; })); }, "mu");
  expect_refused([&] { PreferenceFunction(with([](P& p) { p.mu = 2e6; })); }, "mu");  // NaN once, at 1e154
  expect_refused([&] { PreferenceFunction(with([](P& p) { p.normals.clear(); })); }, "at least one");
  expect_refused([&] { PreferenceFunction(with([](P& p) { p.normals[2] = Vector3d::Zero(); })); }, "non-zero");
  expect_refused([&] { PreferenceFunction(with([](P& p) { p.normals[2].x() = NAN; })); }, "finite");
  expect_refused([&] { PreferenceFunction(with([](P& p) { p.ring_offsets = {1.0}; })); }, "ring offsets");
  expect_refused([&] { PreferenceFunction(with([](P& p) { p.rotation(0, 0) = -1; })); }, "rotation");
  expect_refused([&] { PreferenceFunction(with([](P& p) { p.rotation *= 2; })); }, "rotation");
  expect_refused([] { gauss::preset_style("sphere"); }, "valid presets");
}

TEST(BrokenMesh, ExtremeButValidParametersStayFinite) {
  const Mesh m = cube_sphere(4);
  for (double sigma : {1e-3, 1.0, 64.0, 1e3})
    for (double mu : {0.0, 1.0, 100.0})
      for (double lambda : {0.0, 4.0, 1e4}) {
        gauss::StyleParams p = gauss::preset_style(sigma > 10 ? "double_cone" : "icosahedron");
        p.sigma = sigma;
        p.mu = mu;
        Options o;
        o.steps = 8;
        o.lambda = lambda;
        o.styles = {PreferenceFunction(p)};
        SCOPED_TRACE("sigma " + std::to_string(sigma) + " mu " + std::to_string(mu) + " lambda " + std::to_string(lambda));
        expect_sane(m, stylize(m, o), 4.0);
      }
}

TEST(BrokenMesh, PinsAndFaceStylesOnBrokenMeshes) {
  Mesh m = moebius(30, 3);
  append(m, tetrahedron(Vector3d(3, 0, 0)));
  Options o;
  o.pins = {0, 1, 2, static_cast<int64_t>(m.num_vertices() - 1)};
  for (int64_t v : o.pins)
    for (int k = 0; k < 3; ++k) o.targets.push_back(m.V[3 * v + k] + (k == 2 ? 0.3 : 0.0));
  o.styles = {PreferenceFunction(gauss::preset_style("cube")), PreferenceFunction(gauss::preset_style("cone"))};
  for (int f = 0; f < m.num_faces(); ++f) o.face_styles.push_back(f % 3 - 1);
  const std::vector<double> out = stylize(m, o);
  expect_sane(m, out);
  for (size_t i = 0; i < o.pins.size(); ++i)
    EXPECT_EQ(point(out, o.pins[i]), point(o.targets, i)) << "pins are returned exactly";
}

}  // namespace

}  // namespace test_broken_mesh
