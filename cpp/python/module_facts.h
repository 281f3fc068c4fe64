#pragma once
// What gauss_core exports from the solver's tables (settings.h, presets.h): PRESETS, METHODS, DEFAULTS,
// LIMITS, SIZE_LIMITS, PRESET_LAMBDA and
// PAPER_STEP_MAX_SIGMA, and the reading of a method's name. For the Python module only.
#include <pybind11/pybind11.h>

#include <algorithm>
#include <cctype>
#include <iterator>
#include <string>

#include "gauss/solver/gauss_solver.h"
#include "gauss/style/presets.h"
#include "gauss/settings.h"

namespace gauss_python {

namespace py = pybind11;

// A method by name (gauss::settings::method_names), in any case: the add-on passes its enum ids ('CUBIC').
inline gauss::Method parse_method(const std::string& name) {
  std::string lower = name, known;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  for (size_t i = 0; i < std::size(gauss::settings::method_names); ++i) {
    if (lower == gauss::settings::method_names[i]) return static_cast<gauss::Method>(i);
    known += std::string(i ? ", '" : "'") + gauss::settings::method_names[i] + "'";
  }
  throw py::value_error("method must be one of " + known + " (got '" + name + "')");
}

inline void export_facts(py::module_& m) {
  namespace settings = gauss::settings;
  py::list presets;
  for (const std::string& n : gauss::preset_names()) presets.append(n);
  m.attr("PRESETS") = py::tuple(presets);
  py::dict defaults, limits;
  for (const gauss::Setting* setting : settings::all) {
    if (setting->integer) {
      defaults[setting->name] = static_cast<long>(setting->default_value);
      limits[setting->name] = py::make_tuple(static_cast<long>(setting->min), static_cast<long>(setting->max));
    } else {
      defaults[setting->name] = setting->default_value;
      limits[setting->name] = py::make_tuple(setting->min, setting->max);
    }
  }
  for (const gauss::Option* option : settings::options) defaults[option->name] = option->default_value;
  defaults["preset"] = settings::default_preset;
  defaults["method"] = settings::default_method;
  py::list methods;
  for (const char* name : settings::method_names) methods.append(name);
  m.attr("METHODS") = py::tuple(methods);
  m.attr("DEFAULTS") = defaults;
  m.attr("LIMITS") = limits;
  py::dict sizes;
  sizes["normals"] = settings::max_style_normals;
  sizes["rings"] = settings::max_style_rings;
  m.attr("SIZE_LIMITS") = sizes;
  // The lambda a preset is meant to run at where it differs from DEFAULTS['lam'] (docs/styles.md).
  py::dict preset_lambda;
  preset_lambda["sheet_metal"] = settings::sheet_metal_lambda;
  m.attr("PRESET_LAMBDA") = preset_lambda;
  // Above this sigma the normal step solves Eq. 18 on the sphere (normal_step.h, trust_region_normal).
  m.attr("PAPER_STEP_MAX_SIGMA") = settings::paper_step_max_sigma;
}

}  // namespace gauss_python
