#pragma once
// Every solver setting's default, hard limits and Python doc, written once, and the table of how
// gauss_core.Solver binds them (solver_settings, solver_readouts at the end).
//
// Everything else derives from this file: the solver's and the preference function's input checks,
// the Python module's keyword arguments, properties and their docs (cpp/python/solver_bindings.cpp
// walks the tables), its exports gauss_core.DEFAULTS / gauss_core.LIMITS, and through those the Blender
// add-on's properties (default, hard range), validation and panel. The build also writes the settings
// to the add-on's core_facts.json (tools/gauss_facts.cpp), which the add-on reads when the native
// module cannot be loaded, so saved settings still register with the right defaults.
// How to add a setting: docs/architecture.md#how-to-add-a-style-or-a-setting.
//
// Limits are inclusive. They are where a setting stops being useful, kept well inside where the
// arithmetic would overflow (lambda and mu multiply squared edge lengths; sigma is an exponent).
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>

namespace gauss {

struct Setting {
  const char* name;   // the Python name (Solver keyword / Style keyword / add-on property)
  const char* label;  // how error messages call it
  double default_value;
  double min, max;
  bool integer;
  const char* doc;  // what Python's help() says of it (a Solver property or a Style keyword)

  bool accepts(double v) const { return v >= min && v <= max; }  // false for NaN

  // Throws std::invalid_argument naming the setting and its range unless accepts(v).
  void check(double v) const {
    if (accepts(v)) return;
    std::ostringstream msg;
    msg << label << " must be " << (integer ? "an integer" : "a number") << " between " << min << " and " << max
        << " (got " << v << ")";
    throw std::invalid_argument(msg.str());
  }
};

// An on/off option of the solver: exported in gauss_core.DEFAULTS (a bool; it has no limits).
struct Option {
  const char* name;  // the Python name (Solver keyword and property)
  bool default_value;
  const char* doc;  // what Python's help() says of it
};

// A setting that takes one of a list of names (the method): exported in gauss_core.DEFAULTS as a str.
struct Choice {
  const char* name;  // the Python name (Solver keyword and property)
  const char* default_value;
  const char* doc;  // what Python's help() says of it
};

namespace settings {

// The doc of each setting is what Python's help() shows; the bindings add where its default and range are.

inline constexpr Setting lambda{"lam", "lambda", 4.0, 0.0, 1e4, false,
                                "lambda of Eq. 27: how strongly edges follow the preferred normals. Setting it does "
                                "not re-factor."};
inline constexpr Setting sigma{"sigma", "sigma", 4.0, 1e-3, 1e3, false,
                               "sigma of Eq. 9: concentration of each preferred normal's bump on the Gauss sphere."};
inline constexpr Setting mu{"mu", "mu", 1.0, 0.0, 1e3, false,
                            "Weight of -mu * g(n_f) for a style's faces, relative to the other styles and to ARAP."};
inline constexpr Setting axis_contribution{"axis_contribution", "axis_contribution", 0.5, 0.0, 1.0, false,
                                           "Weight of a ring style's discrete (axis) normals relative to its rings."};
inline constexpr Setting admm_iterations{"admm_iterations", "ADMM iterations", 1, 1, 100, true,
                                         "ADMM rounds per step (Algorithm 1's inner loop)."};
// Gauss's lambda (above) weighs another energy, so each method has its own; 0.2 is the reference
// implementation's default.
inline constexpr Setting cubic_lambda{"cubic_lambda", "cubic lambda", 0.2, 0.0, 100.0, false,
                                      "lambda of the cubic method (Cubic Stylization, Liu & Jacobson 2019): the "
                                      "weight of its term lambda * a_i * ||R_i n_i||_1 against ARAP in a unit "
                                      "bounding box, scaled per face by its style's mu."};

// Stylization methods, by the names gauss_core takes (Solver(method=...)): the paper's "gauss" and
// Cubic Stylization's "cubic" (cubic_local_step.h). A new method is appended, never reordered: the
// add-on's enum stores these positions in saved files.
inline constexpr const char* method_names[] = {"gauss", "cubic"};
inline constexpr const char* default_method = "gauss";
inline constexpr Choice method{"method", default_method,
                               "The next step's method, one of METHODS in any case ('gauss': this paper; 'cubic': "
                               "Cubic Stylization, whose strength is cubic_lambda, scaled per face by its style's "
                               "mu and turned by its style's rotation). Switching keeps pins, styles and the "
                               "factorization."};

// reldV is the stopping rule of the reference cubic stylization code; below 1e-5 its rounding floor is
// too close (a still mesh reads ~4e-7).
inline constexpr Setting tolerance{"tolerance", "tolerance", 1e-3, 1e-5, 1.0, false,
                                   "The reldV (last_reldv: a step's largest coordinate change over the largest "
                                   "coordinate displacement from the rest mesh) below which `converged` is True."};

inline constexpr const Setting* all[] = {&lambda,          &sigma,        &mu,       &axis_contribution,
                                         &admm_iterations, &cubic_lambda, &tolerance};

// Off by default, as the paper's method does not rescale (volume_keeper.h).
inline constexpr Option keep_volume{"keep_volume", false,
                                    "After each step, scale every component without a pin uniformly about its "
                                    "centroid back to its rest volume (closed components) or surface area (open "
                                    "ones), since stylization shrinks a mesh."};

// fixed_point_iteration.h; how many steps it saves: docs/performance.md#converging-in-fewer-steps.
inline constexpr Option acceleration{"acceleration", true,
                                     "Accelerate the iteration (momentum with adaptive restart), for both methods: "
                                     "fewer steps to the same result (docs/performance.md, 'Converging in fewer "
                                     "steps'). The cubic method's per-vertex ADMM state is extrapolated with the "
                                     "vertices. False: the plain iteration. Either way every step ends on a step "
                                     "of the method's local-global iteration."};

// Off by default: the paper's method does not look (self_intersection.h).
inline constexpr Option avoid_self_intersections{
    "avoid_self_intersections", false,
    "No step (nor a move of the pins) brings two faces into contact that were not in contact when it was "
    "switched on (or at reset() and set_vertices()): vertices that would are held back (held_vertices), so the "
    "result never passes through itself where the input did not. Each step takes longer (how much: "
    "docs/performance.md, \"The guard's cost\")."};

// Off by default in the solver, which then steps bit for bit as the paper's method; the add-on turns it
// on for new objects (docs/resolution.md).
inline constexpr Option resolution_independent{
    "resolution_independent", false,
    "Stylize alike at any tessellation of a surface, for both methods: a mesh finer than the reference "
    "density gets the bending stiffness ARAP has at the reference, and the preference of a face coarser than "
    "the reference is weighed by its rest area, so lam (and cubic_lambda) mean the same on a coarse and a "
    "subdivided mesh (docs/resolution.md). False: the paper's method, bit for bit."};

// Off by default: Resolution Independent's rule before 2026-12-06, kept so that files saved under it
// replay as they were (the add-on's settings versioning sets it for them; docs/resolution.md).
inline constexpr Option weigh_finer_faces{
    "weigh_finer_faces", false,
    "With resolution_independent: weigh the preference of faces finer than the reference density by their "
    "rest area too, as that setting did before 2026-12-06 (files saved then keep their result with it). It "
    "makes a fine face's coupling up to reference/area times lam, which keeps some runs from settling "
    "(docs/resolution.md). Without resolution_independent, or with the cubic method, it changes nothing."};

// Off by default: the paper's method has no notion of regions (flat_regions.h).
inline constexpr Option square_flat_regions{
    "square_flat_regions", false,
    "Give the large flat regions of the rest mesh straight, square outlines instead of round ones, for both "
    "methods: the faces around each region turn about its normal towards the axes of its outline "
    "(docs/styles.md, 'Square Flat Regions'). False: no change, bit for bit."};

// Off by default: the normal step before 2026-12-07, kept so that files and recipes with a sharper
// style replay as they were (the add-on's settings versioning sets it for them; docs/high_sigma.md).
inline constexpr Option paper_step_any_sigma{
    "paper_step_any_sigma", false,
    "Take the paper's one Newton step for a face's normal (Eqs. 21-22) at every sigma, as before 2026-12-07 "
    "(files saved then keep their result with it). False: above sigma 8, for styles whose preferred normals "
    "stand apart (Style.trust_region_step), the step is taken on the sphere within one bump's width instead, "
    "since there the paper's step makes faces jump between preferred normals at every step and a run never "
    "settles (docs/high_sigma.md). At sigma 8 and below, for rings and Sheet Metal, it changes nothing."};

inline constexpr const Option* options[] = {&keep_volume, &acceleration, &avoid_self_intersections,
                                            &resolution_independent, &weigh_finer_faces, &square_flat_regions,
                                            &paper_step_any_sigma};

// Up to this sigma a face's normal takes the paper's one Newton step (Eqs. 21-22), bit for bit; above it
// (without paper_step_any_sigma, for the styles normal_step.h's takes_trust_region_step names) a
// trust-region Newton step on the sphere (normal_step.h: trust_region_normal). On Spot, the 6K bunny and Suzanne no face's paper step falls
// back to the gradient at sigma 4 and 8, and from 12 on runs stop settling (docs/high_sigma.md).
inline constexpr double paper_step_max_sigma = 8.0;
// ... and only for a style whose bumps stand apart, PreferenceFunction::separation() above this: each
// bump fallen below about 1% of its peak at its nearest neighbour's centre. Where they overlap more (the
// icosahedron's 20 normals up to sigma 17, the truncated pyramid's up to 15) g's ridges between them
// carry the paper's step, which settles there, and the trust-region step did not on Spot
// (docs/high_sigma.md). Nor for styles with rings (cylinder, cone), where it did not either.
inline constexpr double trust_region_min_separation = 4.5;

// The face area (solver frame: longest bounding-box side 1) at which Resolution Independent changes
// nothing; finer meshes are stylized as a mesh of this density is. Why this value:
// docs/resolution.md#the-reference-density.
inline constexpr double reference_face_area = 6e-4;

// The acceleration's parameters per method (fixed_point_iteration.h): the momentum factor beta; for how
// many steps a vertex whose step turned against its momentum goes without it, so that flapping sliver
// regions are not kicked further; and stop_factor: an extrapolated step's reldV counts as measured /
// stop_factor, because measured from the extrapolated point the cubic method's step understates how far
// the shape still moves. Each was chosen as the fastest to the plain iteration's converged share, which
// is measured in docs/performance.md#converging-in-fewer-steps.
struct Momentum {
  double beta;
  int hold;
  double stop_factor;
};
inline constexpr Momentum gauss_momentum{0.8, 4, 1.0};
inline constexpr Momentum cubic_momentum{0.93, 0, 0.7};

// Sizes (exported as gauss_core.SIZE_LIMITS and written to core_facts.json). A style's preferred
// normals: set-up is O(K log K) up to this many (normal_field.h); bigger sets are refused with a
// message that points to gauss_core.merge_directions. Rings: their weights are solved densely (R by R).
inline constexpr int max_style_normals = 100000;
inline constexpr int max_style_rings = 256;

// The style every face has until set_styles() says otherwise, and the add-on's default slot preset.
inline constexpr const char* default_preset = "cube";

// The Sheet Metal style (preset "sheet_metal", developable_normals.h) turns each normal by a small angle
// onto its neighbourhood's great circle, a far weaker pull than a turn to a fixed direction: it needs a
// sharper bump (its preset's sigma) and a much stronger lambda (what gauss_bench runs it at) to unbend a
// mesh; the lambda is the lowest round one at which the developability falls tenfold on the corpus's
// bunny, Spot and armadillos, since a stronger one only loses more of the shape. Measured:
// docs/styles.md#sheet-metal.
inline constexpr double sheet_metal_sigma = 16.0;
inline constexpr double sheet_metal_lambda = 200.0;

// Limits on the input rather than settings (no default): beyond them the arithmetic would overflow.
// Coordinates of vertices that faces use: within +-max_coordinate (near 1e308 the output
// x * scale + center overflows to infinity).
inline constexpr double max_coordinate = 1e200;
// Pin targets and the vertices set_vertices() takes: within max_pin_distance times the mesh's size of
// its centre (beyond ~1e150 sizes, squared edge lengths overflow and E_ARAP turns infinite).
inline constexpr double max_pin_distance = 1e12;

// --- How gauss_core.Solver binds the solver (cpp/python/solver_bindings.cpp walks these tables). ---
//
// A setting row: the setting (its name, default, doc and limits above) with the solver's getter and
// setter of it. Python gets a keyword-only argument of Solver() with the setting's default, applied by
// the setter after the set-up (and checked before it), and a property of the same name whose doc is
// the setting's. Value is the setter's type: double or int for a Setting, bool for an Option, the
// Method enum for the Choice. Rows are names, never positions, so no two settings can be swapped.
template <class Solver, class Descriptor, class Value>
struct SettingRow {
  const Descriptor* setting;
  Value (Solver::*get)() const;
  void (Solver::*set)(Value);
};
template <class Solver, class Descriptor, class Value>
constexpr SettingRow<Solver, Descriptor, Value> row(const Descriptor& setting, Value (Solver::*get)() const,
                                                    void (Solver::*set)(Value)) {
  return {&setting, get, set};
}

// A read-out row: a read-only property of Solver that returns the getter's value.
template <class Solver, class Value>
struct ReadoutRow {
  const char* name;  // the Python name
  Value (Solver::*get)() const;
  const char* doc;
};
template <class Solver, class Value>
constexpr ReadoutRow<Solver, Value> readout(const char* name, Value (Solver::*get)() const, const char* doc) {
  return {name, get, doc};
}

// Every setting of the solver, in the order Solver()'s keywords list and apply them. A template so that
// this header needs no solver: the bindings instantiate it with GaussSolver (gauss_solver.h).
template <class Solver>
constexpr auto solver_settings() {
  return std::make_tuple(row(lambda, &Solver::lambda, &Solver::set_lambda),
                         row(admm_iterations, &Solver::admm_iterations, &Solver::set_admm_iterations),
                         row(method, &Solver::method, &Solver::set_method),
                         row(cubic_lambda, &Solver::cubic_lambda, &Solver::set_cubic_lambda),
                         row(tolerance, &Solver::tolerance, &Solver::set_tolerance),
                         row(keep_volume, &Solver::keep_volume, &Solver::set_keep_volume),
                         row(acceleration, &Solver::acceleration, &Solver::set_acceleration),
                         row(avoid_self_intersections, &Solver::avoid_self_intersections,
                             &Solver::set_avoid_self_intersections),
                         row(resolution_independent, &Solver::resolution_independent,
                             &Solver::set_resolution_independent),
                         row(weigh_finer_faces, &Solver::weigh_finer_faces, &Solver::set_weigh_finer_faces),
                         row(square_flat_regions, &Solver::square_flat_regions,
                             &Solver::set_square_flat_regions),
                         row(paper_step_any_sigma, &Solver::paper_step_any_sigma,
                             &Solver::set_paper_step_any_sigma));
}

// Every scalar read-out of the solver (arrays, dicts and methods are bound by hand in cpp/python/).
template <class Solver>
constexpr auto solver_readouts() {
  return std::make_tuple(
      readout("last_reldv", &Solver::last_reldv,
              "reldV of the last step: its largest coordinate change over the largest coordinate displacement\n"
              "from the rest mesh. inf before the first step and after any change of the settings, styles, pins\n"
              "or vertices: a change leaves the run unconverged until a step says otherwise."),
      readout("converged", &Solver::converged,
              "last_reldv < tolerance: the last step moved the mesh by less than the tolerance, and nothing\n"
              "changed since; False while held_back."),
      readout("held_back", &Solver::held_back,
              "The run stopped moving because avoid_self_intersections holds it, not because it converged: the\n"
              "last step moved less than the tolerance, but with what the guard held back of its vertices\n"
              "(held_vertices) it may have moved the tolerance or more. step_until stops here as at convergence."),
      readout("held_vertices", &Solver::held_vertices,
              "Vertices avoid_self_intersections held back in the last step or pin move (0 when it is off)."),
      readout("step_count", &Solver::step_count, "Steps since the set-up or the last reset()."),
      readout("runaway_steps", &Solver::runaway_steps,
              "Steps since the set-up or the last reset() whose result ran away (far past the mesh, its pins and\n"
              "the last set_vertices) and that were redone as plain ARAP steps. Only meshes with strongly\n"
              "negative cotangent weights do this (docs/robustness.md)."),
      readout("factorization_count", &Solver::factorization_count,
              "Factorizations so far: 1 after the set-up, one more per set_pins()."),
      readout("num_vertices", &Solver::num_vertices, "#V: the rows of V."),
      readout("num_faces", &Solver::num_input_faces, "#F: the rows of F."),
      readout("arap_energy", &Solver::arap_energy, "E_ARAP of the current mesh (normalized frame)."),
      readout("g_energy", &Solver::g_energy, "E_g = sum over styled faces of g(n_f)."),
      readout("cubic_admm_iterations", &Solver::cubic_admm_iterations,
              "ADMM iterations of the last cubic step, summed over the vertices."),
      readout("cubic_energy", &Solver::cubic_energy, "sum_i lambda_i |Q_i^T R_i n_i|_1 of the last cubic step."));
}

}  // namespace settings
}  // namespace gauss
