#pragma once
// Every solver setting's default and hard limits, written once.
//
// Everything else derives from this table: the solver's and the preference function's input checks,
// the Python module's keyword defaults and its exports gauss_core.DEFAULTS / gauss_core.LIMITS, and
// through those the Blender add-on's properties (default, hard range), validation and panel. The build
// also writes the table to the add-on's core_facts.json (tools/gauss_facts.cpp), which the add-on reads
// when the native module cannot be loaded, so saved settings still register with the right defaults.
//
// Limits are inclusive. They are where a setting stops being useful, kept well inside where the
// arithmetic would overflow (lambda and mu multiply squared edge lengths; sigma is an exponent).
#include <sstream>
#include <stdexcept>
#include <string>

namespace gauss {

struct Setting {
  const char* name;   // the Python name (Solver keyword / Style keyword / add-on property)
  const char* label;  // how error messages call it
  double default_value;
  double min, max;
  bool integer;

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
};

namespace settings {

// lambda of Eq. 27: how strongly edges follow the preferred normals.
inline constexpr Setting lambda{"lam", "lambda", 4.0, 0.0, 1e4, false};
// sigma of Eq. 9: concentration of each preferred normal's bump on the Gauss sphere.
inline constexpr Setting sigma{"sigma", "sigma", 4.0, 1e-3, 1e3, false};
// mu: weight of -mu * g(n_f) for a style's faces, relative to the other styles and to ARAP.
inline constexpr Setting mu{"mu", "mu", 1.0, 0.0, 1e3, false};
// Weight of a ring style's discrete (axis) normals relative to its rings.
inline constexpr Setting axis_contribution{"axis_contribution", "axis_contribution", 0.5, 0.0, 1.0, false};
// ADMM rounds per step (Algorithm 1's inner loop).
inline constexpr Setting admm_iterations{"admm_iterations", "ADMM iterations", 1, 1, 100, true};
// lambda of the cubic method (Cubic Stylization, Liu & Jacobson 2019): the weight of its term
// lambda * a_i * ||R_i n_i||_1 against ARAP in a unit bounding box; 0.2 is the reference
// implementation's default. Gauss's lambda (above) weighs another energy, so each method has its own.
inline constexpr Setting cubic_lambda{"cubic_lambda", "cubic lambda", 0.2, 0.0, 100.0, false};

// Stylization methods, by the names gauss_core takes (Solver(method=...)): the paper's "gauss" and
// Cubic Stylization's "cubic" (cubic_local_step.h). A new method is appended, never reordered: the
// add-on's enum stores these positions in saved files.
inline constexpr const char* method_names[] = {"gauss", "cubic"};
inline constexpr const char* default_method = "gauss";

// A run has converged when a step moved the mesh by less than this relative change, reldV
// (fixed_point_iteration.h): the largest coordinate change of the step over the largest coordinate
// displacement from the rest mesh (the stopping rule of the reference cubic stylization code).
// Below 1e-5 the rounding floor of reldV is too close (a still mesh reads ~4e-7).
inline constexpr Setting tolerance{"tolerance", "tolerance", 1e-3, 1e-5, 1.0, false};

inline constexpr const Setting* all[] = {&lambda,          &sigma,        &mu,       &axis_contribution,
                                         &admm_iterations, &cubic_lambda, &tolerance};

// Keep Volume (volume_keeper.h): after each step, scale every component back to its rest volume (closed)
// or area (open), since stylization shrinks a mesh. Off by default, as the paper's method does not rescale.
inline constexpr Option keep_volume{"keep_volume", false};

// Accelerate the iteration (fixed_point_iteration.h): the same result in about a third of the steps.
inline constexpr Option acceleration{"acceleration", true};

// Avoid Self-Intersections (self_intersection.h): no step brings two faces into contact that were not
// at the start; vertices that would are held back. Off by default: the paper's method does not look.
inline constexpr Option avoid_self_intersections{"avoid_self_intersections", false};

inline constexpr const Option* options[] = {&keep_volume, &acceleration, &avoid_self_intersections};

// The acceleration's parameters per method (fixed_point_iteration.h): the momentum factor beta, and for
// how many steps a vertex whose step turned against its momentum goes without it, so that flapping
// sliver regions are not kicked further. The cubic method's iteration carries its ADMM state and creeps
// more slowly, so a stronger momentum and no hold serve it best: the fastest to the same converged share
// on the bunny, Spot and the armadillo (docs/performance.md). The Gauss method needs its hold to keep the
// plain iteration's converged share: without it the 43K armadillo stops after 60 steps at 0.820, where
// the plain iteration reaches 0.833 in 126 steps and the hold 0.836; on the 35K bunny and Spot the
// shares agree within 0.002 either way.
// stop_factor: an extrapolated step's reldV counts as measured / stop_factor. Measured from the
// extrapolated point, the cubic method's step (its ADMM warm-started from an extrapolated state too)
// understates how far the shape still moves: at a factor of 1 the 43K armadillo stopped at a share of
// 0.434 at lambda 0.4, where the plain iteration converges to 0.471 (the reference: 0.462), and at
// 0.578 instead of 0.604 at lambda 0.8. At 0.7 every mesh and lambda we measured (armadillo 43K and
// 14.5K, bunny 35K and 6K, Spot; lambda 0.2, 0.4, 0.8) stops within 0.01 of the plain iteration's
// share, in 5 to 15 times fewer steps (docs/performance.md). The Gauss method's accelerated stop
// already agrees with its plain one.
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

// Limits on the input rather than settings (no default): beyond them the arithmetic would overflow.
// Coordinates of vertices that faces use: within +-max_coordinate (near 1e308 the output
// x * scale + center overflows to infinity).
inline constexpr double max_coordinate = 1e200;
// Pin targets and the vertices set_vertices() takes: within max_pin_distance times the mesh's size of
// its centre (beyond ~1e150 sizes, squared edge lengths overflow and E_ARAP turns infinite).
inline constexpr double max_pin_distance = 1e12;

}  // namespace settings
}  // namespace gauss
