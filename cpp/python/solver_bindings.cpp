// Bindings of gauss_core.Solver: the wrapper that owns a GaussSolver (copies inputs while the GIL is
// held, releases it for set-ups and steps, and serializes every use of the solver with a mutex), then
// its Python interface. Run control (step_until, convergence, warm starts) is added by
// iteration_bindings.h.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "bound_style.h"
#include "gauss/solver/gauss_solver.h"
#include "gauss/util/memory_budget.h"
#include "gauss/util/progress.h"
#include "gauss/settings.h"
#include "iteration_bindings.h"
#include "module_facts.h"
#include "module_parts.h"
#include "numpy_arrays.h"

namespace gauss_python {

namespace py = pybind11;
namespace settings = gauss::settings;
using gauss::GaussSolver;
using gauss::PreferenceFunction;

namespace {

// The Progress a Python caller passed (None: none), kept alive for the duration of a set-up.
std::shared_ptr<gauss::Progress> read_progress(const py::object& progress) {
  if (progress.is_none()) return nullptr;
  if (!py::isinstance<gauss::Progress>(progress)) throw py::type_error("progress must be a gauss_core.Progress or None");
  return progress.cast<std::shared_ptr<gauss::Progress>>();
}

class Solver {
 public:
  // Inputs are copied while the GIL is held; the set-up itself runs without it, so another Python
  // thread (Blender's UI timer) can watch or cancel the progress meanwhile.
  Solver(const py::object& V, const py::object& F, const py::object& pinned, const py::object& pin_positions,
         double lam, int admm_iterations, const std::string& method, double cubic_lambda, double tolerance,
         bool keep_volume, bool acceleration, bool avoid_self_intersections, const py::object& progress) {
    const gauss::Method chosen = parse_method(method);  // refused before the set-up's cost
    settings::cubic_lambda.check(cubic_lambda);
    settings::tolerance.check(tolerance);
    std::vector<double> v = read_matrix<double>(V, 3, "V", false);
    std::vector<int64_t> f = read_matrix<int64_t>(F, 3, "F", true);
    std::vector<int64_t> pins;
    std::vector<double> targets;
    read_pins(pinned, pin_positions, pins, targets);
    settings::admm_iterations.check(admm_iterations);
    const std::shared_ptr<gauss::Progress> watcher = read_progress(progress);
    {
      py::gil_scoped_release release;
      const int nV = static_cast<int>(v.size() / 3);
      try {
        solver_ = std::make_unique<GaussSolver>(v.data(), nV, f.data(), static_cast<int>(f.size() / 3), pins,
                                                targets.empty() ? nullptr : targets.data(), lam, watcher.get());
      } catch (const std::bad_alloc&) {
        throw gauss::OutOfMemory("not enough memory to set up a mesh of " + std::to_string(nV) + " vertices");
      }
    }
    solver_->set_admm_iterations(admm_iterations);
    solver_->set_cubic_lambda(cubic_lambda);
    solver_->set_method(chosen);
    solver_->set_tolerance(tolerance);
    solver_->set_keep_volume(keep_volume);
    solver_->set_acceleration(acceleration);
    solver_->set_avoid_self_intersections(avoid_self_intersections);
    styles_.push_back(make_style(settings::default_preset, gauss::default_style()));
  }

  void set_styles(const std::vector<Style>& styles) {
    std::vector<PreferenceFunction> gs;
    for (const Style& s : styles) gs.push_back(*s.g);
    std::lock_guard<std::mutex> lock(mutex_);
    solver_->set_styles(std::move(gs));
    styles_ = styles;
  }
  void set_style(int i, const Style& s) {
    std::lock_guard<std::mutex> lock(mutex_);
    solver_->set_style(i, *s.g);
    styles_[i] = s;
  }
  void set_face_styles(const py::object& idx) {
    std::vector<int64_t> s = read_matrix<int64_t>(idx, 1, "face_styles", true);
    std::lock_guard<std::mutex> lock(mutex_);
    solver_->set_face_styles(s.data(), static_cast<int>(s.size()));
  }
  void set_face_weights(const py::object& weights, const py::object& vertex_weights) {
    // The columns are the caller's (at most one per style): read them off a 2-d array; anything
    // else is read as one column per style, whose check names the shape expected.
    const py::array arr = py::array::ensure(weights);
    const py::ssize_t cols = arr && arr.ndim() == 2 ? arr.shape(1) : solver_->num_styles();
    std::vector<double> w = read_matrix<double>(weights, cols, "face_weights", false);
    std::vector<double> vw;
    if (!vertex_weights.is_none()) vw = read_matrix<double>(vertex_weights, cols, "vertex_weights", false);
    const int rows = cols > 0 ? static_cast<int>(w.size() / cols) : static_cast<int>(arr ? arr.shape(0) : 0);
    const int vertex_rows = cols > 0 ? static_cast<int>(vw.size() / cols) : solver_->num_vertices();
    std::lock_guard<std::mutex> lock(mutex_);
    solver_->set_face_weights(w.data(), rows, static_cast<int>(cols), vertex_weights.is_none() ? nullptr : vw.data(),
                              vertex_rows);
  }
  void set_pins(const py::object& pinned, const py::object& positions, const py::object& progress) {
    std::vector<int64_t> pins;
    std::vector<double> targets;
    read_pins(pinned, positions, pins, targets);
    const std::shared_ptr<gauss::Progress> watcher = read_progress(progress);
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    try {
      solver_->set_pins(pins, targets.empty() ? nullptr : targets.data(), watcher.get());
    } catch (const std::bad_alloc&) {
      throw gauss::OutOfMemory("not enough memory to re-factor the mesh for the new pins");
    }
  }
  void set_pin_positions(const py::object& positions) {
    const size_t num_pins = solver_->pinned().size();
    py::array arr = as_array(positions, "positions");
    if (arr.ndim() == 2 && static_cast<size_t>(arr.shape(0)) != num_pins) {  // before copying a huge array
      std::ostringstream msg;
      msg << "positions must have one row per pinned vertex (" << num_pins << "), got " << arr.shape(0);
      throw py::value_error(msg.str());
    }
    std::vector<double> targets = read_matrix<double>(arr, 3, "positions", false);
    std::lock_guard<std::mutex> lock(mutex_);
    solver_->set_pin_positions(targets.data(), static_cast<int>(targets.size() / 3));
  }
  py::array_t<int64_t> pinned() {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::vector<int64_t>& pins = solver_->pinned();
    py::array_t<int64_t> out(static_cast<py::ssize_t>(pins.size()));
    std::copy(pins.begin(), pins.end(), out.mutable_data());
    return out;
  }
  py::array_t<double> pin_positions() {
    std::lock_guard<std::mutex> lock(mutex_);
    return to_array(solver_->pin_positions());
  }
  void step(int n) {
    if (n < 0) throw py::value_error("the number of steps must be >= 0");
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    for (int i = 0; i < n; ++i) solver_->step();
  }
  py::array_t<double> vertices() {
    py::array_t<double> out({static_cast<py::ssize_t>(solver_->num_vertices()), py::ssize_t(3)});
    std::lock_guard<std::mutex> lock(mutex_);
    solver_->copy_vertices(out.mutable_data());
    return out;
  }
  void vertices_into(py::array out) {
    const py::ssize_t n = solver_->num_vertices();
    const bool shape_ok = (out.ndim() == 2 && out.shape(0) == n && out.shape(1) == 3) ||
                          (out.ndim() == 1 && out.shape(0) == 3 * n);
    if (!shape_ok) {
      std::ostringstream msg;
      msg << "out must have shape (" << n << ", 3) or (" << 3 * n << ",)";
      throw py::value_error(msg.str());
    }
    if (!(out.flags() & py::array::c_style) || !out.writeable())
      throw py::value_error("out must be a writeable C-contiguous array");
    if (out.itemsize() <= 0)  // never divide by it: a numpy this pybind11 misreads shows 0 here
      throw py::value_error("out has an item size of " + std::to_string(out.itemsize()) + " bytes");
    if (reinterpret_cast<std::uintptr_t>(out.data()) % static_cast<std::uintptr_t>(out.itemsize()) != 0)
      throw py::value_error("out must be an aligned array (its data pointer is not a multiple of its item size)");
    std::lock_guard<std::mutex> lock(mutex_);
    if (py::isinstance<py::array_t<float>>(out) && out.dtype().is(py::dtype::of<float>()))
      solver_->copy_vertices(static_cast<float*>(out.mutable_data()));
    else if (out.dtype().is(py::dtype::of<double>()))
      solver_->copy_vertices(static_cast<double*>(out.mutable_data()));
    else
      throw py::type_error("out must have dtype float32 or float64");
  }

  GaussSolver& core() { return *solver_; }
  std::mutex& mutex() { return mutex_; }
  const std::vector<Style>& styles() const { return styles_; }

 private:
  void read_pins(const py::object& pinned, const py::object& positions, std::vector<int64_t>& pins,
                 std::vector<double>& targets) {
    if (!pinned.is_none()) pins = read_matrix<int64_t>(pinned, 1, "pinned", true);
    if (!positions.is_none()) {
      targets = read_matrix<double>(positions, 3, "pin_positions", false);
      if (targets.size() != 3 * pins.size()) {
        std::ostringstream msg;
        msg << "pin_positions must have one row per pinned vertex (" << pins.size() << "), got "
            << targets.size() / 3;
        throw py::value_error(msg.str());
      }
    }
  }

  std::unique_ptr<GaussSolver> solver_;
  std::vector<Style> styles_;
  std::mutex mutex_;
};

}  // namespace

void bind_solver(py::module_& m) {
  py::class_<Solver>(m, "Solver", R"doc(
Gauss stylization of one triangle mesh. The constructor does the set-up (normalization, cotangent
weights, topology, sparse Cholesky factorization); step() runs Algorithm 1 of the paper.

Solver(V, F, pinned=None, pin_positions=None, lam, admm_iterations, method, cubic_lambda, tolerance,
       keep_volume, acceleration, avoid_self_intersections, progress=None)
  (defaults and ranges: DEFAULTS, LIMITS)
  V: (#V, 3) float32/float64 coordinates.  F: (#F, 3) int32/int64 triangle indices.
  pinned: (#P,) vertex indices that keep their position; pin_positions: (#P, 3) targets
  (default: their rest positions).  lam: lambda.  admm_iterations: ADMM rounds per step.
  method: one of METHODS, any case ('gauss': this paper; 'cubic': Cubic Stylization, whose strength is
  cubic_lambda, scaled per face by its style's mu and turned by its style's rotation).
  tolerance: the reldV below which `converged` is True.  keep_volume, acceleration,
  avoid_self_intersections: see the properties.
  progress: a gauss_core.Progress to watch or cancel the set-up from another thread (the
  set-up releases the GIL); a cancelled set-up raises gauss_core.Cancelled.
Raises MemoryError if the mesh's factorization would not fit in the available memory.
By default one style, DEFAULTS['preset'] with the default sigma and mu, applies to every face.)doc")
      .def(py::init<const py::object&, const py::object&, const py::object&, const py::object&, double, int,
                    const std::string&, double, double, bool, bool, bool, const py::object&>(),
           py::arg("V"), py::arg("F"), py::arg("pinned") = py::none(), py::arg("pin_positions") = py::none(),
           py::arg("lam") = settings::lambda.default_value,
           py::arg("admm_iterations") = static_cast<int>(settings::admm_iterations.default_value),
           py::arg("method") = settings::default_method, py::arg("cubic_lambda") = settings::cubic_lambda.default_value,
           py::arg("tolerance") = settings::tolerance.default_value,
           py::arg("keep_volume") = settings::keep_volume.default_value,
           py::arg("acceleration") = settings::acceleration.default_value,
           py::arg("avoid_self_intersections") = settings::avoid_self_intersections.default_value,
           py::arg("progress") = py::none())
      .def("set_styles", &Solver::set_styles, py::arg("styles"),
           "Replaces the style list (takes effect at the next step, no re-factorization).")
      .def("set_style", &Solver::set_style, py::arg("index"), py::arg("style"), "Replaces one style.")
      .def_property_readonly("styles", &Solver::styles, "The current style list.")
      .def("set_face_styles", &Solver::set_face_styles, py::arg("face_styles"),
           "(#F,) ints: style index per face, -1 = unstyled (pure ARAP). No re-factorization.")
      .def("set_face_weights", &Solver::set_face_weights, py::arg("face_weights"),
           py::arg("vertex_weights") = py::none(),
           "(#F, k) floats in [0, 1], k <= len(styles): each face's weight for each of the first k styles (the\n"
           "others weigh 0). A face's preference is the weight-scaled sum of its styles' (mu_s * w_s each);\n"
           "all 0: unstyled. One weight of 1 on a face is exactly set_face_styles with that style.\n"
           "vertex_weights: optional (#V, k) floats in [0, 1], the cubic method's per-vertex weights (without\n"
           "them a vertex takes its faces'). Replaces set_face_styles' assignment. No re-factorization.")
      .def("set_pins", &Solver::set_pins, py::arg("pinned"), py::arg("positions") = py::none(),
           py::arg("progress") = py::none(),
           "Sets the pinned vertices and their targets (re-factors; releases the GIL; progress as in the\n"
           "constructor). On any error, Cancelled included, the solver keeps its previous pins.")
      .def("set_pin_positions", &Solver::set_pin_positions, py::arg("positions"),
           "(#P, 3) new targets for the current pins, in the order of `pinned`. No re-factorization; the pins\n"
           "sit at their targets at once, the rest of the mesh follows at the next step.")
      .def_property_readonly("pinned", &Solver::pinned, "(#P,) int64 copy of the pinned vertex indices.")
      .def_property_readonly("pin_positions", &Solver::pin_positions, "(#P, 3) float64 copy of the pins' targets.")
      .def_property("lam", [](Solver& s) { return s.core().lambda(); },
                    [](Solver& s, double l) { std::lock_guard<std::mutex> lock(s.mutex()); s.core().set_lambda(l); },
                    "lambda: how strongly edges follow the preferred normals (range: LIMITS['lam']).\n"
                    "Setting it does not re-factor.")
      .def_property("admm_iterations", [](Solver& s) { return s.core().admm_iterations(); },
                    [](Solver& s, int n) { std::lock_guard<std::mutex> lock(s.mutex()); s.core().set_admm_iterations(n); },
                    "ADMM rounds per step (range: LIMITS['admm_iterations']).")
      .def_property("method", [](Solver& s) { return settings::method_names[static_cast<int>(s.core().method())]; },
                    [](Solver& s, const std::string& m) { const gauss::Method chosen = parse_method(m);
                      std::lock_guard<std::mutex> lock(s.mutex()); s.core().set_method(chosen); },
                    "The next step's method (METHODS); switching keeps pins, styles and the factorization.")
      .def_property("cubic_lambda", [](Solver& s) { return s.core().cubic_lambda(); },
                    [](Solver& s, double l) { std::lock_guard<std::mutex> lock(s.mutex()); s.core().set_cubic_lambda(l); },
                    "lambda of the cubic method (range: LIMITS['cubic_lambda']).")
      .def_property_readonly("cubic_admm_iterations", [](Solver& s) { return s.core().cubic_admm_iterations(); },
                             "ADMM iterations of the last cubic step, summed over the vertices.")
      .def_property_readonly("cubic_energy", [](Solver& s) { std::lock_guard<std::mutex> lock(s.mutex());
                               return s.core().cubic_energy(); }, "sum_i lambda_i |Q_i^T R_i n_i|_1 of the last cubic step.")
      .def("step", &Solver::step, py::arg("n") = 1, "Runs n iterations (releases the GIL).")
      .def("reset", [](Solver& s) { std::lock_guard<std::mutex> lock(s.mutex()); s.core().reset(); },
           "Current vertices := rest vertices; step_count := 0.")
      .def_property_readonly("vertices", &Solver::vertices, "(#V, 3) float64 copy of the current vertices.")
      .def("vertices_into", &Solver::vertices_into, py::arg("out"),
           "Writes the current vertices into a C-contiguous float32/float64 array of shape (#V, 3) or (3*#V,).")
      .def_property_readonly("arap_energy", [](Solver& s) {
             std::lock_guard<std::mutex> lock(s.mutex());
             return s.core().arap_energy();
           }, "E_ARAP of the current mesh (normalized frame).")
      .def_property_readonly("g_energy", [](Solver& s) {
             std::lock_guard<std::mutex> lock(s.mutex());
             return s.core().g_energy();
           }, "E_g = sum over styled faces of g(n_f).")
      .def_property_readonly("step_count", [](Solver& s) { return s.core().step_count(); })
      .def_property_readonly("factorization_count", [](Solver& s) { return s.core().factorization_count(); })
      .def_property_readonly("num_vertices", [](Solver& s) { return s.core().num_vertices(); })
      .def_property_readonly("num_faces", [](Solver& s) { return s.core().num_input_faces(); })
      .def_property_readonly("last_step_ms", [](Solver& s) {
             const gauss::StepTimings& t = s.core().last_timings();
             py::dict d;
             d["faces"] = t.faces; d["rotations"] = t.rotations; d["admm"] = t.admm; d["rhs"] = t.rhs; d["solve"] = t.solve; d["threads"] = t.threads;
             return d;
           }, "Milliseconds per phase of the last step.");
  py::class_<Solver> solver_class = py::reinterpret_borrow<py::class_<Solver>>(m.attr("Solver"));
  gauss_python::bind_iteration(solver_class);
}

}  // namespace gauss_python
