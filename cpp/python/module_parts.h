#pragma once
// The parts of the gauss_core module, one group of bindings per source file. module.cpp calls them in
// the order declared here (the order the module's attributes are created in).
#include <pybind11/pybind11.h>

namespace gauss_python {

// merge_directions (style_bindings.cpp): near-parallel normals merged before they make a style.
void bind_direction_merge(pybind11::module_& m);
// Cancelled, MemoryError for OutOfMemory, Progress (run_control_bindings.cpp): watching and stopping a set-up.
void bind_errors_and_progress(pybind11::module_& m);
// set_num_threads, get_num_threads (run_control_bindings.cpp).
void bind_threads(pybind11::module_& m);
// Style (style_bindings.cpp): a preference function g, its presets and its read-outs.
void bind_style(pybind11::module_& m);
// Solver (solver_bindings.cpp): set-up, styles, pins, stepping and read-outs of one mesh.
void bind_solver(pybind11::module_& m);
// self_intersections (collision_bindings.cpp): the pairs of faces that pass through each other.
void bind_self_intersections(pybind11::module_& m);
// Proxy (proxy_bindings.cpp): a simplified copy of a large mesh and the transfer of its deformation.
void bind_proxy(pybind11::module_& m);

}  // namespace gauss_python
