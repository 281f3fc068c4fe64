// The settings table (settings.h) and the preset registry (presets.h) are what the solver enforces.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "gauss/solver/gauss_solver.h"
#include "gauss/style/presets.h"
#include "gauss/settings.h"
#include "test_expect.h"
#include "test_meshes.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_settings {

using gauss::GaussSolver;
using gauss::PreferenceFunction;
using gauss::Setting;
namespace settings = gauss::settings;

namespace {

// The nearest values just outside a setting's range.
double below(const Setting& s) { return s.integer ? s.min - 1 : std::nextafter(s.min, -INFINITY); }
double above(const Setting& s) { return s.integer ? s.max + 1 : std::nextafter(s.max, INFINITY); }

// Applies one setting's value where the solver takes it: a style's parameter, or the solver's.
// Steps once and returns whether every coordinate stayed finite; throws what the solver throws.
bool apply_and_step(const Setting& s, double value) {
  static const gauss::TriangleMesh m = gauss_test::icosphere(2);
  gauss::StyleParams p = gauss::preset_style("double_cone");  // rings too, so axis_contribution matters
  if (&s == &settings::sigma) p.sigma = value;
  if (&s == &settings::mu) p.mu = value;
  if (&s == &settings::axis_contribution) p.axis_contribution = value;
  const PreferenceFunction g(p);
  const double lambda = &s == &settings::lambda ? value : settings::lambda.default_value;
  GaussSolver solver(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces(), {}, nullptr, lambda);
  if (&s == &settings::lambda) solver.set_lambda(value);
  if (&s == &settings::admm_iterations) solver.set_admm_iterations(static_cast<int>(value));
  if (&s == &settings::cubic_lambda) {  // the cubic method reads it (with the style's mu)
    solver.set_cubic_lambda(value);
    solver.set_method(gauss::Method::cubic);
  }
  if (&s == &settings::tolerance) solver.set_tolerance(value);
  solver.set_styles({g});
  solver.step();
  std::vector<double> out(m.V.size());
  solver.copy_vertices(out.data());
  for (double x : out)
    if (!std::isfinite(x)) return false;
  return std::isfinite(solver.arap_energy()) && std::isfinite(solver.g_energy()) && std::isfinite(solver.cubic_energy());
}

}  // namespace

TEST(Settings, TheSolverAcceptsEveryLimitAndRefusesJustOutside) {
  for (const Setting* s : settings::all) {
    for (double v : {s->min, s->default_value, s->max}) {
      bool finite = false;
      EXPECT_NO_THROW(finite = apply_and_step(*s, v)) << s->name << " = " << v;
      EXPECT_TRUE(finite) << s->name << " = " << v;
    }
    for (double v : {below(*s), above(*s), std::numeric_limits<double>::quiet_NaN()}) {
      if (s->integer && std::isnan(v)) continue;  // integers cannot be NaN
      SCOPED_TRACE(std::string(s->name) + " = " + std::to_string(v));
      gauss_test::expect_refused([&] { apply_and_step(*s, v); }, std::string(s->label) + " must be");
    }
  }
}

TEST(Settings, DefaultsLieInsideTheirLimits) {
  for (const Setting* s : settings::all) {
    EXPECT_TRUE(s->accepts(s->default_value)) << s->name;
    EXPECT_LT(s->min, s->max) << s->name;
    if (s->integer) EXPECT_EQ(s->default_value, std::round(s->default_value)) << s->name;
  }
  EXPECT_NO_THROW(gauss::preset_style(settings::default_preset));
}

TEST(Presets, TheRegistryOrderIsUnchanged) {
  // Saved .blend files store the add-on's style enum by position in this list: append only.
  const std::vector<std::string> expected = {
      "cube",           "tetrahedron",      "octahedron",        "dodecahedron",     "icosahedron",
      "square_pyramid", "truncated_pyramid", "triangular_prism", "hexagonal_prism",  "plane",
      "cylinder",       "cone",             "double_cone",       "sheet_metal"};
  EXPECT_EQ(gauss::preset_names(), expected);
  for (const std::string& name : gauss::preset_names()) EXPECT_NO_THROW(gauss::preset_style(name)) << name;
  gauss_test::expect_refused([] { gauss::preset_style("sphere"); }, "valid presets: cube, tetrahedron");
}

TEST(Presets, TheDefaultStyleIsTheDefaultPreset) {
  const gauss::StyleParams d = gauss::default_style(), p = gauss::preset_style(settings::default_preset);
  EXPECT_EQ(d.normals, p.normals);
  EXPECT_EQ(d.sigma, settings::sigma.default_value);
  EXPECT_EQ(d.mu, settings::mu.default_value);
  EXPECT_EQ(d.axis_contribution, settings::axis_contribution.default_value);
  // A solver without set_styles() stylizes with it.
  const gauss::TriangleMesh m = gauss_test::icosphere(2);
  GaussSolver implicit(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
  GaussSolver explicit_(m.V.data(), m.num_vertices(), m.F.data(), m.num_faces());
  explicit_.set_styles({PreferenceFunction(p)});
  for (int i = 0; i < 5; ++i) implicit.step(), explicit_.step();
  std::vector<double> a(m.V.size()), b(m.V.size());
  implicit.copy_vertices(a.data());
  explicit_.copy_vertices(b.data());
  EXPECT_EQ(a, b);
}

}  // namespace test_settings
