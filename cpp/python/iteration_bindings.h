#pragma once
// gauss_core.Solver's run control: stepping until converged, the read-outs that say how far a run is,
// what a step does besides Algorithm 1 (keep_volume, acceleration) and setting the current vertices
// (a warm start).
// Kept apart from solver_bindings.cpp, which adds these to its Solver class with bind_iteration().
// SolverWrapper: solver_bindings.cpp's Solver (core(): the GaussSolver, mutex(): held around every use
// of it).
#include <pybind11/pybind11.h>

#include <mutex>
#include <sstream>
#include <vector>

#include "numpy_arrays.h"

namespace gauss_python {

template <class SolverWrapper>
void bind_iteration(pybind11::class_<SolverWrapper>& cls) {
  namespace py = pybind11;
  cls.def("step_until", [](SolverWrapper& s, const py::object& tol, int max_steps) {
        const double tolerance = tol.is_none() ? s.core().tolerance() : tol.cast<double>();
        py::gil_scoped_release release;
        std::lock_guard<std::mutex> lock(s.mutex());
        return s.core().step_until(tolerance, max_steps);
      }, py::arg("tol"), py::arg("max_steps"),
      "Steps until a step's reldV (last_reldv) is below tol (None: self.tolerance), at most max_steps\n"
      "times; returns the number of steps taken (0 if already converged at tol). Sets self.tolerance to\n"
      "tol. Releases the GIL like step().");
  cls.def_property("tolerance", [](SolverWrapper& s) { return s.core().tolerance(); },
      [](SolverWrapper& s, double t) {
        std::lock_guard<std::mutex> lock(s.mutex());
        s.core().set_tolerance(t);
      }, "The reldV below which `converged` is True (range: LIMITS['tolerance']).");
  cls.def_property_readonly("last_reldv", [](SolverWrapper& s) {
        std::lock_guard<std::mutex> lock(s.mutex());
        return s.core().last_reldv();
      }, "reldV of the last step: its largest coordinate change over the largest coordinate displacement\n"
         "from the rest mesh. inf before the first step and after any change of the settings, styles, pins\n"
         "or vertices: a change leaves the run unconverged until a step says otherwise.");
  cls.def_property_readonly("converged", [](SolverWrapper& s) {
        std::lock_guard<std::mutex> lock(s.mutex());
        return s.core().converged();
      }, "last_reldv < tolerance: the last step moved the mesh by less than the tolerance, and nothing\n"
         "changed since; False while held_back.");
  cls.def_property_readonly("held_back", [](SolverWrapper& s) {
        std::lock_guard<std::mutex> lock(s.mutex());
        return s.core().held_back();
      }, "The run stopped moving because avoid_self_intersections holds it, not because it converged: the\n"
         "last step moved less than the tolerance, but its held vertices (held_vertices) would have moved\n"
         "more without the guard. step_until stops here as at convergence.");
  cls.def_property("keep_volume", [](SolverWrapper& s) { return s.core().keep_volume(); },
      [](SolverWrapper& s, bool on) {
        std::lock_guard<std::mutex> lock(s.mutex());
        s.core().set_keep_volume(on);
      }, "After each step, scale every component without a pin uniformly about its centroid back to its\n"
         "rest volume (closed components) or surface area (open ones). Default: DEFAULTS['keep_volume'].");
  cls.def_property("avoid_self_intersections", [](SolverWrapper& s) { return s.core().avoid_self_intersections(); },
      [](SolverWrapper& s, bool on) {
        std::lock_guard<std::mutex> lock(s.mutex());
        s.core().set_avoid_self_intersections(on);
      }, "No step (nor a move of the pins) brings two faces into contact that were not in contact when\n"
         "it was switched on (or at reset() and set_vertices()): vertices that would are held back, so the\n"
         "result never passes through itself where the input did not. Each step takes longer (how much:\n"
         "docs/performance.md, \"The guard's cost\").\n"
         "Default: DEFAULTS['avoid_self_intersections'].");
  cls.def_property_readonly("held_vertices", [](SolverWrapper& s) {
        std::lock_guard<std::mutex> lock(s.mutex());
        return s.core().held_vertices();
      }, "Vertices avoid_self_intersections held back in the last step or pin move (0 when it is off).");
  cls.def_property("acceleration", [](SolverWrapper& s) { return s.core().acceleration(); },
      [](SolverWrapper& s, bool on) {
        std::lock_guard<std::mutex> lock(s.mutex());
        s.core().set_acceleration(on);
      }, "Accelerate the iteration (momentum with adaptive restart), for both methods: a third of the\n"
         "steps or fewer to converge (Gauss, 35K bunny: 0.29; cubic: 0.12), to the same result. The cubic\n"
         "method's per-vertex ADMM state is extrapolated with the vertices. False: the plain iteration.\n"
         "Either way every step ends on a step of the method's local-global iteration.\n"
         "Default: DEFAULTS['acceleration'].");
  cls.def("set_vertices", [](SolverWrapper& s, const py::object& vertices) {
        const int n = s.core().num_vertices();
        py::array arr = as_array(vertices, "vertices");
        if (arr.ndim() == 2 && arr.shape(0) != n) {  // before copying a huge array
          std::ostringstream msg;
          msg << "vertices must have one row per vertex (" << n << "), got " << arr.shape(0);
          throw py::value_error(msg.str());
        }
        std::vector<double> v = read_matrix<double>(arr, 3, "vertices", false);
        std::lock_guard<std::mutex> lock(s.mutex());
        s.core().set_vertices(v.data(), static_cast<int>(v.size() / 3));
      }, py::arg("vertices"),
      "(#V, 3) new current vertices: a warm start for the next step (e.g. the previous frame of a bake).\n"
      "The rest shape and the factorization stay; pins stay at their targets, vertices no face uses at\n"
      "their input positions; step_count is kept. What earlier steps carried over is dropped, so the\n"
      "steps that follow depend on these vertices alone. NaN, infinite or far-off coordinates are\n"
      "refused (ValueError) without effect.");
}

}  // namespace gauss_python
