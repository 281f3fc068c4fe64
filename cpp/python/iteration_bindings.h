#pragma once
// gauss_core.Solver's run control: stepping until converged and setting the current vertices (a warm
// start). The settings and read-outs that say how far a run is (tolerance, last_reldv, converged, ...)
// are rows of settings.h's tables, bound by solver_bindings.cpp.
// Kept apart from solver_bindings.cpp, which adds these to its Solver class with bind_iteration().
// SolverWrapper: solver_bindings.cpp's Solver (core(): the GaussSolver, mutex(): held around every use
// of it).
#include <pybind11/pybind11.h>

#include <algorithm>
#include <cstdint>
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
  cls.def_property_readonly("held_vertex_indices", [](SolverWrapper& s) {
        std::vector<int> held;
        {
          std::lock_guard<std::mutex> lock(s.mutex());
          held = s.core().held_vertex_indices();
        }
        py::array_t<int32_t> out(static_cast<py::ssize_t>(held.size()));
        std::copy(held.begin(), held.end(), out.mutable_data());
        return out;
      }, "(held_vertices,) int32: which vertices avoid_self_intersections held back in the last step or\n"
         "pin move, ascending (empty when it is off): where the run is held, e.g. to select them.");
  cls.def("set_vertices", [](SolverWrapper& s, const py::object& vertices) {
        const int n = s.core().num_vertices();
        py::array arr = as_array(vertices, "vertices");
        if (arr.ndim() == 2 && arr.shape(0) != n) {  // before copying a huge array
          std::ostringstream msg;
          msg << "vertices must have one row per vertex (" << n << "), got " << arr.shape(0);
          throw py::value_error(msg.str());
        }
        std::vector<double> v = read_matrix<double>(arr, 3, "vertices", false);
        // With Resolution Independent it fits the start's rotations (seconds at a million vertices):
        // a worker thread's warm start must not hold Blender's Python.
        py::gil_scoped_release release;
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
