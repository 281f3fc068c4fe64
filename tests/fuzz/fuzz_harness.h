#pragma once
// The fuzz target's body: one input = one session with GaussSolver through its public entry points
// (mesh arrays with arbitrary indices and coordinates, pins and their targets, styles from presets or
// from arbitrary normals/rings/sigma/mu/rotation, face styles, lambda, ADMM iterations, steps, reset,
// read-outs, moving the pins). Shared by the libFuzzer target (fuzz_solver.cpp) and by the replay of the corpus and of
// the regressions in tests/cpp/test_robustness.cpp, so every input the fuzzer ever crashed on stays
// covered by ctest under any compiler.
//
// Besides what the sanitizers check, a violation of this contract calls abort():
//  * bad input is refused with std::invalid_argument (any other exception escapes: a crash);
//  * a solver that was built steps and reads out finite coordinates and energies, and the coordinates
//    stay bounded: within kGrowth times the extent of the rest mesh and the pin targets (the
//    session's earlier ones too: a vertex let go springs back over steps) of their centre, however
//    many steps ran (slivers once made meshes explode, finite but 1e80 wide);
//  * nothing is lost: vertices that no usable face references come back bit for bit as given, and
//    pinned vertices exactly at their targets.
//
// Input layout (bytes consumed front to back; missing bytes read as 0): mesh, pins, lambda, then up
// to 16 operations, then new pin targets, then a continuation with the cubic method. tests/fuzz/make_corpus.py writes seeds in this layout.
//
// Files: fuzz_reader.h reads the bytes, fuzz_inputs.h decodes them into a mesh, pins and styles,
// fuzz_contract.h checks the read-outs; this file runs the session.
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include "fuzz_contract.h"
#include "fuzz_inputs.h"
#include "fuzz_reader.h"
#include "gauss/solver/gauss_solver.h"
#include "gauss/style/preference_function.h"

namespace gauss_fuzz {

// Moves the current pins (set_pin_positions, no re-factorization): near their targets or anywhere, or
// with a wrong count. It runs after the operations, so inputs saved before it still replay the sessions
// they were saved for.
inline void drag_pins(Reader& r, gauss::GaussSolver& s, const Mesh& m, Pins& pins) {
  Pins moved = pins;
  if (moved.target.empty())
    for (int64_t v : moved.index) moved.target.insert(moved.target.end(), &m.V[3 * v], &m.V[3 * v] + 3);
  const uint8_t mode = r.byte();
  for (double& x : moved.target) x = mode % 2 ? r.real() : x + r.real() / 8.0;
  const int count = static_cast<int>(moved.index.size()) - (mode >= 224 ? 1 : 0);
  GAUSS_FUZZ_TRACE("  set_pin_positions (%d of %zu)\n", count, moved.index.size());
  try {
    s.set_pin_positions(moved.target.empty() ? nullptr : moved.target.data(), count);
    if (count != static_cast<int>(moved.index.size())) fail("a wrong number of pin positions was accepted");
    retire(moved, pins, m);
    pins = std::move(moved);
  } catch (const std::invalid_argument& e) {
    GAUSS_FUZZ_TRACE("    refused: %s\n", e.what());
  }
}

// The same session continued with the cubic method (cubic_local_step.h): a cubic lambda (default or
// any), a run, optionally new styles or a reset and back to the Gauss method for a step. It runs after
// drag_pins, so inputs saved before it still replay the sessions they were saved for first.
template <class Step>
void cubic_session(Reader& r, gauss::GaussSolver& s, const Mesh& m, const std::vector<uint8_t>& referenced,
                   const Pins& pins, Step&& step) {
  const uint8_t mode = r.byte();
  try {
    if (mode & 1) s.set_cubic_lambda(r.param());
  } catch (const std::invalid_argument& e) {
    GAUSS_FUZZ_TRACE("  set_cubic_lambda refused: %s\n", e.what());
  }
  s.set_method(gauss::Method::cubic);
  const int n = 1 + r.byte() % 64;
  GAUSS_FUZZ_TRACE("  cubic: lambda %g, %d steps\n", s.cubic_lambda(), n);
  for (int i = 0; i < n; ++i) step();
  check(s, m, referenced, pins);
  if (mode & 2)
    if (auto g = make_style(r)) {  // the cubic method reads its mu and rotation
      try {
        s.set_style(0, *g);
      } catch (const std::invalid_argument&) {  // there is no style 0
      }
      step();
    }
  if (mode & 4) s.reset(), step(), step();
  if (mode & 8) s.set_method(gauss::Method::gauss), step();
  check(s, m, referenced, pins);
}

inline void run_one(const uint8_t* data, size_t size) {
  Reader r(data, size);
  const Mesh m = make_mesh(r);
  Pins pins = make_pins(r, m);
  const double lambda = r.byte() < 128 ? 4.0 : r.param();
  std::unique_ptr<gauss::GaussSolver> s;
  try {
    s = std::make_unique<gauss::GaussSolver>(m.V.data(), m.nv(), m.F.data(), m.nf(), pins.index,
                                             pins.target.empty() ? nullptr : pins.target.data(), lambda);
  } catch (const std::invalid_argument& e) {
    GAUSS_FUZZ_TRACE("mesh %d vertices, %d faces, %zu pins, lambda %g: refused: %s\n", m.nv(), m.nf(),
                     pins.index.size(), lambda, e.what());
    return;
  }
  GAUSS_FUZZ_TRACE("mesh %d vertices, %d faces, %zu pins, lambda %g: accepted\n", m.nv(), m.nf(), pins.index.size(),
                   lambda);
  // Accepted: every index is in range. A face is usable if its three indices differ.
  std::vector<uint8_t> referenced(m.nv(), 0);
  for (int f = 0; f < m.nf(); ++f) {
    const int64_t a = m.F[3 * f], b = m.F[3 * f + 1], c = m.F[3 * f + 2];
    if (a != b && b != c && c != a) referenced[a] = referenced[b] = referenced[c] = 1;
  }
  if (s->num_vertices() != m.nv() || s->num_input_faces() != m.nf()) fail("the solver lost vertices or faces");

  // Work budget: dozens of 1000-round steps take seconds under the sanitizers and teach nothing new.
  long rounds_left = 4000;  // a 1000-step run fits, with room for the other operations
  auto step = [&] {
    if (rounds_left < s->admm_iterations()) return;
    rounds_left -= s->admm_iterations();
    s->step();
  };
  const int ops = 1 + r.byte() % 16;
  for (int op = 0; op < ops && !r.empty(); ++op) {
    const int code = r.byte() % 10;
    static const char* const names[10] = {"set_styles", "set_style", "set_face_styles", "set_lambda", "set_pins",
                                          "set_admm_iterations", "step", "reset", "check", "long_run"};
    GAUSS_FUZZ_TRACE("  %s\n", names[code]);
    try {
      switch (code) {
        case 0: {
          std::vector<gauss::PreferenceFunction> styles;
          const int n = r.byte() % 4;
          for (int i = 0; i < n; ++i)
            if (auto g = make_style(r)) styles.push_back(*g);
          s->set_styles(std::move(styles));
          break;
        }
        case 1: {
          const int index = static_cast<int>(r.byte() % (s->num_styles() + 2)) - 1;
          if (auto g = make_style(r)) s->set_style(index, *g);
          break;
        }
        case 2: {
          const int count = r.byte() < 224 ? m.nf() : r.byte() % (m.nf() + 2);
          std::vector<int64_t> fs(count);
          for (int64_t& x : fs) {
            const uint8_t b = r.byte();
            x = b < 250 ? static_cast<int64_t>(b % (s->num_styles() + 1)) - 1
                        : (b == 250 ? -2 : b == 251 ? s->num_styles() : b == 252 ? INT64_MIN : INT64_MAX);
          }
          s->set_face_styles(fs.data(), count);
          break;
        }
        case 3:
          s->set_lambda(r.param());
          break;
        case 4: {
          Pins p = make_pins(r, m);
          s->set_pins(p.index, p.target.empty() ? nullptr : p.target.data());
          retire(p, pins, m);
          pins = std::move(p);
          break;
        }
        case 5: {
          static const int counts[16] = {-1, 0, 1, 1, 1, 2, 2, 2, 3, 3, 4, 5, 8, 20, 1000, 1001};
          s->set_admm_iterations(counts[r.byte() % 16]);
          break;
        }
        case 6: {
          const int n = 1 + r.byte() % 4;
          for (int i = 0; i < n; ++i) step();
          break;
        }
        case 7:
          s->reset();
          if (s->step_count() != 0) fail("reset did not reset the step count");
          break;
        case 8:
          check(*s, m, referenced, pins);
          break;
        default: {  // a live run left going: up to 1000 steps, then the read-outs
          const int n = 100 * (1 + r.byte() % 10);
          for (int i = 0; i < n; ++i) step();
          check(*s, m, referenced, pins);
          break;
        }
      }
    } catch (const std::invalid_argument& e) {
      // Refused with a message: fine, and the solver must still work (checked below).
      GAUSS_FUZZ_TRACE("    refused: %s\n", e.what());
    }
  }
  step();
  check(*s, m, referenced, pins);
  drag_pins(r, *s, m, pins);
  step();
  check(*s, m, referenced, pins);
  try {
    cubic_session(r, *s, m, referenced, pins, step);
  } catch (const std::invalid_argument& e) {
    GAUSS_FUZZ_TRACE("    refused: %s\n", e.what());
  }
  GAUSS_FUZZ_TRACE("  done: %d steps since reset, %d styles, E_g %g\n", s->step_count(), s->num_styles(), s->g_energy());
}

}  // namespace gauss_fuzz
