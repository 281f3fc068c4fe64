#pragma once
// Gauss stylization (Kohlbrenner et al. 2021): ARAP extended by -mu * sum_f g(n_f), minimized by
// Algorithm 1: an ADMM local step on auxiliary face normals n*_f (normal_step.h) and edges e*_ij, the
// ARAP rotation fit, and a global step against the constrained Laplacian (constrained_laplacian.h),
// which is factored once per set of pins.
//
// Usage (geometry-central style: the constructor does the expensive set-up, methods are cheap):
//   GaussSolver s(V, nV, F, nF);         // normalize, cotangent weights, topology, factorization
//   s.set_styles({PreferenceFunction(preset_style("cube"))});
//   for (...) s.step();                  // no allocation, no sparse look-up, no factorization
//   s.copy_vertices(out);
//
// A second method shares all of that: Cubic Stylization (Liu & Jacobson 2019), whose local step
// (cubic_local_step.h) replaces the ADMM on normals and edges; set_method() switches between them at
// any time, without a new set-up.
//
// Frames: the solver works on a normalized copy (vertex centroid at the origin, longest bounding-box
// side 1) so that lambda, sigma and mu mean what they mean in the paper; inputs and outputs are in
// the caller's frame.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "gauss/collision/self_intersection.h"
#include "gauss/solver/constrained_laplacian.h"
#include "gauss/solver/contact_springs.h"
#include "gauss/solver/cubic_local_step.h"
#include "gauss/solver/developable_normals.h"
#include "gauss/solver/fixed_point_iteration.h"
#include "gauss/solver/flat_regions.h"
#include "gauss/solver/normal_step.h"
#include "gauss/mesh/mesh_topology.h"
#include "gauss/style/preference_function.h"
#include "gauss/util/progress.h"
#include "gauss/settings.h"
#include "gauss/util/thread_tuner.h"
#include "gauss/solver/volume_keeper.h"

namespace gauss {

// The local step a step runs; the numbers are the positions in settings::method_names.
enum class Method { gauss = 0, cubic = 1 };

struct StepTimings {  // milliseconds spent in each phase of the last step
  // faces: initialization with the first ADMM round's normal update; admm: the edge update and any
  // later rounds; rhs: Eq. 27's right-hand side; solve: the triangular solves and re-centring.
  // The cubic method: faces = the face covariances, admm = the per-vertex ADMM with its rotations,
  // rotations = 0. guard: Avoid Self-Intersections' check of the step's result (0 without it).
  double faces = 0, rotations = 0, admm = 0, rhs = 0, solve = 0, guard = 0;
  int threads = 1;  // threads the step ran on (see thread_tuner.h and parallel.h)
};

class GaussSolver {
 public:
  // V: num_vertices by 3 row-major coordinates (those of vertices that faces use within
  // +-settings::max_coordinate); F: num_faces by 3 row-major vertex indices.
  // pinned: #P distinct vertex indices; pin_positions: #P by 3 targets (nullptr: the rest positions),
  // within settings::max_pin_distance times the mesh's size of it. lambda: settings::lambda.
  // progress: optional; reports every SetupPhase (progress.h) and cancels the set-up on request.
  // Throws std::invalid_argument on bad input (message says what is wrong), OutOfMemory
  // (memory_budget.h) if the factorization would not fit in memory, Cancelled.
  GaussSolver(const double* V, int num_vertices, const int64_t* F, int num_faces,
              const std::vector<int64_t>& pinned = {}, const double* pin_positions = nullptr,
              double lambda = settings::lambda.default_value, Progress* progress = nullptr);

  // --- Styles: take effect at the next step, never re-factor. ---
  // Default: one style, default_style() (presets.h), on every face.
  void set_styles(std::vector<PreferenceFunction> styles);
  void set_style(int index, PreferenceFunction style);
  // Per input face: index into the style list, or -1 for an unstyled face (pure ARAP).
  void set_face_styles(const int64_t* style_of_input_face, int count);
  // Per input face, a weight in [0, 1] for each of the first num_styles (<= num_styles()) styles
  // (face_weights: num_faces by num_styles, row-major; the styles after them weigh 0): a face's
  // preference is the weight-scaled sum of its styles', -sum_s w_s mu_s g_s(n_f), so a weight of 0.5
  // stylizes half as strongly and a face whose weights are all 0 is unstyled. A face with one weight
  // of 1 and the rest 0 steps exactly as set_face_styles() with that style makes it, and costs the same.
  // vertex_weights (optional; #V by num_styles, caller's numbering, in [0, 1]): the cubic method's
  // weight of each vertex for each style, which scales its strength (see set_method); without it a
  // vertex takes the weights of its faces. Replaces what set_face_styles() set, and the reverse.
  // Throws std::invalid_argument, changing nothing, on a count that does not fit or a weight that
  // is NaN or outside [0, 1].
  void set_face_weights(const double* face_weights, int num_faces, int num_styles,
                        const double* vertex_weights = nullptr, int num_vertices = 0);
  int num_styles() const { return static_cast<int>(styles_.size()); }

  // --- Parameters: lambda only scales Eq. 27's right-hand side, so only set_pins() re-factors. ---
  void set_lambda(double lambda);
  double lambda() const { return lambda_; }
  // A new set of pins (as in the constructor); re-factors (progress: SetupPhase::ordering onwards).
  // The pins move to their targets now. On any exception, Cancelled included, the solver keeps its
  // previous pins and factor.
  void set_pins(const std::vector<int64_t>& pinned, const double* pin_positions = nullptr,
                Progress* progress = nullptr);
  // New targets for the current pins, without re-factoring: pin_positions is count by 3, in the order
  // of pinned(), count == #P, each target finite and within settings::max_pin_distance mesh sizes. The pins
  // move to their targets now; the rest of the mesh follows at the next step. Throws
  // std::invalid_argument (and changes nothing) otherwise.
  void set_pin_positions(const double* pin_positions, int count);
  const std::vector<int64_t>& pinned() const { return pinned_input_; }             // #P, caller's numbering
  const std::vector<Eigen::Vector3d>& pin_positions() const { return pin_targets_; }  // #P by 3, caller's frame
  void set_admm_iterations(int n);
  int admm_iterations() const { return admm_iterations_; }
  // Keep Volume (settings::keep_volume, volume_keeper.h): after each step, components without a pin
  // are scaled back to their rest volume (closed) or area (open).
  void set_keep_volume(bool on);
  bool keep_volume() const { return keep_volume_; }
  // Acceleration (settings::acceleration, fixed_point_iteration.h): momentum with adaptive restart,
  // with each method's settings::Momentum; the cubic method's carried ADMM state is extrapolated with
  // the vertices. Off: the plain iteration of Algorithm 1. Either way a step ends on a step of the
  // method's local-global iteration.
  void set_acceleration(bool on);
  bool acceleration() const { return iteration_.acceleration(); }
  const settings::Momentum& momentum() const { return iteration_.momentum(); }  // the method's
  // Avoid Self-Intersections (settings::avoid_self_intersections, self_intersection.h): no step and no
  // move of the pins brings two faces into contact that were not in contact at the start (when it is
  // switched on, and after reset() or set_vertices()); vertices that would are held back short of it,
  // and the next global steps hold them there with contact springs (contact_springs.h).
  // Switching it on allocates the guard (std::bad_alloc or OutOfMemory like the set-up).
  void set_avoid_self_intersections(bool on);
  // Resolution Independent (settings::resolution_independent, docs/resolution.md): a bending term on the
  // rotations that gives a mesh finer than the reference the bending stiffness ARAP has at the
  // reference, for both methods, and the preference of a face coarser than the reference weighed by its
  // rest area (the normal step's coupling lambda w_ij scaled by settings::reference_face_area / the
  // face's area). So lambda means the same at any tessellation. Off: the paper's method, bit for bit.
  void set_resolution_independent(bool on);
  bool resolution_independent() const { return resolution_independent_; }
  // settings::weigh_finer_faces: the setting's rule before 2026-12-06, which weighed every face's
  // preference by its area, the finer ones too.
  void set_weigh_finer_faces(bool on);
  bool weigh_finer_faces() const { return weigh_finer_faces_; }
  // settings::paper_step_any_sigma: the paper's normal step at every sigma, as before 2026-12-07; off,
  // the faces of the styles normal_step.h's takes_trust_region_step names (sharper than
  // settings::paper_step_max_sigma, bumps apart) take a trust-region step on the sphere instead.
  void set_paper_step_any_sigma(bool on);
  bool paper_step_any_sigma() const { return paper_step_any_sigma_; }
  // The face area (solver frame) at which Resolution Independent changes nothing; by default
  // settings::reference_face_area. Changeable to measure the choice (gauss_bench --reference-face-area);
  // throws std::invalid_argument unless positive and finite.
  void set_reference_face_area(double area);
  double reference_face_area() const { return reference_face_area_; }
  // Square Flat Regions (settings::square_flat_regions, flat_regions.h): the faces around each large
  // flat region of the rest mesh pull the rotation fit of their vertices towards turning them onto the
  // axes of the region's outline, for both methods, scaled by each face's style strength (mu times its
  // weight). The regions are found when it is switched on. Off: bit for bit as without it.
  void set_square_flat_regions(bool on);
  bool square_flat_regions() const { return square_flat_regions_; }
  // The large flat regions found (empty while the setting is off), solver frame.
  const std::vector<FlatRegion>& flat_regions() const { return square_.regions; }
  bool avoid_self_intersections() const { return guard_ != nullptr; }
  // The guard's contact springs in the global step (contact_springs.h): their stiffness (0: none, the
  // guard alone), how many the last step had, and the conjugate-gradient iterations of its solve.
  void set_contact_stiffness(double stiffness);
  double contact_stiffness() const { return springs_.stiffness(); }
  int contact_springs() const { return springs_.active() ? springs_.count() : 0; }
  int contact_iterations() const { return springs_.active() ? springs_.last_iterations() : 0; }
  // Vertices the guard held back in the last step or pin move (0 when it is off).
  int held_vertices() const { return guard_ ? guard_->last_held() : 0; }
  // Which: held_vertices() vertex indices (caller's numbering, ascending); empty when the guard is off.
  std::vector<int> held_vertex_indices() const;
  // The run has stopped moving because the guard holds it, not because it converged: the last step
  // moved less than the tolerance, but without the guard it may not have. The step's own result is the
  // guarded one plus what the guard denied, so its reldV is at most last_reldv plus the denied part's:
  // only below the tolerance is the run converged whatever the guard did.
  bool held_back() const { return last_reldv() < tolerance_ && last_reldv() + denied_reldv_ >= tolerance_; }

  // --- Method: the next step's local step; pins, styles and the factorization stay. ---
  // The first switch to Method::cubic prepares its per-vertex data (O(#V), no factorization). With it,
  // a style's mu scales cubic_lambda on its faces and its rotation turns the cube; its preferred
  // normals, sigma and lambda are not used. A vertex's strength is the mean over its faces of
  // sum_s w_s mu_s for the face's styles s (unstyled faces count 0), where w_s is the vertex's own
  // weight for s if set_face_weights() was given vertex weights, else the face's; its orientation
  // that of the style whose weights over its faces sum highest (with weights 1: the style most of
  // its faces have; ties: the lower style index).
  void set_method(Method method);
  Method method() const { return method_; }
  void set_cubic_lambda(double lambda);  // settings::cubic_lambda
  double cubic_lambda() const { return cubic_lambda_; }

  // One iteration of the method's local-global step (Algorithm 1 for Gauss), applied at the
  // momentum point when accelerated, then Keep Volume if it is on.
  void step();
  // Steps until a step's reldV is below `tolerance` (settings::tolerance): the run converged() or is
  // held_back(); at most max_steps (>= 0) times; returns the number of steps taken (0 if it already was).
  // Sets tolerance() to `tolerance`. Throws std::invalid_argument (before stepping) on a bad argument.
  int step_until(double tolerance, int max_steps);
  // Current vertices := rest vertices (pins at their targets); step count := 0.
  void reset();
  // Current vertices := V (count by 3, caller's frame and numbering, count == #V): a warm start for
  // the next step, e.g. the previous frame's result in an animation bake. The rest shape, styles and
  // factorization stay; pins stay at their targets and vertices no face uses at their input
  // positions; the step count is kept. What the iteration carried over from earlier steps (the
  // rotation fit's warm start, the bending term's rotations) is made anew: identity as reset() makes
  // it, or with Resolution Independent the rotations of V itself, so the steps that follow depend on
  // V alone.
  // Throws std::invalid_argument, changing nothing, unless every coordinate is finite and every vertex
  // that faces use lies within settings::max_pin_distance times the mesh's size of it.
  void set_vertices(const double* V, int count);

  // --- Convergence (fixed_point_iteration.h). Every edit above (styles, lambda, ADMM rounds, keep
  // volume, pins, their targets, reset, set_vertices) changes the map or the iterate, so it makes
  // last_reldv() +infinity. ---
  double last_reldv() const { return iteration_.last_reldv(); }  // +infinity before the first step
  // The tolerance converged() compares with: settings::tolerance (checked), set here or by step_until().
  void set_tolerance(double tolerance);
  double tolerance() const { return tolerance_; }
  // At rest and not held there by the guard (held_back()).
  bool converged() const { return last_reldv() < tolerance_ && !held_back(); }

  // --- Read-outs. ---
  void copy_vertices(double* out) const;  // #V by 3, caller's frame
  void copy_vertices(float* out) const;
  double arap_energy() const;  // E_ARAP of the current mesh with its optimal rotations (normalized frame)
  double g_energy() const;     // E_g = sum over faces of sum_s w_s g_s(n_f) (w: set_face_weights, else 1)
  int step_count() const { return step_count_; }
  int runaway_steps() const { return runaway_steps_; }
  int factorization_count() const { return factorization_count_; }
  int num_vertices() const { return topo_.num_vertices; }
  int num_input_faces() const { return num_input_faces_; }
  const StepTimings& last_timings() const { return timings_; }
  // The cubic method: ADMM iterations of the last step summed over the vertices (0 before one), and
  // its term sum_i lambda_i ||Q_i^T R_i n_i||_1 with the last step's rotations.
  long long cubic_admm_iterations() const { return cubic_ready_ ? cubic_.last_admm_iterations() : 0; }
  double cubic_energy() const { return cubic_ready_ ? cubic_.cubic_energy(cubic_lambda_, rotation_) : 0.0; }
  long long factor_nonzeros() const { return laplacian_.factor_nonzeros(); }
  // Lean steps keep no per-face scratch, slot rest vectors or slot edge weights (the members' notes
  // below) and compute what they would read of them: 168 bytes a face less (0.7 GB at 2M vertices)
  // for a slower step (15% at 2M). The default from kSinglePrecisionUnknowns vertices up, where the
  // memory is what limits. The results are the same bits either way; tests compare them.
  void set_lean_steps(bool lean);
  bool lean_steps() const { return slot_rest_.empty(); }

 private:
  void compute_rest_quantities();
  void update_face_coupling();  // bending_beta_ from face_area_ and resolution_independent_
  // Slot k of face f (the edge from its corner k to corner k+1): its weight times its rest vector.
  Eigen::Vector3d slot_rest(int f, int k) const {
    if (!slot_rest_.empty()) return slot_rest_[f][k];
    const auto& t = topo_.faces[f];
    return slot_weight_[f][k] * (rest_[t[(k + 1) % 3]] - rest_[t[k]]);
  }
  // Slot k's edge weight (edge_weight_ of its edge).
  double slot_edge_weight(int f, int k) const {
    return slot_edge_weight_.empty() ? edge_weight_[topo_.face_edge[f][k]] : slot_edge_weight_[f][k];
  }
  // The factor of lambda in face f's normal step: 1, or with resolution_independent the reference
  // area over the face's where the face is coarser than the reference (with weigh_finer_faces: on
  // every face; docs/resolution.md).
  double face_coupling(int f) const;
  void update_square_prior();   // square_prior_ from square_ and the faces' styles (when on)
  // set_pins' work inside a set-up that `progress` already reports (the constructor's or set_pins').
  // Moves the pinned vertices to their targets; with the guard on, short of new contacts.
  void place_pins_guarded();
  void apply_pins(const std::vector<int64_t>& pinned, const double* pin_positions, Progress& progress);
  // One local-global step on X_ (Algorithm 1: local step, then the global solve), timing its phases.
  void local_global_step();
  void face_pass();
  // Face f's ARAP covariance sum_k w_k e_k ehat_k^T at X_ (e: its edge vectors there, if at hand).
  Eigen::Matrix3d face_covariance(int f) const;
  Eigen::Matrix3d face_covariance(int f, const Eigen::Vector3d* e) const;
  Eigen::Matrix3d vertex_covariance(int v) const;  // sum of face_covariance over vertex v's faces
  void fit_rotations();  // rotation_ from the faces' covariances
  void fit_rotations_of_start();  // rotation_ of the current vertices alone (set_vertices)
  // With resolution_independent: per vertex, the bending term's sum_j beta_ij w_ij R_j (R of the last
  // step), and with square_flat_regions the squaring pull square_prior_, which the rotation fits add to
  // their covariance; nullptr when both are off.
  const Eigen::Matrix3d* rotation_prior();
  // P += vertex v's row of rotation_prior(), from rotation_, its terms weighed by `factor`
  // (rotation_prior_factor(): the method's).
  void add_rotation_prior(int v, double factor, Eigen::Matrix3d& P) const;
  double rotation_prior_factor() const;
  void admm_round(bool first_round);
  // The global step's right-hand side from rotation_: Eq. 27's (the Gauss method: ARAP's targets and
  // the lambda w e* pull), plain ARAP's over the faces, or the cubic method's (per vertex).
  enum class Rhs { gauss, arap, cubic };
  void assemble_rhs(Rhs terms);
  void assemble_rhs_lean(Rhs terms);  // the same, for lean steps (no face_scratch_ to gather from)
  // Face f's mean rotation (Eq. 27 rotates its slots' rest vectors by it).
  Eigen::Matrix3d face_rotation(int f) const;
  // The Gauss step's guard against running away (docs/robustness.md, "Negative cotangent weights"): the
  // reach box (centre reach_centre_, half its longest side reach_; normalized frame) holds the used rest
  // vertices, the pin targets and the caller's last set_vertices(); a step whose result lies farther
  // than kRunawayReach half-sizes from its centre is redone as a plain ARAP step, which does not read
  // the iterate.
  void update_reach();
  bool ran_away() const;
  // The cubic method's per-vertex strength and orientation from styles_ and the faces' styles.
  void update_cubic_styles();
  // After styles_ or the faces' styles changed: blend_mu_ and blend_shares_ anew, then the cubic
  // method's strengths.
  void styles_changed();
  // The highest style index any face uses (-1 if none).
  int highest_face_style() const;
  // The Gauss method's normal update for face f of style code s (face_style_): newton_normal, or
  // trust_region_normal where takes_trust_region_step says so (normal_step.h).
  Eigen::Vector3d normal_update(int f, int s, const Eigen::Vector3d& n, const Eigen::Vector3d* es, const double* lw,
                                const double* u) const;
  // While a developable or gauss_map style is set: preferred_normal_ from the current vertices (with a
  // developable style: developable_normals.h, for every face; else each face's own normal).
  void update_preferred_normals() const;
  // The targets (caller's frame) of the given pins (#P, caller's numbering) from #P by 3 positions
  // (nullptr: the rest positions); throws unless the pins are distinct vertices and every target is
  // finite and within settings::max_pin_distance times the mesh's size of it.
  std::vector<Eigen::Vector3d> checked_pin_targets(const std::vector<int64_t>& pinned, const double* positions) const;
  std::vector<Eigen::Vector3d> to_solver_frame(const std::vector<Eigen::Vector3d>& caller) const;
  Eigen::Vector3d to_caller(const Eigen::Vector3d& x) const { return x * scale_ + center_; }
  template <typename T>
  void write_vertices(T* out) const;

  // Internally vertices and faces are renumbered for locality (spatial_order.h); every array
  // below is in that numbering, the public interface in the caller's.
  std::vector<int> new_of_old_;
  mutable std::vector<int> old_of_new_;  // its inverse, made by the first held_vertex_indices() call
  MeshTopology topo_;
  int num_input_faces_ = 0;
  std::vector<Eigen::Vector3d> input_;  // caller's coordinates, returned verbatim for fixed vertices
  Eigen::Vector3d center_;
  double scale_ = 1.0;
  std::vector<Eigen::Vector3d> rest_, X_;  // normalized frame

  // Rest quantities.
  // What follows from these in a few operations is computed where it is used (face_coupling(), the
  // bending term's slot weights), or kept only while the steps are not lean (slot_rest(),
  // slot_edge_weight()): at sculpt scale every 8 bytes a face is 32 MB.
  std::vector<std::array<double, 3>> slot_weight_;    // #F by 3: cot(opposite angle) / 2, or cotangent_weights.h's floor
  std::vector<std::array<Eigen::Vector3d, 3>> slot_rest_;  // #F by 3: weight * rest edge vector (not lean)
  std::vector<double> edge_weight_;                  // #E: sum of the slot weights of the edge
  std::vector<std::array<double, 3>> slot_edge_weight_;  // #F by 3: edge_weight_ of each slot (not lean)
  std::vector<double> face_area_;                   // #F: rest area
  std::vector<double> bending_beta_;                 // #V while resolution_independent: beta (else empty)
  std::vector<Eigen::Matrix3d> rotation_prior_;       // #V while either pull is on: the rotation fit's prior
  bool square_flat_regions_ = settings::square_flat_regions.default_value;
  SquareTargets square_;                              // while square_flat_regions: the regions and targets
  std::vector<Eigen::Matrix3d> square_prior_;         // #V while square_flat_regions: sum k w mu t n^T

  // Styles.
  std::vector<PreferenceFunction> styles_;
  // A face's styles: face_style_ s >= 0 is one style of weight face_weight_ (1 unless
  // set_face_weights() gave another), -1 unstyled, and s <= -2 blend b = -2 - s, which has the
  // styles and weights blend_terms_[blend_start_[b] .. blend_start_[b + 1]). Faces with one style,
  // the common case, skip the blend's sum, so they cost what an unblended face does.
  struct BlendTerm {
    int style;
    double weight;
  };
  std::vector<int> face_style_;                 // #F (solver faces)
  std::vector<double> face_weight_;             // #F
  std::vector<int> blend_start_{0};             // #blends + 1
  std::vector<BlendTerm> blend_terms_;
  std::vector<double> blend_mu_;                // #blends: sum_s w_s mu_s (from styles_)
  std::vector<StyleShare> blend_shares_;        // as blend_terms_: the normal update's shares
  std::vector<double> vertex_weight_;           // #V by vertex_weight_styles_ (solver numbering) or empty
  int vertex_weight_styles_ = 0;
  // While a style is developable (sheet metal) or a gauss_map (anchored), sized by styles_changed(): each
  // face's preferred normal, updated before each Gauss step (and by g_energy()), and the per-vertex
  // scratch a developable style makes it with. Empty otherwise. Mutable: g_energy() reads the current
  // mesh's. A gauss_map style looks up the example normal nearest to it.
  bool any_developable_ = false;
  bool any_anchored_ = false;
  mutable std::vector<Eigen::Vector3d> preferred_normal_;   // #F
  mutable std::vector<Eigen::Matrix3d> vertex_moment_;      // #V
  mutable std::vector<Eigen::Vector3d> vertex_ruling_;      // #V

  // Parameters, constraints and the global step's system.
  double lambda_ = settings::lambda.default_value;
  int admm_iterations_ = static_cast<int>(settings::admm_iterations.default_value);
  Method method_ = Method::gauss;
  double cubic_lambda_ = settings::cubic_lambda.default_value;
  CubicLocalStep cubic_;      // prepared by the first set_method(Method::cubic)
  bool cubic_ready_ = false;
  std::vector<int64_t> pinned_input_;                // caller's numbering
  std::vector<Eigen::Vector3d> pin_targets_;         // caller's frame (returned verbatim)
  ConstrainedLaplacian laplacian_;                   // internal numbering, normalized frame
  int factorization_count_ = 0;
  VolumeKeeper volume_;                              // rest sizes of the components without a pin
  bool keep_volume_ = settings::keep_volume.default_value;
  bool resolution_independent_ = settings::resolution_independent.default_value;
  bool weigh_finer_faces_ = settings::weigh_finer_faces.default_value;
  bool paper_step_any_sigma_ = settings::paper_step_any_sigma.default_value;
  double reference_face_area_ = settings::reference_face_area;
  std::unique_ptr<SelfIntersectionGuard> guard_;     // while avoid_self_intersections is on
  std::vector<Eigen::Vector3d> safe_;                // #V while it is on: X before the step
  double denied_reldv_ = 0;                          // the last step's move the guard took back, as reldV
  ContactSprings springs_;                           // while the guard is on: its held vertices' springs
  Eigen::Vector3d reach_centre_ = Eigen::Vector3d::Zero();  // update_reach()
  double reach_ = 1.0;
  int runaway_steps_ = 0;                            // steps redone as plain ARAP since the set-up or reset

  // Per-step buffers (allocated once).
  std::vector<Eigen::Vector3d> normal_star_;                 // #F
  std::vector<std::array<double, 3>> dual_;                  // #F by 3 (u_fij, w.r.t. lo->hi edges)
  std::vector<double> face_mu_;                              // #F: mu, 0 if unstyled or degenerate
  std::vector<Eigen::Vector3d> edge_star_;                   // #E (lo -> hi)
  std::vector<Eigen::Matrix3d> rotation_;                    // #V
  std::vector<Eigen::Quaterniond> rotation_q_;               // #V: warm start of the rotation fit
  // #F, for two phases of a step that never overlap: first each face's ARAP covariance
  // (face_covariance() or the cubic method's, read by the rotation fit), then the right-hand sides
  // of its corners, corner k in column k (assemble_rhs()). One array for both saves a 3x3 block a
  // face (docs/performance.md#set-up-at-scale). Lean steps keep none: the rotation fit and the
  // right-hand side compute what they read of it, three times a face instead of once. The cubic
  // method makes it when it is first set.
  std::vector<Eigen::Matrix3d> face_scratch_;
  StepTimings timings_;
  ThreadTuner tuner_;
  int step_count_ = 0;
  FixedPointIteration iteration_;  // reldV and the acceleration
  double tolerance_ = settings::tolerance.default_value;
};

}  // namespace gauss
