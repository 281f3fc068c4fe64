// GaussSolver between steps: styles, parameters and pins. Everything here takes effect at the next
// step; only set_pins() re-factors (see constrained_laplacian.h).
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "gauss/gauss_solver.h"
#include "gauss/settings.h"

namespace gauss {

using Eigen::Vector3d;

void GaussSolver::set_styles(std::vector<PreferenceFunction> styles) {
  for (int s : face_style_)
    if (s >= static_cast<int>(styles.size())) {
      std::ostringstream msg;
      msg << "faces use style " << s << " but only " << styles.size()
          << " styles were given; assign face styles that fit the new list first";
      throw std::invalid_argument(msg.str());
    }
  styles_ = std::move(styles);
}

void GaussSolver::set_style(int index, PreferenceFunction style) {
  if (index < 0 || index >= num_styles()) {
    std::ostringstream msg;
    msg << "style index " << index << " is out of range (there are " << num_styles() << " styles)";
    throw std::invalid_argument(msg.str());
  }
  styles_[index] = std::move(style);
}

void GaussSolver::set_face_styles(const int64_t* style_of_input_face, int count) {
  if (count != num_input_faces_) {
    std::ostringstream msg;
    msg << "face styles must have one entry per face (" << num_input_faces_ << "), got " << count;
    throw std::invalid_argument(msg.str());
  }
  for (int i = 0; i < count; ++i)
    if (style_of_input_face[i] < -1 || style_of_input_face[i] >= num_styles()) {
      std::ostringstream msg;
      msg << "face " << i << " has style " << style_of_input_face[i] << "; valid: -1 (unstyled) to "
          << num_styles() - 1;
      throw std::invalid_argument(msg.str());
    }
  for (size_t f = 0; f < topo_.faces.size(); ++f)
    face_style_[f] = static_cast<int>(style_of_input_face[topo_.input_face[f]]);
}

void GaussSolver::set_lambda(double lambda) {
  settings::lambda.check(lambda);
  // Eq. 27: lambda only scales the right-hand side, so the factor stays valid.
  lambda_ = lambda;
}

void GaussSolver::set_admm_iterations(int n) {
  settings::admm_iterations.check(n);
  admm_iterations_ = n;
}

std::vector<Vector3d> GaussSolver::checked_pin_targets(const std::vector<int64_t>& pinned,
                                                       const double* positions) const {
  const int nV = topo_.num_vertices;
  std::vector<Vector3d> targets(pinned.size());
  std::vector<uint8_t> seen(nV, 0);
  for (size_t i = 0; i < pinned.size(); ++i) {
    const int64_t v = pinned[i];
    if (v < 0 || v >= nV) {
      std::ostringstream msg;
      msg << "pinned vertex index " << v << " is out of range (the mesh has " << nV << " vertices)";
      throw std::invalid_argument(msg.str());
    }
    if (seen[v]++) {
      std::ostringstream msg;
      msg << "vertex " << v << " is pinned more than once";
      throw std::invalid_argument(msg.str());
    }
    targets[i] = positions ? Vector3d(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2])
                           : input_[new_of_old_[v]];
    if (!targets[i].allFinite()) {
      std::ostringstream msg;
      msg << "the target of pinned vertex " << v << " is NaN or infinite";
      throw std::invalid_argument(msg.str());
    }
    if (!((targets[i] - center_).cwiseAbs().maxCoeff() <= settings::max_pin_distance * scale_)) {
      std::ostringstream msg;
      msg << "the target of pinned vertex " << v << " is too far from the mesh (more than "
          << settings::max_pin_distance << " times its size)";
      throw std::invalid_argument(msg.str());
    }
  }
  return targets;
}

std::vector<Vector3d> GaussSolver::to_solver_frame(const std::vector<Vector3d>& caller) const {
  std::vector<Vector3d> out(caller.size());
  for (size_t i = 0; i < caller.size(); ++i) out[i] = (caller[i] - center_) / scale_;
  return out;
}

void GaussSolver::set_pins(const std::vector<int64_t>& pinned, const double* pin_positions) {
  std::vector<Vector3d> targets = checked_pin_targets(pinned, pin_positions);
  std::vector<int64_t> internal(pinned.size());
  for (size_t i = 0; i < pinned.size(); ++i) internal[i] = new_of_old_[pinned[i]];
  laplacian_ = ConstrainedLaplacian(topo_, edge_weight_, rest_, internal, to_solver_frame(targets));
  ++factorization_count_;
  pinned_input_ = pinned;
  pin_targets_ = std::move(targets);
  laplacian_.place_pins(X_);
}

void GaussSolver::set_pin_positions(const double* pin_positions, int count) {
  if (count != static_cast<int>(pinned_input_.size()) || (count > 0 && pin_positions == nullptr)) {
    std::ostringstream msg;
    msg << "pin positions must have one row per pinned vertex (" << pinned_input_.size() << "), got " << count;
    throw std::invalid_argument(msg.str());
  }
  std::vector<Vector3d> targets = checked_pin_targets(pinned_input_, pin_positions);
  laplacian_.set_pin_positions(to_solver_frame(targets));
  pin_targets_ = std::move(targets);
  laplacian_.place_pins(X_);
}

}  // namespace gauss
