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
// Frames: the solver works on a normalized copy (vertex centroid at the origin, longest bounding-box
// side 1) so that lambda, sigma and mu mean what they mean in the paper; inputs and outputs are in
// the caller's frame.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

#include "gauss/constrained_laplacian.h"
#include "gauss/mesh_topology.h"
#include "gauss/preference_function.h"
#include "gauss/settings.h"
#include "gauss/thread_tuner.h"

namespace gauss {

struct StepTimings {  // milliseconds spent in each phase of the last step
  // faces: initialization with the first ADMM round's normal update; admm: the edge update and any
  // later rounds; rhs: Eq. 27's right-hand side; solve: the triangular solves and re-centring.
  double faces = 0, rotations = 0, admm = 0, rhs = 0, solve = 0;
  int threads = 1;  // threads the step ran on (see thread_tuner.h and parallel.h)
};

class GaussSolver {
 public:
  // V: num_vertices by 3 row-major coordinates (those of vertices that faces use within
  // +-settings::max_coordinate); F: num_faces by 3 row-major vertex indices.
  // pinned: #P distinct vertex indices; pin_positions: #P by 3 targets (nullptr: the rest positions),
  // within settings::max_pin_distance times the mesh's size of it. lambda: settings::lambda.
  // Throws std::invalid_argument on bad input (message says what is wrong).
  GaussSolver(const double* V, int num_vertices, const int64_t* F, int num_faces,
              const std::vector<int64_t>& pinned = {}, const double* pin_positions = nullptr,
              double lambda = settings::lambda.default_value);

  // --- Styles: take effect at the next step, never re-factor. ---
  // Default: one style, default_style() (presets.h), on every face.
  void set_styles(std::vector<PreferenceFunction> styles);
  void set_style(int index, PreferenceFunction style);
  // Per input face: index into the style list, or -1 for an unstyled face (pure ARAP).
  void set_face_styles(const int64_t* style_of_input_face, int count);
  int num_styles() const { return static_cast<int>(styles_.size()); }

  // --- Parameters: lambda only scales Eq. 27's right-hand side, so only set_pins() re-factors. ---
  void set_lambda(double lambda);
  double lambda() const { return lambda_; }
  // A new set of pins (as in the constructor); re-factors. The pins move to their targets now.
  void set_pins(const std::vector<int64_t>& pinned, const double* pin_positions = nullptr);
  // New targets for the current pins, without re-factoring: pin_positions is count by 3, in the order
  // of pinned(), count == #P, each target finite and within settings::max_pin_distance mesh sizes. The pins
  // move to their targets now; the rest of the mesh follows at the next step. Throws
  // std::invalid_argument (and changes nothing) otherwise.
  void set_pin_positions(const double* pin_positions, int count);
  const std::vector<int64_t>& pinned() const { return pinned_input_; }             // #P, caller's numbering
  const std::vector<Eigen::Vector3d>& pin_positions() const { return pin_targets_; }  // #P by 3, caller's frame
  void set_admm_iterations(int n);
  int admm_iterations() const { return admm_iterations_; }

  // One iteration of Algorithm 1.
  void step();
  // Current vertices := rest vertices (pins at their targets); step count := 0.
  void reset();

  // --- Read-outs. ---
  void copy_vertices(double* out) const;  // #V by 3, caller's frame
  void copy_vertices(float* out) const;
  double arap_energy() const;  // E_ARAP of the current mesh with its optimal rotations (normalized frame)
  double g_energy() const;     // E_g = sum over styled faces of g(n_f)
  int step_count() const { return step_count_; }
  int factorization_count() const { return factorization_count_; }
  int num_vertices() const { return topo_.num_vertices; }
  int num_input_faces() const { return num_input_faces_; }
  const StepTimings& last_timings() const { return timings_; }
  long long factor_nonzeros() const { return laplacian_.factor_nonzeros(); }

 private:
  void compute_rest_quantities();
  void face_pass();
  void fit_rotations();  // rotation_ from face_cov_
  void admm_round(bool first_round);
  void assemble_rhs();
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
  MeshTopology topo_;
  int num_input_faces_ = 0;
  std::vector<Eigen::Vector3d> input_;  // caller's coordinates, returned verbatim for fixed vertices
  Eigen::Vector3d center_;
  double scale_ = 1.0;
  std::vector<Eigen::Vector3d> rest_, X_;  // normalized frame

  // Rest quantities.
  std::vector<std::array<double, 3>> slot_weight_;    // #F by 3: cot(opposite angle) / 2
  std::vector<std::array<Eigen::Vector3d, 3>> slot_rest_;  // #F by 3: weight * rest edge vector
  std::vector<double> edge_weight_;                  // #E: sum of the slot weights of the edge
  std::vector<std::array<double, 3>> slot_edge_weight_;  // #F by 3: edge_weight_ of each slot (locality)

  // Styles.
  std::vector<PreferenceFunction> styles_;
  std::vector<int> face_style_;  // #F (solver faces), -1 = unstyled

  // Parameters, constraints and the global step's system.
  double lambda_ = settings::lambda.default_value;
  int admm_iterations_ = static_cast<int>(settings::admm_iterations.default_value);
  std::vector<int64_t> pinned_input_;                // caller's numbering
  std::vector<Eigen::Vector3d> pin_targets_;         // caller's frame (returned verbatim)
  ConstrainedLaplacian laplacian_;                   // internal numbering, normalized frame
  int factorization_count_ = 0;

  // Per-step buffers (allocated once).
  std::vector<Eigen::Vector3d> normal_star_;                 // #F
  std::vector<std::array<double, 3>> dual_;                  // #F by 3 (u_fij, w.r.t. lo->hi edges)
  std::vector<double> face_mu_;                              // #F: mu, 0 if unstyled or degenerate
  std::vector<Eigen::Vector3d> edge_star_;                   // #E (lo -> hi)
  std::vector<Eigen::Matrix3d> face_cov_;                    // #F: sum_k w e_k ehat_k^T
  std::vector<Eigen::Matrix3d> rotation_;                    // #V
  std::vector<Eigen::Quaterniond> rotation_q_;               // #V: warm start of the rotation fit
  std::vector<std::array<Eigen::Vector3d, 3>> corner_rhs_;   // #F by 3
  StepTimings timings_;
  ThreadTuner tuner_;
  int step_count_ = 0;
};

}  // namespace gauss
