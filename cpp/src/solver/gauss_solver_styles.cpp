// GaussSolver's styles and which faces have them: the style list, each face's style or weighted
// blend of styles, and the cubic method's per-vertex strength and orientation derived from them.
// Everything here takes effect at the next step and never re-factors.
#include <algorithm>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "gauss/solver/gauss_solver.h"

namespace gauss {

void GaussSolver::set_styles(std::vector<PreferenceFunction> styles) {
  const int used = highest_face_style();
  if (used >= static_cast<int>(styles.size())) {
    std::ostringstream msg;
    msg << "faces use style " << used << " but only " << styles.size()
        << " styles were given; assign face styles that fit the new list first";
    throw std::invalid_argument(msg.str());
  }
  styles_ = std::move(styles);
  styles_changed();
}

void GaussSolver::set_style(int index, PreferenceFunction style) {
  if (index < 0 || index >= num_styles()) {
    std::ostringstream msg;
    msg << "style index " << index << " is out of range (there are " << num_styles() << " styles)";
    throw std::invalid_argument(msg.str());
  }
  styles_[index] = std::move(style);
  styles_changed();
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
  face_weight_.assign(topo_.faces.size(), 1.0);
  blend_start_.assign(1, 0);
  blend_terms_.clear();
  vertex_weight_.clear();
  vertex_weight_styles_ = 0;
  styles_changed();
}

namespace {

// Throws unless every one of the count weights is a number in [0, 1]; `what` names a row ("face",
// "vertex") for the message.
void check_weights(const double* weights, int rows, int styles, const char* what) {
  for (int64_t i = 0; i < int64_t{rows} * styles; ++i) {
    const double w = weights[i];
    if (!(w >= 0.0 && w <= 1.0)) {  // NaN fails both
      std::ostringstream msg;
      msg << "the weight of " << what << " " << i / styles << " for style " << i % styles << " is " << w
          << "; weights must be numbers from 0 to 1";
      throw std::invalid_argument(msg.str());
    }
  }
}

}  // namespace

void GaussSolver::set_face_weights(const double* face_weights, int num_faces, int num_styles,
                                   const double* vertex_weights, int num_vertices) {
  if (num_faces != num_input_faces_ || num_styles < 0 || num_styles > this->num_styles() ||
      (num_faces > 0 && num_styles > 0 && face_weights == nullptr)) {
    std::ostringstream msg;
    msg << "face weights must have one row per face (" << num_input_faces_ << ") and at most one column per style ("
        << this->num_styles() << "), got " << num_faces << " by " << num_styles;
    throw std::invalid_argument(msg.str());
  }
  if (vertex_weights != nullptr && num_vertices != topo_.num_vertices) {
    std::ostringstream msg;
    msg << "vertex weights must have one row per vertex (" << topo_.num_vertices << ") and as many columns as the "
        << "face weights (" << num_styles << "), got " << num_vertices << " rows";
    throw std::invalid_argument(msg.str());
  }
  check_weights(face_weights, num_faces, num_styles, "face");
  if (vertex_weights != nullptr) check_weights(vertex_weights, num_vertices, num_styles, "vertex");

  const int nF = static_cast<int>(topo_.faces.size());
  std::vector<int> style(nF, -1);
  std::vector<double> weight(nF, 1.0);
  std::vector<int> start(1, 0);
  std::vector<BlendTerm> terms;
  for (int f = 0; f < nF; ++f) {
    const double* row = face_weights + static_cast<int64_t>(topo_.input_face[f]) * num_styles;
    int nonzero = 0, first = -1;
    for (int s = 0; s < num_styles; ++s)
      if (row[s] > 0.0) nonzero += 1, first = first < 0 ? s : first;
    if (nonzero == 1) {
      style[f] = first;
      weight[f] = row[first];
    } else if (nonzero > 1) {
      for (int s = 0; s < num_styles; ++s)
        if (row[s] > 0.0) terms.push_back({s, row[s]});
      style[f] = -2 - (static_cast<int>(start.size()) - 1);
      start.push_back(static_cast<int>(terms.size()));
    }
  }
  std::vector<double> per_vertex;
  if (vertex_weights != nullptr) {
    per_vertex.resize(static_cast<size_t>(num_vertices) * num_styles);
    for (int old = 0; old < num_vertices; ++old)
      for (int s = 0; s < num_styles; ++s)
        per_vertex[static_cast<size_t>(new_of_old_[old]) * num_styles + s] =
            vertex_weights[static_cast<int64_t>(old) * num_styles + s];
  }
  face_style_ = std::move(style);
  face_weight_ = std::move(weight);
  blend_start_ = std::move(start);
  blend_terms_ = std::move(terms);
  vertex_weight_ = std::move(per_vertex);
  vertex_weight_styles_ = vertex_weights != nullptr ? num_styles : 0;
  styles_changed();
}

int GaussSolver::highest_face_style() const {
  int highest = -1;
  for (int s : face_style_) highest = std::max(highest, s);
  for (const BlendTerm& t : blend_terms_) highest = std::max(highest, t.style);
  return highest;
}

void GaussSolver::styles_changed() {
  any_developable_ = std::any_of(styles_.begin(), styles_.end(), [](const PreferenceFunction& g) { return g.developable(); });
  any_anchored_ = std::any_of(styles_.begin(), styles_.end(), [](const PreferenceFunction& g) { return g.anchored(); });
  preferred_normal_.resize(any_anchored_ ? topo_.faces.size() : 0);
  vertex_moment_.resize(any_developable_ ? topo_.num_vertices : 0);
  vertex_ruling_.resize(any_developable_ ? topo_.num_vertices : 0);
  const int blends = static_cast<int>(blend_start_.size()) - 1;
  blend_mu_.assign(blends, 0.0);
  blend_shares_.resize(blend_terms_.size());
  for (int b = 0; b < blends; ++b) {
    double mu = 0;
    for (int i = blend_start_[b]; i < blend_start_[b + 1]; ++i)
      mu += blend_terms_[i].weight * styles_[blend_terms_[i].style].mu();
    blend_mu_[b] = mu;
    for (int i = blend_start_[b]; i < blend_start_[b + 1]; ++i) {
      const BlendTerm& t = blend_terms_[i];
      blend_shares_[i] = {t.style, mu > 0 ? t.weight * styles_[t.style].mu() / mu : 0.0};
    }
  }
  update_cubic_styles();
  if (square_flat_regions_) update_square_prior();  // its pull scales with each face's strength
  iteration_.invalidate();
}

void GaussSolver::update_cubic_styles() {
  if (!cubic_ready_) return;
  const int nV = topo_.num_vertices;
  std::vector<double> strength(nV, 0.0);
  std::vector<int> frame(nV, 0);  // 0: no style (identity), s + 1: style s
  std::vector<Eigen::Matrix3d> frames(1, Eigen::Matrix3d::Identity());
  for (const PreferenceFunction& style : styles_) frames.push_back(style.rotation());
  std::vector<double> vote(styles_.size(), 0.0);  // per style: its weights over the vertex's faces
  std::vector<int> voted;                          // the styles with a vote, to clear them after
  for (int v = 0; v < nV; ++v) {
    const int begin = topo_.vertex_corner_start[v], end = topo_.vertex_corner_start[v + 1];
    if (begin == end) continue;
    double sum = 0;
    // A face's style s of weight w (the face's, or this vertex's own when vertex weights were given).
    const auto add = [&](int s, double face_w) {
      const double w = s < vertex_weight_styles_ ? vertex_weight_[static_cast<size_t>(v) * vertex_weight_styles_ + s]
                                                 : face_w;
      sum += styles_[s].mu() * w;
      if (vote[s] == 0.0 && w > 0.0) voted.push_back(s);
      vote[s] += w;
    };
    for (int i = begin; i < end; ++i) {
      const int f = topo_.vertex_corners[i] / 3, s = face_style_[f];
      if (s >= 0) {
        add(s, face_weight_[f]);
      } else if (s <= -2) {
        for (int k = blend_start_[-2 - s]; k < blend_start_[-1 - s]; ++k) add(blend_terms_[k].style, blend_terms_[k].weight);
      }
    }
    int best = -1;
    for (int s : voted)
      if (best < 0 || vote[s] > vote[best] || (vote[s] == vote[best] && s < best)) best = s;
    for (int s : voted) vote[s] = 0.0;
    voted.clear();
    strength[v] = sum / (end - begin);
    frame[v] = best + 1;
  }
  cubic_.set_vertex_styles(strength, frame, frames);
}

}  // namespace gauss
