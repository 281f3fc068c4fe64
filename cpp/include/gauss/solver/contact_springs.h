#pragma once
// Contact springs: the global step's side of Avoid Self-Intersections (self_intersection.h is the
// other side). The guard only clips a step's result; where the style presses whole limbs into the
// body, the global step, which knows nothing of the contact, pushed them in again at every step, the
// guard clipped them again, and the run stalled far from the style (docs/performance.md#avoiding-self-intersections).
// Here every vertex the guard held back gets a plane spring: towards the plane through where the guard
// left it (p_i), normal to the vertex's surface normal n_i there (the contact's normal: surfaces pressed
// together meet face to face), added to the global step's system:
//   minimize  x^T L x / 2 - b^T x + sum_i w_i (n_i . (x_i - p_i))^2 / 2,
// so the rest of the mesh is solved knowing that the held vertices do not go further in, while they
// stay free to slide along the contact (a spring towards p_i itself stuck them: measured in
// docs/performance.md#contact-springs).
//
// The factored L_ff is kept: with P the held unknowns' columns of the identity and K = diag(w_i n_i
// n_i^T), the solution is x = L^-1 (b + P f), where the springs' forces f = K (p - P^T x), each along its
// n_i, solve the small system (K^+ + P^T L^-1 P) f = K K^+ (p - P^T L^-1 b) in the span of the normals.
// That system is symmetric positive definite there and is solved by conjugate gradients, each
// iteration one solve with the existing factor (the three coordinates together), warm-started from
// the last step's forces: the contact changes little from step to step. An iteration only reads the
// springs' rows of its solve, so where the springs are few it solves only on the elimination tree's
// paths above them (cholesky_solver.h: plan_sparse); the step's solution is then one whole solve with
// the forces on the right-hand side. Where the springs are many, each iteration solves whole, and the
// solution is summed up from those solves as the forces are. No re-factorization, and with no spring
// the global step is the plain one, bit for bit.
//
// A spring stays kKeepSteps steps after its vertex was last held, so that a contact the springs keep
// apart (the guard then holds nothing there) does not let go at once and press in again.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "gauss/mesh/mesh_topology.h"
#include "gauss/solver/constrained_laplacian.h"

namespace gauss {

class ContactSprings {
 public:
  // A spring's stiffness w_i, in units of L_ff's diagonal at its vertex (the sum of its edge weights).
  // 1: on the 14.6K armadillo stiffer springs (4) reached the same share with more iterations, softer
  // (0.25) a lower share (docs/performance.md#contact-springs).
  static constexpr double kDefaultStiffness = 1.0;
  static constexpr int kKeepSteps = 10;
  // The conjugate gradients stop at this residual relative to the right-hand side, or after
  // kMaxIterations (each a solve with the factor). 1e-2, because the next step corrects what this one
  // leaves: on the 14.6K armadillo 1e-4 took 20 iterations a step against 9, for the same share. 3e-2
  // took the watertight bunny under Tetrahedron at lambda 20 from 20 to 12, but on a sphere held almost
  // whole it stopped with an error 2.6 times the springs' whole effect (the dense-solve test of
  // test_contact_springs.cpp; docs/performance.md#contact-springs).
  static constexpr double kTolerance = 1e-2;
  static constexpr int kMaxIterations = 40;
  // The iterations solve above the springs only (cholesky_solver.h's plan) when that is less than
  // this share of the factor: it runs on two threads only where the plan reaches far enough into both
  // parts of the factor's cut (CholeskySolver::plan_splits), the whole solve on two wherever the
  // factor is not small.
  static constexpr double kPlannedShare = 0.5;

  // Bytes the springs may hold for a mesh of this many vertices: the per-vertex slot and two
  // buffers of the unknowns (the per-spring arrays come on top, as many as vertices are held).
  static int64_t bytes_needed(int64_t num_vertices) { return (4 + 2 * 24) * num_vertices; }

  void set_stiffness(double stiffness) { stiffness_ = stiffness; }
  double stiffness() const { return stiffness_; }
  // Forgets every spring (the pins and with them the unknowns changed, or the run starts anew).
  void clear();
  // After a guarded step: `held` (solver numbering) were held back, and X is the step's result. Held
  // vertices that are unknowns of L get (or renew) a spring towards the plane through X[v] normal to
  // the vertex's normal at X; springs whose vertex was not held for kKeepSteps steps go.
  void note_held(const std::vector<int>& held, const std::vector<Eigen::Vector3d>& X, const ConstrainedLaplacian& L,
                 const MeshTopology& topo);
  bool active() const { return !vertex_.empty() && stiffness_ > 0; }
  int count() const { return static_cast<int>(vertex_.size()); }
  // L's right-hand side set (L.set_rhs): solves the system with the springs and writes X as L.solve() does.
  void solve(ConstrainedLaplacian& L, std::vector<Eigen::Vector3d>& X);
  // Conjugate-gradient iterations of the last solve() (each one solve with the factor), and whether
  // they solved with the whole factor (else on the plan above the springs).
  int last_iterations() const { return iterations_; }
  bool last_solved_whole() const { return !planned_; }

 private:
  double stiffness_ = kDefaultStiffness;
  std::vector<int> slot_of_vertex_;      // #V: the vertex's spring, -1 without
  std::vector<int> vertex_, unknown_;    // per spring
  std::vector<Eigen::Vector3d> anchor_;  // per spring: p (normalized frame, after the solve's shift)
  std::vector<int> idle_;                // per spring: steps since its vertex was last held
  std::vector<Eigen::Vector3d> force_;   // per spring: f of the last solve (the warm start)
  std::vector<Eigen::Vector3d> normal_;  // per spring: its vertex's unit normal when it was last held
  // Per spring, the conjugate gradients' vectors and its row (elimination order); per unknown (by 3,
  // elimination order) L^-1 b (where the iterations solve whole, then L^-1 (b + P f) as f grows) and
  // one solve's buffer; the supernodes above the springs' rows. Kept:
  // a step allocates nothing once they have grown.
  std::vector<Eigen::Vector3d> target_, residual_, direction_, preconditioned_, applied_, reached_;
  std::vector<int> rows_, plan_;
  std::vector<double> base_, work_;
  bool planned_ = false;
  int iterations_ = 0;
};

}  // namespace gauss
