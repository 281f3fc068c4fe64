// A step must not touch the heap, so that a live run's tick never waits on the allocator: this file replaces
// the global allocation functions with counting ones for the whole test binary.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include <Eigen/Geometry>

#include "gauss/proxy/proxy_mesh.h"
#include "gauss/proxy/proxy_transfer.h"
#include "gauss/sparse/cholesky_solver.h"
#include "gauss/solver/gauss_solver.h"
#include "gauss/style/presets.h"
#include "test_meshes.h"

namespace {
std::atomic<long> g_allocations{0};
}

void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(n ? n : 1);
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

// The replacements above must stay global; the tests, like every test file's, are in a namespace of
// their own (a unity build compiles several files in one translation unit).
namespace test_step_allocations {

// Heap allocations in five steps of `s`, after three that warm up (the thread pool starts its workers,
// buffers sized by a setting just changed are made).
long allocations_in_steps(gauss::GaussSolver& s) {
  for (int i = 0; i < 3; ++i) s.step();
  const long before = g_allocations.load();
  for (int i = 0; i < 5; ++i) s.step();
  return g_allocations.load() - before;
}

TEST(StepAllocations, StepsDoNotAllocate) {
  // Large enough for the parallel paths (more than 4096 faces), with pins (on one of two components:
  // Keep Volume scales the other), two styles (one with rings), an unstyled face and several ADMM
  // rounds, so every branch of a step runs.
  const gauss::TriangleMesh m = gauss_test::beside(gauss_test::icosphere(5), gauss_test::icosphere(2));
  gauss::GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), {0, 17});
  s.set_styles({gauss::PreferenceFunction(gauss::preset_style("cube")),
                gauss::PreferenceFunction(gauss::preset_style("double_cone"))});
  std::vector<int64_t> fs(m.num_faces());
  for (int f = 0; f < m.num_faces(); ++f) fs[f] = f % 3 == 0 ? 1 : 0;
  fs[5] = -1;
  s.set_face_styles(fs.data(), m.num_faces());
  s.set_admm_iterations(2);
  EXPECT_EQ(allocations_in_steps(s), 0);
  // What wraps a step: Keep Volume, stepping until converged.
  s.set_keep_volume(true);
  const long before_options = g_allocations.load();
  for (int i = 0; i < 5; ++i) s.step();
  s.step_until(gauss::settings::tolerance.min, 5);
  EXPECT_EQ(g_allocations.load() - before_options, 0);
  std::vector<double> out(m.V.size());
  const long before_copy = g_allocations.load();
  s.copy_vertices(out.data());
  EXPECT_EQ(g_allocations.load() - before_copy, 0);
  // The cubic method: preparing it may allocate, its steps may not (two styles, one turned, an
  // unstyled face, pins: every branch of its ADMM).
  s.set_method(gauss::Method::cubic);
  gauss::StyleParams turned = gauss::preset_style("cube");
  turned.rotation = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  s.set_style(1, gauss::PreferenceFunction(turned));
  EXPECT_EQ(allocations_in_steps(s), 0);
  EXPECT_GT(s.cubic_admm_iterations(), 0);
  // Avoid Self-Intersections: switching it on allocates its guard; a step it checks does not (its
  // hierarchy, task list and contact buffers are kept from step to step).
  s.set_avoid_self_intersections(true);
  EXPECT_EQ(allocations_in_steps(s), 0);
  // Resolution Independent: switching it on allocates its weights; its steps (the bending term's pull
  // on every rotation fit, both methods) do not.
  s.set_avoid_self_intersections(false);
  s.set_resolution_independent(true);
  EXPECT_EQ(allocations_in_steps(s), 0);
  s.set_method(gauss::Method::gauss);
  EXPECT_EQ(allocations_in_steps(s), 0);
}

TEST(StepAllocations, LeanStepsDoNotAllocate) {
  // What a mesh of a million vertices or more steps with (shown here on a small one): lean steps
  // (gauss_solver.h), with Resolution Independent's bending term.
  const gauss::TriangleMesh m = gauss_test::icosphere(5);
  gauss::GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), {0, 17});
  s.set_styles({gauss::PreferenceFunction(gauss::preset_style("cube"))});
  s.set_lean_steps(true);
  s.set_resolution_independent(true);
  EXPECT_EQ(allocations_in_steps(s), 0);
}

TEST(StepAllocations, SheetMetalStepsDoNotAllocate) {
  // The developable style's preferred normals are made before every Gauss step and by g_energy():
  // choosing the style sizes their buffers; the steps (one style alone, and blended with another on
  // some faces) and the read-out do not allocate. Large enough for the parallel paths.
  const gauss::TriangleMesh m = gauss_test::icosphere(5);
  gauss::GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
  s.set_styles({gauss::PreferenceFunction(gauss::preset_style("sheet_metal")),
                gauss::PreferenceFunction(gauss::preset_style("cube"))});
  for (int i = 0; i < 3; ++i) s.step();
  const long before = g_allocations.load();
  for (int i = 0; i < 5; ++i) s.step();
  EXPECT_GT(s.g_energy(), 0.0);
  EXPECT_EQ(g_allocations.load() - before, 0);
  std::vector<double> w(2 * static_cast<size_t>(m.num_faces()));
  for (int f = 0; f < m.num_faces(); ++f) w[2 * f] = 1.0, w[2 * f + 1] = f % 2 ? 0.5 : 0.0;
  s.set_face_weights(w.data(), m.num_faces(), 2);
  EXPECT_EQ(allocations_in_steps(s), 0);
}

TEST(StepAllocations, CholeskySolveDoesNotAllocate) {
  // Large enough for nested dissection, both parts on threads and the sums owed to the rows above
  // the cut (a step's solve on the 60,002-vertex cube).
  gauss::TriangleMesh m = gauss_test::grid_cube(100);
  std::vector<Eigen::Triplet<double>> entries;
  const int n = m.num_vertices();
  std::vector<double> diagonal(n, 1e-3);
  for (int f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = static_cast<int>(m.F[3 * f + k]), b = static_cast<int>(m.F[3 * f + (k + 1) % 3]);
      entries.emplace_back(std::max(a, b), std::min(a, b), -0.5);
      diagonal[a] += 0.5;
      diagonal[b] += 0.5;
    }
  for (int i = 0; i < n; ++i) entries.emplace_back(i, i, diagonal[i]);
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  // In doubles, and in floats refined against A (a million unknowns and more), whose scratch is made
  // with the factor.
  for (auto precision : {gauss::CholeskySolver::Precision::double_values,
                         gauss::CholeskySolver::Precision::single_values}) {
    gauss::CholeskySolver s;
    s.factor(A, nullptr, precision);
    std::vector<double> y(3 * static_cast<size_t>(n), 1.0);
    s.solve_ordered_in_place(y.data());  // warm-up: the thread pool starts its workers
    const long before = g_allocations.load();
    for (int i = 0; i < 3; ++i) s.solve_ordered_in_place(y.data());
    EXPECT_EQ(g_allocations.load() - before, 0) << "single precision " << s.single_precision();
  }
}

TEST(StepAllocations, ProxyTransferDoesNotAllocate) {
  // A live tick on a large mesh carries the proxy's shape to it (proxy_transfer.h): big enough for the
  // parallel loops over the proxy's vertices and faces and the mesh's vertices.
  const gauss::TriangleMesh m = gauss_test::icosphere(6);  // 40,962 vertices
  const gauss::ProxyMesh proxy = gauss::proxy_mesh(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), 8000);
  gauss::ProxyTransfer data = gauss::proxy_transfer_precomputation(proxy);
  std::vector<float> P;
  for (const auto& p : proxy.vertices) P.insert(P.end(), {float(1.1 * p.x()), float(p.y()), float(0.9 * p.z())});
  std::vector<double> Pd(P.begin(), P.end());
  std::vector<float> out(m.V.size());
  gauss::proxy_transfer(data, P.data(), out.data());  // warm-up: the thread pool starts its workers
  const long before = g_allocations.load();
  for (int i = 0; i < 3; ++i) {
    gauss::proxy_transfer(data, P.data(), out.data());
    gauss::proxy_transfer(data, Pd.data(), out.data());
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
}

}  // namespace test_step_allocations
