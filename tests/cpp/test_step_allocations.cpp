// A step must not touch the heap (the rule for the per-iteration loop): this file replaces
// the global allocation functions with counting ones for the whole test binary.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "gauss/gauss_solver.h"
#include "gauss/presets.h"
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

TEST(StepAllocations, StepsDoNotAllocate) {
  // Large enough for the parallel paths (more than 4096 faces), with pins (on one of two components:
  // Keep Volume scales the other), two styles (one with rings), an unstyled face and several ADMM
  // rounds, so every branch of a step runs.
  gauss::TriangleMesh m = gauss_test::icosphere(5);
  const gauss::TriangleMesh second = gauss_test::icosphere(2);
  const int offset = m.num_vertices();
  for (size_t i = 0; i < second.V.size(); ++i) m.V.push_back(second.V[i] + (i % 3 == 0 ? 3.0 : 0.0));
  for (int64_t i : second.F) m.F.push_back(i + offset);
  gauss::GaussSolver s(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), {0, 17});
  s.set_styles({gauss::PreferenceFunction(gauss::preset_style("cube")),
                gauss::PreferenceFunction(gauss::preset_style("double_cone"))});
  std::vector<int64_t> fs(m.num_faces());
  for (int f = 0; f < m.num_faces(); ++f) fs[f] = f % 3 == 0 ? 1 : 0;
  fs[5] = -1;
  s.set_face_styles(fs.data(), m.num_faces());
  s.set_admm_iterations(2);
  for (int i = 0; i < 3; ++i) s.step();  // warm-up: the thread pool starts its workers
  const long before = g_allocations.load();
  for (int i = 0; i < 5; ++i) s.step();
  EXPECT_EQ(g_allocations.load() - before, 0);
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
}
