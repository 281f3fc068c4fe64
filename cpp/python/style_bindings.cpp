// Bindings of gauss_core.Style and merge_directions: what a preference function g is made of (preferred
// normals, rings, presets, sigma, mu, orientation) and what it evaluates to. Inputs are checked here
// (ValueError/TypeError) before any copy of a large array is made.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "bound_style.h"
#include "gauss/solver/normal_step.h"
#include "gauss/style/direction_merge.h"
#include "gauss/style/normal_field.h"
#include "gauss/style/presets.h"
#include "gauss/settings.h"
#include "module_parts.h"
#include "numpy_arrays.h"

namespace gauss_python {

namespace py = pybind11;
namespace settings = gauss::settings;
using gauss::StyleParams;

void bind_direction_merge(py::module_& m) {
  m.def("merge_directions", [](const py::object& normals, double max_angle_degrees, const py::object& weights) {
        std::vector<double> n = read_matrix<double>(normals, 3, "normals", false);
        std::vector<Eigen::Vector3d> dirs(n.size() / 3);
        for (size_t i = 0; i < dirs.size(); ++i) {
          const Eigen::Vector3d d(n[3 * i], n[3 * i + 1], n[3 * i + 2]);
          const double len = d.norm();
          if (!d.allFinite() || !(len > 1e-300) || !std::isfinite(len)) {
            std::ostringstream msg;
            msg << "normal " << i << " is zero, NaN or infinite; every direction must be a finite, non-zero 3-vector";
            throw py::value_error(msg.str());
          }
          dirs[i] = d / len;
        }
        std::vector<double> w;
        if (!weights.is_none()) {
          w = read_matrix<double>(weights, 1, "weights", false);
          if (w.size() != dirs.size()) {
            std::ostringstream msg;
            msg << "weights must have one entry per normal (" << dirs.size() << "), got " << w.size();
            throw py::value_error(msg.str());
          }
        }
        if (!(max_angle_degrees >= 0.0 && max_angle_degrees <= 90.0))
          throw py::value_error("max_angle_degrees must lie between 0 and 90 (got " + std::to_string(max_angle_degrees) + ")");
        gauss::MergedDirections md;
        {
          py::gil_scoped_release release;
          md = gauss::merge_directions(dirs, w, max_angle_degrees * (M_PI / 180.0));
        }
        py::array_t<double> counts(static_cast<py::ssize_t>(md.weights.size()));
        for (size_t i = 0; i < md.weights.size(); ++i) counts.mutable_at(i) = md.weights[i];
        return py::make_tuple(to_array(md.directions), counts);
      }, py::arg("normals"), py::arg("max_angle_degrees"), py::arg("weights") = py::none(), R"doc(
Merges near-parallel directions: (directions (M, 3), weights (M,)).

normals: (K, 3) non-zero vectors (normalized here); weights: (K,) values >= 0 (e.g. face areas),
default 1 each, so the second result counts the directions merged into each one.
Directions are taken as seeds in order of decreasing weight (ties: by direction); each seed takes
every remaining direction within max_angle_degrees (0..90) of it and becomes their weighted mean.
So every input lies within max_angle_degrees of its seed, any two seeds are farther apart than that,
and the result does not depend on the order of the inputs. O(K log K).)doc");
}

void bind_style(py::module_& m) {
  py::class_<Style>(m, "Style", R"doc(
A preference function g on the Gauss sphere with its own sigma (concentration) and mu (strength).

Style(normals=None, *, sigma, mu, rotation=None, axis=None, ring_offsets=(), axis_contribution)
  (defaults and ranges of sigma, mu, axis_contribution: DEFAULTS and LIMITS)
  normals: (K, 3) preferred normals (normalized here); may be None if ring_offsets are given.
  axis, ring_offsets: circles x . axis = d on the Gauss sphere (cylinder d = 0, cone d != 0).
  axis_contribution: weight of the discrete normals relative to the rings (only with rings).
  rotation: 3x3 rotation matrix applied to the normals and the axis (the style's orientation).
Weights are solved so that g = 1 at every preferred normal (Eq. 10 of the paper).)doc")
      .def(py::init([](const py::object& normals, double sigma, double mu, const py::object& rotation,
                       const py::object& axis, const py::object& ring_offsets, double axis_contribution) {
             StyleParams p;
             if (!normals.is_none() && as_array(normals, "normals").size() > 0) {
               // Refused before the copy: a huge array must not cost memory first.
               if (as_array(normals, "normals").size() > 3 * static_cast<py::ssize_t>(settings::max_style_normals))
                 throw py::value_error("a style takes at most " + std::to_string(settings::max_style_normals) +
                                       " preferred normals; merge near-parallel ones first (merge_directions)");
               std::vector<double> n = read_matrix<double>(normals, 3, "normals", false);
               for (size_t i = 0; i + 2 < n.size(); i += 3) p.normals.emplace_back(n[i], n[i + 1], n[i + 2]);
             }
             if (!ring_offsets.is_none()) p.ring_offsets = read_matrix<double>(ring_offsets, 1, "ring_offsets", false);
             if (!axis.is_none()) p.axis = read_vector3(axis, "axis");
             p.sigma = sigma;
             p.mu = mu;
             p.rotation = read_rotation(rotation);
             p.axis_contribution = axis_contribution;
             return make_style("custom", p);
           }),
           py::arg("normals") = py::none(), py::kw_only(), py::arg("sigma") = settings::sigma.default_value,
           py::arg("mu") = settings::mu.default_value, py::arg("rotation") = py::none(), py::arg("axis") = py::none(),
           py::arg("ring_offsets") = py::none(), py::arg("axis_contribution") = settings::axis_contribution.default_value)
      .def_static("preset", [](const std::string& name, const py::object& sigma, double mu, const py::object& rotation,
                               double axis_contribution) {
             StyleParams p = gauss::preset_style(name);
             if (!sigma.is_none()) p.sigma = sigma.cast<double>();
             p.mu = mu;
             p.rotation = read_rotation(rotation);
             p.axis_contribution = axis_contribution;
             return make_style(name, p);
           },
           py::arg("name"), py::arg("sigma") = py::none(), py::arg("mu") = settings::mu.default_value,
           py::arg("rotation") = py::none(), py::arg("axis_contribution") = settings::axis_contribution.default_value,
           "A named style (see PRESETS) with the given sigma (None: the preset's, DEFAULTS['sigma'] for all but\n"
           "sheet_metal), mu, orientation and axis contribution.")
      .def_static("gauss_map", [](const py::object& normals, const py::object& areas, double sigma, double mu,
                                  const py::object& rotation) {
             StyleParams p;
             p.kind = gauss::StyleKind::gauss_map;
             // Refused before the copy: a huge array must not cost memory first.
             if (as_array(normals, "normals").size() > 3 * static_cast<py::ssize_t>(settings::max_style_normals))
               throw py::value_error("an example's Gauss map takes at most " +
                                     std::to_string(settings::max_style_normals) +
                                     " normals; merge near-parallel ones first (merge_directions)");
             std::vector<double> n = read_matrix<double>(normals, 3, "normals", false);
             for (size_t i = 0; i + 2 < n.size(); i += 3) p.normals.emplace_back(n[i], n[i + 1], n[i + 2]);
             if (!areas.is_none()) {
               p.areas = read_matrix<double>(areas, 1, "areas", false);
               if (p.areas.size() != p.normals.size())
                 throw py::value_error("areas must hold one value per normal (" + std::to_string(p.normals.size()) +
                                       "), got " + std::to_string(p.areas.size()));
             }
             p.sigma = sigma;
             p.mu = mu;
             p.rotation = read_rotation(rotation);
             return make_style("gauss_map", p);
           },
           py::arg("normals"), py::arg("areas") = py::none(), py::kw_only(),
           py::arg("sigma") = settings::sigma.default_value, py::arg("mu") = settings::mu.default_value,
           py::arg("rotation") = py::none(), R"doc(
An example's whole Gauss map as a style (kind 'gauss_map', docs/styles.md#gauss-map).

normals: (K, 3) the example's face normals (normalized here), K >= 1; areas: (K,) their areas (>= 0,
positive sum), default equal. Before each step every face looks up the example normal nearest to its
own normal (a k-d tree built here, once); its g is that normal's bump of sigma weighted by its pull (the
example's area within 0.2 rad of it over the largest such area, square-rooted). Up to 64 normals far
enough apart that Eq. 10 weighs each positively, g sums them all with those weights times their pulls,
as Style(normals) does: a cube's six give exactly the Cube preset's g.)doc")
      .def_property_readonly("name", [](const Style& s) { return s.name; }, "Preset name, 'custom' or 'gauss_map'.")
      .def_property_readonly("kind", [](const Style& s) {
             switch (s.g->kind()) {
               case gauss::StyleKind::developable: return "developable";
               case gauss::StyleKind::gauss_map: return "gauss_map";
               default: return "directions";
             }
           },
           "'directions': the style prefers its normals and rings. 'developable' (the sheet_metal\n"
           "preset): it has none; each face prefers its own normal turned onto the great circle of\n"
           "its neighbours' normals, worked out by the solver before each step, so the surface bends\n"
           "one way at a time; value() is then the bump around x itself (1 everywhere). 'gauss_map'\n"
           "(Style.gauss_map): each face prefers the example normal nearest to its own; value(x) is the\n"
           "weighted bump of the one nearest to x (all of them summed, for up to 64 normals far apart).")
      .def_property_readonly("areas", [](const Style& s) -> py::object {
             const gauss::ExampleNormals* e = s.g->example();
             if (e == nullptr) return py::none();
             return py::array_t<double>(static_cast<py::ssize_t>(e->areas().size()), e->areas().data());
           }, "A gauss_map style's areas of its normals, summing to 1; None for other styles.")
      .def_property_readonly("pull", [](const Style& s) -> py::object {
             const gauss::ExampleNormals* e = s.g->example();
             if (e == nullptr) return py::none();
             return py::array_t<double>(static_cast<py::ssize_t>(e->pull().size()), e->pull().data());
           }, "A gauss_map style's pull of each normal, in (0, 1]; None for other styles.")
      .def_property_readonly("normals", [](const Style& s) { return to_array(s.g->normals()); },
                             "(K, 3) preferred normals after rotation.")
      .def_property_readonly("axis", [](const Style& s) { return to_array({s.g->axis()}).reshape({3}); },
                             "Ring axis after rotation.")
      .def_property_readonly("ring_offsets", [](const Style& s) { return s.g->ring_offsets(); })
      .def_property_readonly("sigma", [](const Style& s) { return s.g->sigma(); })
      .def_property_readonly("trust_region_step", [](const Style& s) { return gauss::takes_trust_region_step(*s.g); },
                             "Does a face of this style take the trust-region normal step, unless the solver's\n"
                             "paper_step_any_sigma is on (docs/high_sigma.md)?")
      .def_property_readonly("mu", [](const Style& s) { return s.g->mu(); })
      .def_property_readonly("axis_contribution", [](const Style& s) { return s.params.axis_contribution; })
      .def_property_readonly("fit", [](const Style& s) -> py::object {
             const gauss::NormalField* f = s.g->field();
             if (f == nullptr) return py::none();
             py::dict d;
             d["nodes"] = f->num_nodes();
             d["max_input_error"] = f->max_input_error();
             d["tolerance"] = gauss::NormalField::kTolerance;
             d["truncation_bound"] = f->truncation_bound();
             return d;
           },
           "None when g sums every preferred normal exactly (at most 64); with more, how it stands for them:\n"
           "{'nodes', 'max_input_error': max |g(n_k) - 1| over the normals, measured, 'tolerance': its stated\n"
           "bound, 'truncation_bound': what the skipped terms can change g by}.")
      .def_property_readonly("rotation", [](const Style& s) {
             py::array_t<double> R({3, 3});
             auto w = R.mutable_unchecked<2>();
             for (int i = 0; i < 3; ++i)
               for (int j = 0; j < 3; ++j) w(i, j) = s.params.rotation(i, j);
             return R;
           })
      .def("value", [](const Style& s, const py::object& x) {
             return eval_points(x, [&](const std::vector<double>& p, bool single) -> py::object {
               py::array_t<double> out(static_cast<py::ssize_t>(p.size() / 3));
               for (size_t i = 0; i < p.size() / 3; ++i)
                 out.mutable_at(i) = s.g->value(Eigen::Vector3d(p[3 * i], p[3 * i + 1], p[3 * i + 2]));
               return single ? py::object(py::float_(out.at(0))) : py::object(out);
             });
           }, py::arg("x"), "g(x) for x of shape (3,) or (n, 3).")
      .def("gradient", [](const Style& s, const py::object& x) {
             return eval_points(x, [&](const std::vector<double>& p, bool single) -> py::object {
               const py::ssize_t n = static_cast<py::ssize_t>(p.size() / 3);
               py::array_t<double> out({n, py::ssize_t(3)});
               auto w = out.mutable_unchecked<2>();
               for (py::ssize_t i = 0; i < n; ++i) {
                 double g; Eigen::Vector3d gr; Eigen::Matrix3d H;
                 s.g->evaluate(Eigen::Vector3d(p[3 * i], p[3 * i + 1], p[3 * i + 2]), g, gr, H);
                 for (int k = 0; k < 3; ++k) w(i, k) = gr[k];
               }
               return single ? py::object(out.reshape({3})) : py::object(out);
             });
           }, py::arg("x"), "Unconstrained gradient of g (Eqs. 11, 14), shape (3,) or (n, 3).")
      .def("hessian", [](const Style& s, const py::object& x) {
             return eval_points(x, [&](const std::vector<double>& p, bool single) -> py::object {
               const py::ssize_t n = static_cast<py::ssize_t>(p.size() / 3);
               py::array_t<double> out({n, py::ssize_t(3), py::ssize_t(3)});
               auto w = out.mutable_unchecked<3>();
               for (py::ssize_t i = 0; i < n; ++i) {
                 double g; Eigen::Vector3d gr; Eigen::Matrix3d H;
                 s.g->evaluate(Eigen::Vector3d(p[3 * i], p[3 * i + 1], p[3 * i + 2]), g, gr, H);
                 for (int a = 0; a < 3; ++a)
                   for (int b = 0; b < 3; ++b) w(i, a, b) = H(a, b);
               }
               return single ? py::object(out.reshape({3, 3})) : py::object(out);
             });
           }, py::arg("x"), "Unconstrained Hessian of g (Eqs. 12, 15), shape (3, 3) or (n, 3, 3).")
      .def("__repr__", [](const Style& s) {
        std::ostringstream o;
        o << "<gauss_core.Style '" << s.name << "' sigma=" << s.g->sigma() << " mu=" << s.g->mu()
          << " normals=" << s.g->normals().size() << " rings=" << s.g->ring_offsets().size() << ">";
        return o.str();
      });
}

}  // namespace gauss_python
