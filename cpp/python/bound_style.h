#pragma once
// gauss_core.Style's C++ side, shared by the Style bindings (style_bindings.cpp) and the Solver that
// holds a list of them (solver_bindings.cpp). In a named namespace: pybind11 knows a class by its C++
// type, so both files must see one and the same type.
#include <memory>
#include <string>
#include <utility>

#include "gauss/style/preference_function.h"

namespace gauss_python {

// A style as Python sees it: its parameters (for read-back) plus the evaluated function.
struct Style {
  std::string name;
  gauss::StyleParams params;
  std::shared_ptr<gauss::PreferenceFunction> g;
};

inline Style make_style(std::string name, gauss::StyleParams params) {
  Style s{std::move(name), params, nullptr};
  s.g = std::make_shared<gauss::PreferenceFunction>(params);
  return s;
}

}  // namespace gauss_python
