#pragma once
// Preference function g on the Gauss sphere (paper Sec. 3.1): a von Mises-Fisher mixture over
// discrete preferred normals (Eq. 9) plus optional "circle" terms for cylinder/cone styles (Eq. 13).
//
// Numerics: every exponential is evaluated with its maximum folded into the weights,
//   w_k exp(sigma (x.n_k))           == w'_k exp(sigma (x.n_k - 1)),   w'_k = w_k e^sigma
//   w_r exp(sigma (1 - (x.a - d)^2)) == w'_r exp(-sigma (x.a - d)^2),  w'_r = w_r e^sigma
// so no term exceeds its weight and g, grad g, Hess g stay finite for any sigma > 0.
#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "gauss/style/example_normals.h"
#include "gauss/style/normal_field.h"
#include "gauss/settings.h"

namespace gauss {

// What a style prefers. directions: fixed normals and rings on the sphere (every preset but one).
// developable ("sheet metal"): no fixed directions; each face prefers the normal its neighbourhood
// suggests (GaussSolver works it out before each step: its own normal turned onto the great circle of
// its neighbours' normals, so the surface bends about one axis at a time), and g is one bump of the
// style's sigma around that normal.
// gauss_map: an example's whole Gauss map (its face normals with their areas, ExampleNormals). Up to
// kExactNormals of them, if Eq. 10 weighs every one positively (they are far enough apart), g sums them
// all with those weights times their pulls, as a directions style. Otherwise each face prefers the one
// example normal nearest to its normal at the start of the step, and g is that normal's bump weighted by
// its pull (Liu & Jacobson's snapping; docs/styles.md#gauss-map says what the alternatives did).
enum class StyleKind { directions, developable, gauss_map };

struct StyleParams {
  // Preferred unit normals before rotation (#K by 3); may be empty if rings are given; empty for a
  // developable style; the example's face normals for a gauss_map style.
  std::vector<Eigen::Vector3d> normals;
  // gauss_map only: the example's area at each normal (#K, >= 0), or empty for equal areas.
  std::vector<double> areas;
  // Circle terms: normals x with x.axis == d for each d in ring_offsets (|d| < 1).
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  std::vector<double> ring_offsets;
  // Weight of the discrete normals relative to the rings (only used when rings exist).
  double axis_contribution = settings::axis_contribution.default_value;
  double sigma = settings::sigma.default_value;  // concentration of every term
  double mu = settings::mu.default_value;        // weight of -mu * g in the energy
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // orientation on the Gauss sphere
  StyleKind kind = StyleKind::directions;  // last, so that aggregate initializations keep their order
};

// g with its weights solved so that g(n_k) = 1 at every discrete normal (Eq. 10) and g = 1 on every
// ring (the ring weights solved among themselves, as for the double cone in the paper).
//
// Up to kExactNormals discrete normals (every preset, small custom sets) the weights are solved
// exactly and every term is summed. More normals (up to settings::max_style_normals) go through a
// NormalField: a lattice where they cover the sphere densely, near-parallel ones merged elsewhere,
// weights solved sparsely, only the terms near x summed, within the tolerances normal_field.h states.
class PreferenceFunction {
 public:
  // Throws std::invalid_argument with a readable message on nonsense parameters.
  explicit PreferenceFunction(const StyleParams& params);

  static constexpr int kExactNormals = 64;

  double value(const Eigen::Vector3d& x) const;
  // Value, gradient (Eq. 11, 14) and Hessian (Eq. 12, 15) of g at x in one pass. A developable style
  // has no fixed directions: its g is the bump around x's own direction, exp(sigma (|x| - 1)) (1 on the
  // sphere), what a face on a flat patch is offered.
  void evaluate(const Eigen::Vector3d& x, double& g, Eigen::Vector3d& grad,
                Eigen::Matrix3d& hess) const;
  // The same for a face whose neighbourhood prefers the unit normal `preferred`: a developable style's
  // bump exp(sigma (x.p - 1)) around p; a gauss_map style's bump pull_k exp(sigma (x.e_k - 1)) around the
  // example normal e_k nearest to p; a directions style ignores `preferred`. A gauss_map style without
  // `preferred` (the one-argument evaluate) takes the one nearest to x.
  void evaluate(const Eigen::Vector3d& x, const Eigen::Vector3d& preferred, double& g, Eigen::Vector3d& grad,
                Eigen::Matrix3d& hess) const;

  StyleKind kind() const { return kind_; }
  bool developable() const { return kind_ == StyleKind::developable; }
  // Does g depend on a normal given per face (evaluate with `preferred`)?
  bool anchored() const { return kind_ != StyleKind::directions; }
  // The example of a gauss_map style (normals rotated), or nullptr.
  const ExampleNormals* example() const { return example_.get(); }

  double sigma() const { return sigma_; }
  double mu() const { return mu_; }
  const std::vector<Eigen::Vector3d>& normals() const { return normals_; }  // rotated
  const Eigen::Vector3d& axis() const { return axis_; }                      // rotated
  const Eigen::Matrix3d& rotation() const { return rotation_; }              // the orientation given
  const std::vector<double>& ring_offsets() const { return offsets_; }
  bool has_rings() const { return !offsets_.empty(); }
  // How far apart its bumps are: sigma (1 - cos of the smallest angle between two preferred normals),
  // so that each bump has fallen to e^-separation of its peak at its nearest neighbour's centre;
  // infinity for a single normal, 0 for many normals (a NormalField) and for the other kinds.
  double separation() const { return separation_; }
  // The many-normals representation, or nullptr when the normals are summed exactly.
  const NormalField* field() const { return field_.get(); }

 private:
  std::vector<Eigen::Vector3d> normals_;
  std::vector<double> normal_weights_;  // w'_k, axis contribution already folded in
  // Per normal: n (3), the upper triangle of n n^T (6) and w'_k, contiguous for the hot loop.
  std::vector<std::array<double, 10>> terms_;
  std::vector<char> second_of_pair_;  // per term: the antipode of the term before it
  double exp_minus_2sigma_ = 0;
  std::shared_ptr<const NormalField> field_;  // shared: styles are copied into every solver
  std::shared_ptr<const ExampleNormals> example_;
  Eigen::Vector3d axis_;
  std::vector<double> offsets_;
  std::vector<double> ring_weights_;    // w'_r
  double sigma_, mu_;
  double separation_ = 0;
  Eigen::Matrix3d rotation_;
  StyleKind kind_;
};

}  // namespace gauss
