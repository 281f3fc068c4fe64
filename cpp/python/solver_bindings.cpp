// Bindings of gauss_core.Solver: the wrapper that owns a GaussSolver (copies inputs while the GIL is
// held, releases it for set-ups and steps, and serializes every use of the solver with a mutex), then
// its Python interface. Every setting (a keyword of Solver() and a property) and every scalar read-out
// comes from the tables at the end of settings.h, never by hand here; run control (step_until, warm
// starts) is added by iteration_bindings.h.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
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
  // thread (Blender's UI timer) can watch or cancel the progress meanwhile. The settings are the
  // defaults until the caller's are applied (bind_constructor).
  Solver(const py::object& V, const py::object& F, const py::object& pinned, const py::object& pin_positions,
         const py::object& progress) {
    std::vector<double> v = read_matrix<double>(V, 3, "V", false);
    std::vector<int64_t> f = read_matrix<int64_t>(F, 3, "F", true);
    std::vector<int64_t> pins;
    std::vector<double> targets;
    read_pins(pinned, pin_positions, pins, targets);
    const std::shared_ptr<gauss::Progress> watcher = read_progress(progress);
    {
      py::gil_scoped_release release;
      const int nV = static_cast<int>(v.size() / 3);
      try {
        solver_ = std::make_unique<GaussSolver>(v.data(), nV, f.data(), static_cast<int>(f.size() / 3), pins,
                                                targets.empty() ? nullptr : targets.data(),
                                                settings::lambda.default_value, watcher.get());
      } catch (const std::bad_alloc&) {
        throw gauss::OutOfMemory("not enough memory to set up a mesh of " + std::to_string(nV) + " vertices");
      }
    }
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

// --- The settings and read-out tables of settings.h, as keywords and properties. ---

constexpr auto kSettings = settings::solver_settings<GaussSolver>();
constexpr auto kReadouts = settings::solver_readouts<GaussSolver>();

// The type Python passes and gets for a setting of the solver's type Value: the method travels by name.
template <class Value>
struct PythonValue {
  using type = Value;
  static Value read(const Value& v) { return v; }
  static py::object write(Value v) { return py::cast(v); }
};
template <>
struct PythonValue<gauss::Method> {
  using type = std::string;
  static gauss::Method read(const std::string& name) { return parse_method(name); }
  static py::object write(gauss::Method m) { return py::str(settings::method_names[static_cast<int>(m)]); }
};
template <class Row>
using PythonOf = PythonValue<std::remove_cv_t<std::remove_reference_t<decltype((std::declval<GaussSolver&>().*
                                                                                std::declval<Row>().get)())>>>;

// A keyword's default in its Python type, and the check that refuses a value before the set-up's cost
// (the setter checks again).
template <class Value>
Value default_of(const gauss::Setting& s) { return static_cast<Value>(s.default_value); }
template <class Value>
bool default_of(const gauss::Option& o) { return o.default_value; }
template <class Value>
std::string default_of(const gauss::Choice& c) { return c.default_value; }
inline void check_value(const gauss::Setting& s, double v) { s.check(v); }
inline void check_value(const gauss::Option&, bool) {}
inline void check_value(const gauss::Choice&, const std::string& name) { parse_method(name); }

// help() text of a setting: its doc, then where its default (and range) are.
std::string setting_doc(const gauss::Setting& s) {
  return std::string(s.doc) + "\nDefault: DEFAULTS['" + s.name + "']; range: LIMITS['" + s.name + "'].";
}
std::string setting_doc(const gauss::Option& o) {
  return std::string(o.doc) + "\nDefault: DEFAULTS['" + o.name + "'].";
}
std::string setting_doc(const gauss::Choice& c) {
  return std::string(c.doc) + "\nDefault: DEFAULTS['" + c.name + "'].";
}

// pybind11 keeps the char pointers of docs it is given; these live as long as the module.
const char* kept(std::string text) {
  static std::deque<std::string> texts;
  texts.push_back(std::move(text));
  return texts.back().c_str();
}

// Solver(V, F, pinned=None, pin_positions=None, *, <every setting row>=<its default>, progress=None).
template <size_t... I>
void bind_constructor(py::class_<Solver>& cls, std::index_sequence<I...>) {
  cls.def(py::init([](const py::object& V, const py::object& F, const py::object& pinned,
                      const py::object& pin_positions,
                      const typename PythonOf<std::tuple_element_t<I, decltype(kSettings)>>::type&... values,
                      const py::object& progress) {
            (check_value(*std::get<I>(kSettings).setting, values), ...);
            auto solver = std::make_unique<Solver>(V, F, pinned, pin_positions, progress);
            GaussSolver& core = solver->core();
            using Rows = decltype(kSettings);
            ((core.*std::get<I>(kSettings).set)(PythonOf<std::tuple_element_t<I, Rows>>::read(values)), ...);
            return solver;
          }),
          py::arg("V"), py::arg("F"), py::arg("pinned") = py::none(), py::arg("pin_positions") = py::none(),
          py::kw_only(),
          (py::arg(std::get<I>(kSettings).setting->name) =
               default_of<typename PythonOf<std::tuple_element_t<I, decltype(kSettings)>>::type>(
                   *std::get<I>(kSettings).setting))...,
          py::arg("progress") = py::none());
}

template <class Row>
void bind_setting(py::class_<Solver>& cls, const Row& row) {
  using Python = PythonOf<Row>;
  const auto get = row.get;
  const auto set = row.set;
  cls.def_property(
      row.setting->name,
      [get](Solver& s) {
        std::lock_guard<std::mutex> lock(s.mutex());
        return Python::write((s.core().*get)());
      },
      [set](Solver& s, const typename Python::type& value) {
        const auto v = Python::read(value);  // a bad name is refused before waiting for the lock
        std::lock_guard<std::mutex> lock(s.mutex());
        (s.core().*set)(v);
      },
      kept(setting_doc(*row.setting)));
}

template <class Row>
void bind_readout(py::class_<Solver>& cls, const Row& row) {
  const auto get = row.get;
  cls.def_property_readonly(
      row.name,
      [get](Solver& s) {
        std::lock_guard<std::mutex> lock(s.mutex());
        return (s.core().*get)();
      },
      row.doc);
}

// The class doc's list of settings, from the table.
std::string settings_summary() {
  std::string names;
  std::apply([&](const auto&... row) { ((names += std::string(names.empty() ? "" : ", ") + row.setting->name), ...); },
             kSettings);
  return names;
}

}  // namespace

void bind_solver(py::module_& m) {
  py::class_<Solver> cls(m, "Solver", kept(R"doc(
Gauss stylization of one triangle mesh. The constructor does the set-up (normalization, cotangent
weights, topology, sparse Cholesky factorization); step() runs Algorithm 1 of the paper.

Solver(V, F, pinned=None, pin_positions=None, *, SETTING=DEFAULTS[SETTING]..., progress=None)
  V: (#V, 3) float32/float64 coordinates.  F: (#F, 3) int32/int64 triangle indices.
  pinned: (#P,) vertex indices that keep their position; pin_positions: (#P, 3) targets
  (default: their rest positions).
  The settings, keyword-only, each also a property of that name (see its doc; defaults: DEFAULTS,
  ranges: LIMITS): )doc" + settings_summary() + R"doc(.
  progress: a gauss_core.Progress to watch or cancel the set-up from another thread (the
  set-up releases the GIL); a cancelled set-up raises gauss_core.Cancelled.
Raises MemoryError if the mesh's factorization would not fit in the available memory.
By default one style, DEFAULTS['preset'] with the default sigma and mu, applies to every face.)doc"));
  bind_constructor(cls, std::make_index_sequence<std::tuple_size_v<decltype(kSettings)>>{});
  std::apply([&](const auto&... row) { (bind_setting(cls, row), ...); }, kSettings);
  std::apply([&](const auto&... row) { (bind_readout(cls, row), ...); }, kReadouts);
  cls
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
      .def("step", &Solver::step, py::arg("n") = 1, "Runs n iterations (releases the GIL).")
      .def("reset", [](Solver& s) { std::lock_guard<std::mutex> lock(s.mutex()); s.core().reset(); },
           "Current vertices := rest vertices; step_count := 0.")
      .def_property_readonly("vertices", &Solver::vertices, "(#V, 3) float64 copy of the current vertices.")
      .def("vertices_into", &Solver::vertices_into, py::arg("out"),
           "Writes the current vertices into a C-contiguous float32/float64 array of shape (#V, 3) or (3*#V,).")
      .def_property_readonly("last_step_ms", [](Solver& s) {
             const gauss::StepTimings& t = s.core().last_timings();
             py::dict d;
             d["faces"] = t.faces; d["rotations"] = t.rotations; d["admm"] = t.admm; d["rhs"] = t.rhs; d["solve"] = t.solve; d["guard"] = t.guard; d["threads"] = t.threads;
             return d;
           }, "Milliseconds per phase of the last step.");
  gauss_python::bind_iteration(cls);
}

}  // namespace gauss_python
