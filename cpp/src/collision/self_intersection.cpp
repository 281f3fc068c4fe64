#include "gauss/collision/self_intersection.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <numeric>

#include "gauss/collision/triangle_intersection.h"
#include "gauss/util/parallel.h"

namespace gauss {

using Eigen::Vector3d;

namespace {

// The pair's key, the same in either order: min * 2^32 + max.
uint64_t pair_key(int f, int g) {
  if (f > g) std::swap(f, g);
  return (static_cast<uint64_t>(f) << 32) | static_cast<uint32_t>(g);
}

// The two faces' corners with their shared corners first, in the same order in both; returns how many
// they share.
int arrange(const std::array<int, 3>& fa, const std::array<int, 3>& fb, const std::vector<Vector3d>& X,
            Triangle& a, Triangle& b) {
  int order_a[3], order_b[3], shared = 0;
  bool used_a[3] = {false, false, false}, used_b[3] = {false, false, false};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (!used_b[j] && fa[i] == fb[j]) {
        order_a[shared] = i;
        order_b[shared] = j;
        used_a[i] = used_b[j] = true;
        ++shared;
        break;
      }
  int ka = shared, kb = shared;
  for (int i = 0; i < 3; ++i) {
    if (!used_a[i]) order_a[ka++] = i;
    if (!used_b[i]) order_b[kb++] = i;
  }
  for (int i = 0; i < 3; ++i) {
    a.col(i) = X[fa[order_a[i]]];
    b.col(i) = X[fb[order_b[i]]];
  }
  return shared;
}

// Collects pair keys from several threads: the pairs found are few, so one lock suffices.
struct PairSink {
  std::mutex mutex;
  std::vector<uint64_t> keys;
  void add(uint64_t key) {
    std::lock_guard<std::mutex> lock(mutex);
    keys.push_back(key);
  }
};

}  // namespace

std::vector<std::array<int, 2>> self_intersecting_pairs(const std::vector<std::array<int, 3>>& faces,
                                                        const std::vector<Vector3d>& X) {
  FaceBvh bvh(faces, X);
  bvh.refit_boxes(X, 0.0);  // every pair is searched: no flat patches needed
  PairSink sink;
  bvh.for_overlapping_pairs([&](int, int f, int g) {
    Triangle a, b;
    const int shared = arrange(faces[f], faces[g], X, a, b);
    if (triangles_cross(a, b, shared)) sink.add(pair_key(f, g));
  }, false);  // every pair: the count is exact, not a guard's
  std::sort(sink.keys.begin(), sink.keys.end());
  std::vector<std::array<int, 2>> pairs(sink.keys.size());
  for (size_t i = 0; i < pairs.size(); ++i)
    pairs[i] = {static_cast<int>(sink.keys[i] >> 32), static_cast<int>(sink.keys[i] & 0xffffffffu)};
  return pairs;
}

int64_t count_self_intersections(const std::vector<std::array<int, 3>>& faces, const std::vector<Vector3d>& X) {
  return static_cast<int64_t>(self_intersecting_pairs(faces, X).size());
}

SelfIntersectionGuard::SelfIntersectionGuard(const MeshTopology& topo, const std::vector<Vector3d>& X0)
    : topo_(&topo),
      bvh_(topo.faces, X0),
      star_kind_(X0.size(), kClosedStar),
      flat_star_(X0.size(), 0),
      patch_corner_(X0.size(), 0),
      candidate_(X0.size()),
      aim_(X0.size()),
      step_fraction_(X0.size(), 1.0f),
      round_stamp_(X0.size(), 0),
      moved_stamp_(topo.faces.size(), 0),
      of_stamp_(topo.faces.size(), 0),
      star_stamp_(X0.size(), 0) {
  // A star is one fan around its corner, closed or open, only if each of its edges has two faces
  // that run along it in opposite directions, but for the open fan's two boundary edges. Two fans
  // sharing one corner (two sheets touching there), a non-manifold edge or faces oriented against
  // each other can cover a point twice with every wedge turning the right way and their angles
  // summing to less than a turn: such a star is never flat, its pairs are always tested.
  std::vector<uint8_t> boundary(X0.size(), 0);
  for (size_t e = 0; e < topo.edges.size(); ++e) {
    const int slots = topo.edge_slot_start[e + 1] - topo.edge_slot_start[e];
    const int* slot = &topo.edge_slots[topo.edge_slot_start[e]];
    const bool opposite =
        slots == 2 && topo.face_edge_sign[slot[0] / 3][slot[0] % 3] != topo.face_edge_sign[slot[1] / 3][slot[1] % 3];
    for (int v : topo.edges[e]) {
      if (slots == 1 && boundary[v] < 255) ++boundary[v];
      if (slots > 2 || (slots == 2 && !opposite)) star_kind_[v] = kNeverFlat;
    }
  }
  for (size_t v = 0; v < X0.size(); ++v)
    if (star_kind_[v] != kNeverFlat && boundary[v] > 0) star_kind_[v] = boundary[v] == 2 ? kOpenFan : kNeverFlat;
  moved_faces_.reserve(topo.faces.size());  // at most each once: a step never grows them
  star_list_.reserve(X0.size());
  stage_moves_.reserve(X0.size());
  double length = 0;
  for (const auto& e : topo.edges) length += (X0[e[1]] - X0[e[0]]).norm();
  mean_edge_ = topo.edges.empty() ? 0 : length / static_cast<double>(topo.edges.size());
}

void SelfIntersectionGuard::find_flat_stars(const std::vector<Vector3d>& X, const std::vector<int>* faces, bool patches) {
  const MeshTopology& topo = *topo_;
  constexpr double kTwoPi = 6.283185307179586;
  const auto star = [&](int v) {
    const int begin = topo.vertex_corner_start[v], end = topo.vertex_corner_start[v + 1];
    // The wedge of corner i, from v: its edges a and b (to corners ia and ib), in the face's turning order.
    int ia = -1, ib = -1;
    Vector3d a, b;
    const auto wedge = [&](int i) {
      const int corner = topo.vertex_corners[i];
      const std::array<int, 3>& f = topo.faces[corner / 3];
      const int k = corner % 3;
      ia = f[(k + 1) % 3];
      ib = f[(k + 2) % 3];
      a = X[ia] - X[v];
      b = X[ib] - X[v];
    };
    Vector3d n = Vector3d::Zero();
    bool thick = true;
    for (int i = begin; i < end; ++i) {
      wedge(i);
      const Vector3d twice_area = a.cross(b);
      n += twice_area;
      if (!patches) continue;
      const double longest = std::max({a.squaredNorm(), b.squaredNorm(), (b - a).squaredNorm()});
      thick = thick && twice_area.squaredNorm() >= kThinFace * kThinFace * longest;
    }
    bool flat = n.squaredNorm() > 0;
    // Seen along n, every face must turn the right way (a wedge of less than half a turn), and the
    // wedges must wind around the corner once: a closed star covers the ray along its first edge
    // once (its first wedge; a fold covers it again), an open one sums to less than a full turn.
    // A wedge (a, b) covers the ray where a x ray . n >= 0 and ray x b . n > 0, that is where
    // a . m <= 0 < b . m with m = n x ray: two dot products a wedge instead of two cross products.
    // An edge that is the ray is told by its corner, not by the dot product's rounding: a wedge
    // starting on the ray covers it where it turns the right way, one ending on it does not.
    Vector3d m = Vector3d::Zero();
    int ray = -1;
    double winding = 0;
    int covering = 0;
    for (int i = begin; i < end && flat; ++i) {
      wedge(i);
      const double turn = a.cross(b).dot(n);
      flat = turn > 0;
      if (star_kind_[v] == kOpenFan) {
        const Vector3d pa = a - a.dot(n) / n.squaredNorm() * n, pb = b - b.dot(n) / n.squaredNorm() * n;
        winding += std::atan2(turn / n.norm(), pa.dot(pb));
        continue;
      }
      if (i == begin) {  // starts on the ray, and covers it where it turns the right way (turn > 0 here)
        ray = ia, m = n.cross(a);
        ++covering;
        continue;
      }
      covering += ib != ray && (ia == ray || a.dot(m) <= 0) && b.dot(m) > 0;
    }
    flat_star_[v] = flat && star_kind_[v] != kNeverFlat && (star_kind_[v] == kClosedStar ? covering == 1 : winding < kTwoPi);
    if (patches) patch_corner_[v] = flat_star_[v] && star_kind_[v] == kClosedStar && thick;
  };
  if (faces == nullptr) {
    parallel::for_each(topo.num_vertices, parallel::kMinParallelItems, star);
    return;
  }
  // The stars these faces belong to, each once.
  const uint32_t stamp = ++star_stamp_count_;
  star_list_.clear();
  for (int f : *faces)
    for (int v : topo.faces[f])
      if (star_stamp_[v] != stamp) star_stamp_[v] = stamp, star_list_.push_back(v);
  parallel::for_each(static_cast<int>(star_list_.size()), kMinParallelFaces, [&](int i) { star(star_list_[i]); });
}

int64_t SelfIntersectionGuard::bytes_needed(int64_t num_vertices, int64_t num_faces) {
  // Per vertex the buffers above; per face its two stamps, its place in moved_faces_ and the candidate
  // pairs, about 6 per face on the armadillos (kCandidateReach), with room for twice that and the
  // list's growth.
  return FaceBvh::bytes_needed(num_faces) + (24 + 4 + 4 + 4 + 3 + 24 + 24 + 1 + 24 + 4 + 4 + 4) * num_vertices +
         (4 + 4 + 4 + 16 * 8) * num_faces;
}

bool SelfIntersectionGuard::in_contact(int f, int g, const std::vector<Vector3d>& X, double margin) const {
  const std::array<int, 3>&fa = topo_->faces[f], &fb = topo_->faces[g];
  int shared = 0, corner = -1;
  for (int i : fa)
    if (i == fb[0] || i == fb[1] || i == fb[2]) ++shared, corner = i;
  if (shared >= 2 || (shared == 1 && flat_star_[corner])) return false;
  Triangle a, b;
  arrange(fa, fb, X, a, b);
  return triangles_closer_than(a, b, shared, margin);
}

const std::vector<uint64_t>& SelfIntersectionGuard::contacts(const std::vector<Vector3d>& X, bool skip_allowed,
                                                            double margin) {
  // The pairs sharing no corner come from the candidates where they serve, else from a search of the
  // tree, which needs the flat patches (marked with the stars).
  const bool search_tree = !candidates_hold(X, margin) && !find_candidates(X, margin);
  find_flat_stars(X, nullptr, search_tree);
  found_.clear();
  const auto test = [&](int f, int g) {
    if (!in_contact(f, g, X, margin)) return;
    const uint64_t key = pair_key(f, g);
    if (skip_allowed && allowed(key, f, g, X)) return;
    std::lock_guard<std::mutex> lock(found_mutex_);  // contacts are few: one lock suffices
    found_.push_back(key);
  };
  // Pairs sharing a corner: only around a corner whose star folds can they cross (in_contact skips
  // the others, and pairs sharing an edge). Each pair sharing one corner is seen from that corner.
  const MeshTopology& topo = *topo_;
  parallel::for_each(topo.num_vertices, parallel::kMinParallelItems, [&](int v) {
    if (flat_star_[v]) return;
    const int begin = topo.vertex_corner_start[v], end = topo.vertex_corner_start[v + 1];
    for (int i = begin; i < end; ++i)
      for (int j = i + 1; j < end; ++j) test(topo.vertex_corners[i] / 3, topo.vertex_corners[j] / 3);
  });
  // Pairs sharing none whose boxes overlap.
  if (search_tree) {
    // The vertices move too far for candidates to last: one search of the tree, which leaves out
    // the pairs inside flat patches (face_bvh.h), most of a fast-moving surface's pairs.
    bvh_.refit(X, 0.5 * margin, patch_corner_);
    bvh_.for_overlapping_pairs([&](int, int f, int g) {
      if (!share_corner(f, g)) test(f, g);
    }, true);
  } else {
    // Among the candidates, or of a face that moved too far for them (a pair may then be tested
    // twice: found_ is made unique below).
    parallel::for_each(static_cast<int>(num_candidates_), parallel::kMinParallelItems, [&](int i) {
      const int f = static_cast<int>(candidates_[i] >> 32), g = static_cast<int>(candidates_[i] & 0xffffffffu);
      if (bvh_.boxes_overlap(f, g)) test(f, g);
    });
    parallel::for_each(static_cast<int>(moved_faces_.size()), kMinParallelFaces, [&](int i) {
      bvh_.pairs_with(moved_faces_[i], [&](int f, int g) {
        if (!share_corner(f, g)) test(f, g);
      });
    });
  }
  std::sort(found_.begin(), found_.end());
  found_.erase(std::unique(found_.begin(), found_.end()), found_.end());
  return found_;
}

bool SelfIntersectionGuard::share_corner(int f, int g) const {
  const std::array<int, 3>&a = topo_->faces[f], &b = topo_->faces[g];
  for (int v : a)
    if (v == b[0] || v == b[1] || v == b[2]) return true;
  return false;
}

bool SelfIntersectionGuard::candidates_hold(const std::vector<Vector3d>& X, double margin) {
  if (candidate_reach_ < 0) return false;
  const MeshTopology& topo = *topo_;
  moved_faces_.clear();
  const uint32_t stamp = ++moved_stamp_count_;
  for (size_t v = 0; v < X.size(); ++v) {
    if (!((X[v] - candidates_at_[v]).cwiseAbs().array() > candidate_reach_).any()) continue;
    for (int i = topo.vertex_corner_start[v]; i < topo.vertex_corner_start[v + 1]; ++i) {
      const int f = topo.vertex_corners[i] / 3;
      if (moved_stamp_[f] == stamp) continue;
      moved_stamp_[f] = stamp;
      moved_faces_.push_back(f);
    }
  }
  if (static_cast<double>(moved_faces_.size()) > kMostMovedFaces * static_cast<double>(topo.faces.size())) return false;
  bvh_.refit_boxes(X, 0.5 * margin);
  return true;
}

bool SelfIntersectionGuard::find_candidates(const std::vector<Vector3d>& X, double margin) {
  // Only worth it if most vertices stay within the reach for a few stages; on a strong style's first
  // steps they do not.
  candidate_reach_ = -1;
  moved_faces_.clear();
  const double reach = kCandidateReach * mean_edge_;
  if (kStagesAhead * stage_move_ > reach) return false;
  bvh_.refit_boxes(X, 0.5 * margin + reach);
  // Each task of the search fills a small buffer of its own and moves it into candidates_ when full,
  // at a place it claims: no lock, and the kept list grows only past its largest size so far.
  const int tasks = bvh_.num_tasks();
  task_buffer_.resize(static_cast<size_t>(tasks) * kTaskBuffer);
  task_fill_.assign(tasks, 0);
  std::atomic<size_t> claimed{0};
  const auto flush = [&](int t) {
    const size_t at = claimed.fetch_add(task_fill_[t]);
    for (int i = 0; i < task_fill_[t]; ++i)
      if (at + i < candidates_.size()) candidates_[at + i] = task_buffer_[static_cast<size_t>(t) * kTaskBuffer + i];
    task_fill_[t] = 0;
  };
  bvh_.for_overlapping_pairs([&](int t, int f, int g) {
    if (share_corner(f, g)) return;
    task_buffer_[static_cast<size_t>(t) * kTaskBuffer + task_fill_[t]++] = pair_key(f, g);
    if (task_fill_[t] == kTaskBuffer) flush(t);
  }, false);
  for (int t = 0; t < tasks; ++t) flush(t);
  if (claimed > candidates_.size()) {  // too many for the list: again, with room for a quarter more
    candidates_.resize(claimed + claimed / 4);
    return find_candidates(X, margin);
  }
  num_candidates_ = claimed;
  candidates_at_ = X;
  candidate_reach_ = reach;
  bvh_.refit_boxes(X, 0.5 * margin);
  return true;
}

const std::vector<uint64_t>& SelfIntersectionGuard::contacts_of(const std::vector<int>& faces,
                                                                const std::vector<Vector3d>& X) {
  bvh_.refit_faces(faces, X, 0.5 * kContactMargin);
  find_flat_stars(X, &faces);
  found_.clear();
  // A pair of two of these faces is tested from the lower one only.
  const uint32_t stamp = ++of_stamp_count_;
  for (int f : faces) of_stamp_[f] = stamp;
  parallel::for_each(static_cast<int>(faces.size()), kMinParallelFaces, [&](int i) {
    bvh_.pairs_with(faces[i], [&](int f, int g) {
      if (g < f && of_stamp_[g] == stamp) return;
      if (!in_contact(f, g, X, kContactMargin)) return;
      const uint64_t key = pair_key(f, g);
      if (allowed(key, f, g, X)) return;
      std::lock_guard<std::mutex> lock(found_mutex_);
      found_.push_back(key);
    });
  });
  std::sort(found_.begin(), found_.end());
  found_.erase(std::unique(found_.begin(), found_.end()), found_.end());
  return found_;
}

bool SelfIntersectionGuard::next_to_crossing(int f, int g) const {
  const MeshTopology& topo = *topo_;
  for (int v : topo.faces[f])
    for (int i = topo.vertex_corner_start[v]; i < topo.vertex_corner_start[v + 1]; ++i) {
      const int f0 = topo.vertex_corners[i] / 3;
      for (int w : topo.faces[g])
        for (int j = topo.vertex_corner_start[w]; j < topo.vertex_corner_start[w + 1]; ++j)
          if (std::binary_search(crossing_.begin(), crossing_.end(), pair_key(f0, topo.vertex_corners[j] / 3)))
            return true;
    }
  return false;
}

bool SelfIntersectionGuard::allowed(uint64_t key, int f, int g, const std::vector<Vector3d>& X) {
  if (!std::binary_search(allowed_.begin(), allowed_.end(), key)) {
    // A crossing the mesh already has may slide on to the next faces as the surface moves; a new
    // crossing elsewhere may not begin (docs/interactive.md, Avoid Self-Intersections).
    if (crossing_.empty() || !next_to_crossing(f, g)) return false;
    std::lock_guard<std::mutex> lock(slid_mutex_);
    slid_.push_back(key);
    return true;
  }
  if (std::binary_search(crossing_.begin(), crossing_.end(), key)) return true;
  Triangle a, b;  // touching at the start: allowed while it does not cross
  const int shared = arrange(topo_->faces[f], topo_->faces[g], X, a, b);
  return !triangles_cross(a, b, shared);
}

void SelfIntersectionGuard::take_slid_pairs() {
  if (slid_.empty()) return;
  std::sort(slid_.begin(), slid_.end());
  slid_.erase(std::unique(slid_.begin(), slid_.end()), slid_.end());
  // Merged into a kept buffer and swapped in (inplace_merge would allocate its own buffer each time):
  // the buffers only grow past the largest set so far.
  for (std::vector<uint64_t>* list : {&allowed_, &crossing_}) {
    merged_.resize(list->size() + slid_.size());
    const auto end = std::set_union(list->begin(), list->end(), slid_.begin(), slid_.end(), merged_.begin());
    merged_.erase(end, merged_.end());
    list->swap(merged_);
  }
  slid_.clear();
}

void SelfIntersectionGuard::start_from(const std::vector<Vector3d>& X) {
  slid_.clear();
  candidate_reach_ = -1;
  stage_move_ = 0;
  const std::vector<uint64_t>& near = contacts(X, false, kStartMargin);
  crossing_.clear();
  for (uint64_t key : near) {
    Triangle a, b;
    const int shared =
        arrange(topo_->faces[key >> 32], topo_->faces[static_cast<int>(key & 0xffffffffu)], X, a, b);
    if (triangles_cross(a, b, shared)) crossing_.push_back(key);
  }
  // A pair only a hair apart (within kStartMargin, not kContactMargin) touches from the start where no
  // crossing is next to it; next to one it stays a pair the crossing may slide onto, as any other there.
  allowed_.clear();
  for (uint64_t key : near) {
    const int f = static_cast<int>(key >> 32), g = static_cast<int>(key & 0xffffffffu);
    if (std::binary_search(crossing_.begin(), crossing_.end(), key) || in_contact(f, g, X, kContactMargin) ||
        !next_to_crossing(f, g))
      allowed_.push_back(key);
  }
}

int SelfIntersectionGuard::limit(const std::vector<Vector3d>& safe, std::vector<Vector3d>& X) {
  const int nV = static_cast<int>(X.size());
  double longest = 0;
  for (int v = 0; v < nV; ++v) longest = std::max(longest, (X[v] - safe[v]).cwiseAbs().maxCoeff());
  // The stages a move (largest coordinate) is checked in: none longer than kStageMove, at most 256.
  const auto stages_for = [](double move) {
    constexpr int kMaxStages = 256;
    return static_cast<int>(std::min<double>(kMaxStages, std::max(1.0, std::ceil(move / kStageMove))));
  };
  const int stages = stages_for(longest);
  // How far most vertices go in a stage: whether candidates found now would last (find_candidates()).
  stage_moves_.resize(nV);
  for (int v = 0; v < nV; ++v) stage_moves_[v] = static_cast<float>((X[v] - safe[v]).cwiseAbs().maxCoeff() / stages);
  if (nV > 0) {
    const auto most = stage_moves_.begin() + static_cast<std::ptrdiff_t>(kMostVertices * (nV - 1));
    std::nth_element(stage_moves_.begin(), most, stage_moves_.end());
    stage_move_ = *most;
  }
  if (stages == 1) {
    limit_stage(safe, X);
    take_slid_pairs();
    last_staged_ = false;
    return last_held_;
  }
  if (move_.size() != X.size()) {
    move_.resize(nV);
    stage_start_.resize(nV);
    ever_held_.assign(nV, 0);
    own_stages_.resize(nV);
  }
  whole_ = X;
  // Each vertex in as many stages as its own move needs: a vertex that moves less than kStageMove
  // makes its whole move in the first stage, and the later stages move only the few that go further
  // (a folding part swinging at every step), so only their faces are checked there, not the mesh.
  for (int v = 0; v < nV; ++v) {
    own_stages_[v] = stages_for((X[v] - safe[v]).cwiseAbs().maxCoeff());  // at most `stages`: no move is longer
    move_[v] = (X[v] - safe[v]) / own_stages_[v];
  }
  stage_start_ = safe;
  held_in_any_.clear();
  for (int stage = 0; stage < stages; ++stage) {
    // The sum of a vertex's stages is its step only up to rounding: its last stage aims at the step's
    // own result, so that a vertex never held ends exactly where it would without the guard.
    stage_faces_.clear();
    const uint32_t stamp = ++moved_stamp_count_;
    for (int v = 0; v < nV; ++v) {
      if (own_stages_[v] <= stage) continue;
      X[v] = stage + 1 < own_stages_[v] || ever_held_[v] ? Vector3d(stage_start_[v] + move_[v]) : whole_[v];
      if (stage == 0) continue;
      for (int i = topo_->vertex_corner_start[v]; i < topo_->vertex_corner_start[v + 1]; ++i) {
        const int f = topo_->vertex_corners[i] / 3;
        if (moved_stamp_[f] != stamp) moved_stamp_[f] = stamp, stage_faces_.push_back(f);
      }
    }
    limit_stage(stage_start_, X, stage == 0 ? nullptr : &stage_faces_);
    for (int v : held_)
      if (!ever_held_[v]) ever_held_[v] = 1, held_in_any_.push_back(v);
    stage_start_ = X;
  }
  take_slid_pairs();
  denied_ = 0;
  for (int v : held_in_any_) {
    ever_held_[v] = 0;
    denied_ = std::max(denied_, (whole_[v] - X[v]).cwiseAbs().maxCoeff());
  }
  last_held_ = static_cast<int>(held_in_any_.size());
  last_staged_ = true;
  return last_held_;
}

bool SelfIntersectionGuard::slide_along(int v, int other, const std::vector<Vector3d>& safe) {
  const auto& t = topo_->faces[other];
  if (t[0] == v || t[1] == v || t[2] == v) return false;
  const Vector3d n = (safe[t[1]] - safe[t[0]]).cross(safe[t[2]] - safe[t[0]]);
  const double ln = n.norm();
  if (!(ln > 0)) return false;
  const Vector3d u = n / ln;
  const Vector3d d = aim_[v] - safe[v];
  const double side = (safe[v] - safe[t[0]]).dot(u), towards = d.dot(u);
  if (side * towards >= 0) return false;  // moving away from the other face: sliding changes nothing
  aim_[v] = safe[v] + d - towards * u;
  return true;
}

void SelfIntersectionGuard::limit_stage(const std::vector<Vector3d>& safe, std::vector<Vector3d>& X,
                                        const std::vector<int>* moved) {
  const MeshTopology& topo = *topo_;
  // A held vertex first slides (slide_along), then its step is halved per step back down to
  // kSmallestFraction, then taken back to `safe` outright. Only the corners of faces in a new contact
  // step back, so the hold stays local: a pair whose six corners are all back at `safe` is as it was
  // there, where it was not in a new contact, so every round steps some vertex back or ends the loop
  // (at most six times per vertex). No round count triggers a global rollback: that froze whole
  // meshes (docs/quality.md).
  constexpr float kSmallestFraction = 1.0f / 8;
  held_.clear();
  // found_ is refilled at the end of each round, after the round has read it.
  const std::vector<uint64_t>& found = moved == nullptr ? contacts(X, true, kContactMargin) : contacts_of(*moved, X);
  // One step back for corner v of a face in contact with face `other`: false where v is at `safe` already.
  const auto step_back = [&](int v, int other) {
    float& t = step_fraction_[v];
    if (t == 0.0f) return false;  // already at `safe`
    if (t == 1.0f) held_.push_back(v), aim_[v] = candidate_[v];
    if ((t == 1.0f || (t < 0.0f && t > kLastSlide)) && slide_along(v, other, safe)) {
      t = t == 1.0f ? -1.0f : t - 1.0f;  // -1, -2, ...: slid once, twice, ...
      X[v] = aim_[v];
    } else {
      t = t < 0.0f ? 0.5f : (t > kSmallestFraction ? 0.5f * t : 0.0f);
      X[v] = safe[v] + static_cast<double>(t) * (aim_[v] - safe[v]);
    }
    for (int i = topo.vertex_corner_start[v]; i < topo.vertex_corner_start[v + 1]; ++i)
      touched_.push_back(topo.vertex_corners[i] / 3);
    return true;
  };
  for (int round = 0; !found.empty(); ++round) {
    if (round == 0) candidate_ = X;
    const uint32_t stamp = ++stamp_count_;
    touched_.clear();
    // Each pair found is stepped back until it no longer touches (tested alone after each step back),
    // or its corners are all at `safe`; then a search (contacts_of) looks for what the moves touched
    // elsewhere: one search a round, not one per step back. A pair's first step back leaves out the
    // corners another pair stepped back in this round already (a corner that slid along one face
    // would only be halved by the next: a sheet pressed onto another then stopped sliding); where
    // the pair still touches, its next steps back take all six.
    for (uint64_t key : found) {
      const int f = static_cast<int>(key >> 32), g = static_cast<int>(key & 0xffffffffu);
      for (bool first = true; in_contact(f, g, X, kContactMargin) && !allowed(key, f, g, X); first = false) {
        int corners[6], count = 0;
        bool stepped = false;
        for (int face : {f, g})
          for (int v : topo.faces[face]) {
            if (std::find(corners, corners + count, v) != corners + count) continue;  // a shared corner
            corners[count++] = v;
            if (first && round_stamp_[v] == stamp) continue;
            round_stamp_[v] = stamp;
            stepped = step_back(v, face == f ? g : f) || stepped;
          }
        if (!stepped && !first) break;
      }
    }
    // Every corner of every contact is back at `safe` already: contacts that `safe` itself had (a
    // start the caller set with set_vertices() is taken as it is), nothing left to step back.
    if (touched_.empty()) break;
    std::sort(touched_.begin(), touched_.end());
    touched_.erase(std::unique(touched_.begin(), touched_.end()), touched_.end());
    contacts_of(touched_, X);  // only faces that moved can have come into contact
  }
  last_held_ = static_cast<int>(held_.size());
  denied_ = 0;
  for (int v : held_) {
    denied_ = std::max(denied_, (candidate_[v] - X[v]).cwiseAbs().maxCoeff());
    step_fraction_[v] = 1.0f;
  }
}

}  // namespace gauss
