// Bindings that control a run from outside the solver: the Progress another thread watches and cancels
// a set-up with, the exceptions a set-up ends with (Cancelled; MemoryError for a factorization that would
// not fit) and the number of threads a step uses.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <exception>
#include <sstream>
#include <string>

#include "gauss/util/memory_budget.h"
#include "gauss/util/parallel.h"
#include "gauss/util/progress.h"
#include "module_parts.h"

namespace gauss_python {

namespace py = pybind11;

void bind_errors_and_progress(py::module_& m) {
  py::register_exception<gauss::Cancelled>(m, "Cancelled", PyExc_RuntimeError);
  m.attr("Cancelled").attr("__doc__") =
      "Raised by a Solver set-up (the constructor, set_pins) whose Progress was cancelled.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const gauss::OutOfMemory& e) {
      PyErr_SetString(PyExc_MemoryError, e.what());
    }
  });

  py::class_<gauss::Progress, std::shared_ptr<gauss::Progress>>(m, "Progress", R"doc(
Progress and cancellation of a set-up: pass one as Solver(..., progress=p) or
set_pins(..., progress=p) and watch it from another thread (the set-up releases the GIL).

p.fraction   0.0 .. 1.0, never decreases; roughly proportional to the set-up's time
p.phase      '' before the start, then 'topology', 'weights', 'ordering', 'symbolic',
             'factorizing' (set_pins: from 'ordering'), 'done' at the end
p.cancel()   thread-safe; the set-up raises gauss_core.Cancelled soon after (it checks every few
             milliseconds of work, then frees what it allocated)
p.cancelled  whether cancel() was called (a cancelled Progress stays cancelled)
p.seconds    {phase: seconds} of the last set-up it watched)doc")
      .def(py::init<>())
      .def_property_readonly("fraction", &gauss::Progress::fraction)
      .def_property_readonly("phase", [](const gauss::Progress& p) { return std::string(p.phase()); })
      .def("cancel", &gauss::Progress::cancel, "Asks the set-up to stop (it raises gauss_core.Cancelled).")
      .def_property_readonly("cancelled", &gauss::Progress::cancelled)
      .def_property_readonly("seconds", [](const gauss::Progress& p) {
        py::dict d;
        for (int i = 0; i < static_cast<int>(gauss::SetupPhase::count); ++i) {
          const auto phase = static_cast<gauss::SetupPhase>(i);
          d[gauss::phase_name(phase)] = p.seconds(phase);
        }
        return d;
      })
      .def("__repr__", [](const gauss::Progress& p) {
        std::ostringstream o;
        o << "<gauss_core.Progress " << p.phase() << " " << static_cast<int>(100 * p.fraction()) << "%"
          << (p.cancelled() ? " cancelled" : "") << ">";
        return o.str();
      });
}

void bind_threads(py::module_& m) {
  m.def("set_num_threads", [](int n) {
        if (n < 1) throw py::value_error("the number of threads must be >= 1");
        gauss::parallel::set_max_threads(n);
      }, py::arg("n"), "Sets how many threads steps use (results do not depend on it).");
  m.def("get_num_threads", []() { return gauss::parallel::max_threads(); },
        "Number of threads steps use (default: GAUSS_THREADS or OMP_NUM_THREADS, else one per core).");
}

}  // namespace gauss_python
