// The gauss_core Python module: numpy in, numpy out. Every check that can fail on user data happens in
// the bindings or in the library and raises ValueError/TypeError; nothing reaches native code unchecked.
// This file only assembles the module; each group of bindings lives in its own file (module_parts.h).
#include <pybind11/pybind11.h>

#include "module_facts.h"
#include "module_parts.h"
#include "numpy_abi_guard.h"

PYBIND11_MODULE(gauss_core, m) {
  gauss_python::refuse_unreadable_numpy();  // first: nothing may read an array it cannot read
  m.doc() = "Gauss stylization (Kohlbrenner et al. 2021): ARAP with preferred face normals.";

  gauss_python::export_facts(m);
  // Which Python this binary is for, readable in the file itself (scripts/binary_facts.py).
  m.attr("BUILT_FOR") = "gauss_core for CPython " GAUSS_PYTHON_VERSION;
  gauss_python::bind_direction_merge(m);
  gauss_python::bind_errors_and_progress(m);
  gauss_python::bind_threads(m);
  gauss_python::bind_style(m);
  gauss_python::bind_solver(m);
  gauss_python::bind_self_intersections(m);
  gauss_python::bind_proxy(m);
}
