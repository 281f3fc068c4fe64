#pragma once
// Self-intersections of a triangle mesh: counting them, and a guard that keeps a run from making new
// ones (the paper's own limitation, section 5.2: its energy only looks at the surface).
//
// Counting: count_self_intersections() counts the unordered pairs of faces that cross
// (triangle_intersection.h: what Blender's 3D-Print toolbox counts with BVHTree.overlap, whose list
// holds every such pair twice, once in each order).
//
// The guard (the solver's avoid_self_intersections setting). Why this technique: the global step's
// matrix stays the one factored at set-up (a barrier or contact forces would change it every step),
// and the guard only looks at the result of a step. The global step learns of the contact through
// the vertices the guard held back: the solver gives them springs there (contact_springs.h), solved
// with the same factor. A step of Algorithm 1 maps the vertices from a
// state S, free of new crossings, to a candidate C. The guard refits a bounding-volume hierarchy
// (face_bvh.h) to C and tests the faces whose boxes overlap. Where two faces cross (and did not at the
// start), or come closer than kContactMargin without sharing a corner (and were not within kStartMargin
// at the start), their corners first slide: each keeps its step without the part that goes towards the other face's plane (at S; again
// for a second face it then meets), so a surface pressed onto another goes on moving along it and the
// style goes on acting there. Where that still touches, they are moved back towards S (x = S + t (A -
// S), A the slid candidate, t halved, then 0), the pair tested alone after each move until it no
// longer touches; then the faces around the moved corners are searched again (a round), until no new
// pair is left. Only the corners of faces in a new contact step back, so a hold stays where the contact is (a global rollback froze whole
// meshes); at worst those corners are back at S, which has no new contact: a step can stop short,
// never pass through.
// A mesh that already crosses itself keeps its crossings, and they may slide on to the neighbouring
// faces as the surface moves (a pair whose faces each share a corner with a crossing pair's), but no
// crossing begins anywhere else: held still, the faces around a crossing froze the region around it. This is the intersection-free line search of Incremental
// Potential Contact (Li et al. 2020) made local to the faces involved, on the discrete states a run
// shows (the states between two steps are not checked: the margin keeps faces apart by more than
// rounding, and a move of more than kStageMove is checked in stages of at most that: a part thinner
// than that could still be passed through in one stage).
// Pinned vertices are held back like the others: a handle dragged into the mesh leaves its pins short
// of their targets while going further would pass through.
//
// Cost: most pairs whose boxes overlap are neighbours sharing a corner. Two faces around a corner can
// only cross where the corner's star folds over: projected onto the plane normal to the star's
// (area-weighted) normal, a star whose faces all keep their orientation and wind around the corner
// once (an open star: less than once) covers no point twice, so none of its faces cross. That holds
// for one fan only: a star of two fans (two sheets meeting in the corner), with a non-manifold edge or
// faces oriented against each other is never taken as flat. Only the pairs around the other corners
// are tested, found from the corners themselves. The pairs sharing no corner come from a search of
// the hierarchy that serves many stages once a run slows down (candidates_hold() below): late in a
// run, when only a contact still moves, a check costs a pass over the faces, not a search.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <mutex>
#include <vector>

#include "gauss/collision/face_bvh.h"
#include "gauss/mesh/mesh_topology.h"

namespace gauss {

// Faces closer than this (without a shared corner) count as touching, in the solver's normalized
// frame, whose longest bounding-box side is 1: 1e-4 is 0.01% of the mesh's size, a thousand times
// float32's rounding there, and well below the edge lengths of meshes up to millions of faces.
inline constexpr double kContactMargin = 1e-4;
// Pairs closer than this at the start count as touching there, allowed to touch but never to cross,
// unless they are next to a crossing of the start (those stay pairs the crossing may slide onto, as
// with kContactMargin alone). A scan may hold sheets a hair beyond kContactMargin apart from the start
// (the Stanford bunny's original .ply: two faces 1.15e-4 apart), which a style moves within the margin
// without ever crossing; with the steps' margin at the start the guard held such a run back for good.
inline constexpr double kStartMargin = 2 * kContactMargin;
// The longest move of a vertex checked at once (normalized frame): a longer step or pin move (a
// handle dragged far in one go) is checked in stages, so that it cannot jump through a part thicker
// than this. 2% of the mesh's size, because smaller stages multiply the guard's cost on a strong
// style's first steps (measured: docs/performance.md#the-guards-cost).
inline constexpr double kStageMove = 2e-2;

// The unordered pairs of faces that cross, #P by 2 (f < g, indices into faces, sorted). faces: #F by 3
// (no repeated corner); X: #V by 3 (any frame).
std::vector<std::array<int, 2>> self_intersecting_pairs(const std::vector<std::array<int, 3>>& faces,
                                                        const std::vector<Eigen::Vector3d>& X);
// Their number.
int64_t count_self_intersections(const std::vector<std::array<int, 3>>& faces, const std::vector<Eigen::Vector3d>& X);

class SelfIntersectionGuard {
 public:
  SelfIntersectionGuard() = default;
  // topo: the mesh (kept by reference: the solver's topology outlives the guard); X0: #V by 3, the
  // positions the hierarchy is built on (the rest mesh).
  SelfIntersectionGuard(const MeshTopology& topo, const std::vector<Eigen::Vector3d>& X0);

  // Takes the pairs in contact at X (#V by 3, normalized frame; see kStartMargin) as the start: those that cross may
  // go on crossing (a mesh that already intersects keeps those pairs), those that only touch must
  // never cross, and every other pair must never come into contact.
  void start_from(const std::vector<Eigen::Vector3d>& X);

  // safe: the state before the step (no new contacts); X: the step's result, changed in place to the
  // nearest state on the way back to `safe` without new contacts, per vertex. Returns the number of
  // vertices held back (0: X was left as it was).
  int limit(const std::vector<Eigen::Vector3d>& safe, std::vector<Eigen::Vector3d>& X);

  // Vertices held back by the last limit(): how many, and which (in the topology's numbering, each once).
  int last_held() const { return last_held_; }
  const std::vector<int>& last_held_vertices() const { return last_staged_ ? held_in_any_ : held_; }
  // The longest move (largest coordinate) the last limit() took from a held vertex: how far the run
  // would have gone on without the guard.
  double last_denied() const { return denied_; }

  // Bytes a guard for this mesh holds (its hierarchy and per-vertex buffers; the allowed pairs come
  // on top, as many as the mesh has in contact).
  static int64_t bytes_needed(int64_t num_vertices, int64_t num_faces);

 private:
  // One stage of limit(): a move from `safe` to X no longer than kStageMove. moved: the faces around
  // the vertices that moved, where only those did (a later stage), else null (every vertex may have).
  void limit_stage(const std::vector<Eigen::Vector3d>& safe, std::vector<Eigen::Vector3d>& X,
                   const std::vector<int>* moved = nullptr);
  // Whether a contact of this pair at X is one the start allows, or one a crossing slides into: f
  // and g each share a corner with the faces of a pair that crosses (or crossed) since the start.
  // Those are noted, and become allowed crossings at the end of limit() (take_slid_pairs).
  bool allowed(uint64_t key, int f, int g, const std::vector<Eigen::Vector3d>& X);
  bool next_to_crossing(int f, int g) const;
  // A step back for corner v of a face in a new contact with face `other`: aim_[v] without the part
  // of its step that goes towards `other`'s plane (at `safe`), so that it slides along the contact.
  // False (aim_ unchanged) where that changes nothing.
  bool slide_along(int v, int other, const std::vector<Eigen::Vector3d>& safe);
  // step_fraction_ of a vertex slid k times in this limit_stage: -k; it slides at most -kLastSlide
  // times (on different contacts), then its slid step is halved.
  static constexpr float kLastSlide = -2.0f;
  void take_slid_pairs();
  // Pairs (f < g, as f * 2^32 + g) in contact at X (closer than margin: kContactMargin, or the start's
  // kStartMargin), without the allowed ones if skip_allowed; sorted. Into found_ (reused: a step
  // allocates nothing once it has grown), which is returned.
  const std::vector<uint64_t>& contacts(const std::vector<Eigen::Vector3d>& X, bool skip_allowed, double margin);
  // The pairs sharing no corner whose boxes may overlap (the first num_candidates_ of candidates_):
  // those whose boxes, grown by candidate_reach_ more, overlapped at candidates_at_. Their boxes can
  // only overlap now if a corner moved further than that (per coordinate, as the boxes grow): the
  // faces around such corners (moved_faces_) are searched for one by one. So the tree is searched
  // once for many stages, until more than kMostMovedFaces of the faces have moved too far.
  // candidates_hold() finds those faces and refits the boxes, or says that the candidates no longer
  // serve; find_candidates() finds new ones, or says that they would not last (then contacts()
  // searches the tree for the stage alone, leaving out the pairs inside flat patches as face_bvh.h
  // allows; the candidates hold every pair).
  bool candidates_hold(const std::vector<Eigen::Vector3d>& X, double margin);
  bool find_candidates(const std::vector<Eigen::Vector3d>& X, double margin);
  bool share_corner(int f, int g) const;
  // candidate_reach_ in mean edge lengths at the rest shape: a step late in a run moves 99% of the
  // vertices by less than a tenth of an edge (measured: docs/performance.md#the-guards-cost).
  static constexpr double kCandidateReach = 0.25;
  static constexpr double kMostMovedFaces = 0.02;
  // Candidates are found only if kMostVertices of the vertices move less than their reach in
  // kStagesAhead stages at the current stage's pace (stage_move_).
  static constexpr double kMostVertices = 0.98;
  static constexpr double kStagesAhead = 4;
  // A search for the contacts of this many faces (each a walk down the tree) is worth sharing
  // among threads.
  static constexpr int kMinParallelFaces = 256;

  // Marks flat_star_[v] for every vertex whose star covers no point twice (see above) at X: all, or
  // those of the given faces' corners; and patch_corner_ (of all) if `patches`.
  void find_flat_stars(const std::vector<Eigen::Vector3d>& X, const std::vector<int>* faces, bool patches = false);
  // Whether faces f and g are in contact at X (flat_star_ up to date for their corners).
  bool in_contact(int f, int g, const std::vector<Eigen::Vector3d>& X, double margin) const;
  // The contacts, not allowed, of the given faces with any other (sorted, each once), into found_.
  const std::vector<uint64_t>& contacts_of(const std::vector<int>& faces, const std::vector<Eigen::Vector3d>& X);

  const MeshTopology* topo_ = nullptr;
  FaceBvh bvh_;
  // #V: the vertex's star is one closed fan, one open fan, or neither (two fans sharing the corner, a
  // non-manifold edge, faces oriented against each other): never taken as flat.
  enum : uint8_t { kClosedStar, kOpenFan, kNeverFlat };
  std::vector<uint8_t> star_kind_;
  std::vector<uint8_t> flat_star_;        // #V, per check
  // #V, per search of the tree: a closed flat star none of whose faces is thinner than kThinFace
  // (its least altitude): the corners of the hierarchy's flat patches (face_bvh.h). Why that keeps
  // two faces of a flat patch that share no corner out of contact: seen along the patch's axis the
  // faces around face f's corners cover a band around f at least half their least altitude wide, and
  // that altitude is at least cos(FaceBvh's kFlatAngle) = 0.54 of kThinFace: 2.7 kContactMargin. A
  // face sharing no corner with f lies outside the band (the patch is a height field), so further from
  // f than the margin. Measured on the 43K armadillo: without the thickness rule such pairs were in
  // contact, and with it but a cone of 80 degrees (0.87 kContactMargin by this count) one still was;
  // as it is, 1,641 searches of the tree over the corpus found what a search that skips nothing finds.
  // An open fan is left out: a crack between two boundaries needs no thin face to close.
  std::vector<uint8_t> patch_corner_;
  static constexpr double kThinFace = 10 * kContactMargin;
  // The band's half-width, half of cos(kFlatAngle) kThinFace, must exceed the margin. cos x >= 1 - x^2 / 2
  // for every x, so this bound (2.5 kContactMargin at 1 rad) holds wherever the check passes, and it fails
  // to compile if either constant moves too far (at 80 degrees: 0.13 kContactMargin by this bound).
  static_assert(0.5 * (1 - FaceBvh::kFlatAngle * FaceBvh::kFlatAngle / 2) * kThinFace > kContactMargin,
                "flat patches' faces sharing no corner could come within the contact margin unseen");
  std::vector<uint64_t> allowed_;         // sorted: in contact at the start
  std::vector<uint64_t> crossing_;        // sorted: crossing at the start, and the pairs crossings slid into
  std::vector<uint64_t> slid_;            // pairs a crossing slid into during the current limit()
  std::mutex slid_mutex_;                 // contacts() notes them from several threads
  std::vector<uint64_t> merged_;          // take_slid_pairs()'s output before it is swapped in
  std::vector<Eigen::Vector3d> move_;     // #V: a staged move's whole displacement
  std::vector<Eigen::Vector3d> stage_start_;  // #V
  std::vector<Eigen::Vector3d> whole_;    // #V: a staged limit()'s input, the step's own result
  std::vector<uint8_t> ever_held_;        // #V: held in some stage of the current limit()
  std::vector<Eigen::Vector3d> candidate_;  // #V: the step's result before limit()
  std::vector<Eigen::Vector3d> aim_;      // #V: where a held vertex goes now, its candidate slid
  std::vector<float> step_fraction_;      // #V: t of every vertex in the current limit(), 1 outside it
  std::vector<uint32_t> round_stamp_;     // #V: the last round that stepped the vertex back
  uint32_t stamp_count_ = 0;
  std::vector<int> held_;                 // vertices with t < 1
  std::vector<int> touched_;              // faces moved in the current round
  std::vector<uint64_t> found_;           // the last contacts() or contacts_of()
  std::vector<uint64_t> candidates_;      // see candidates_hold()
  size_t num_candidates_ = 0;
  static constexpr int kTaskBuffer = 64;  // find_candidates(): per task of the search
  std::vector<uint64_t> task_buffer_;
  std::vector<int> task_fill_;
  std::vector<Eigen::Vector3d> candidates_at_;  // #V
  double candidate_reach_ = -1;           // < 0: no candidates yet
  double mean_edge_ = 0;                  // at the rest shape
  double stage_move_ = 0;                 // kMostVertices of the vertices move less in a stage
  std::vector<float> stage_moves_;        // #V: limit()'s scratch for it
  std::vector<int> moved_faces_;          // see candidates_hold()
  std::vector<uint32_t> moved_stamp_;     // #F
  uint32_t moved_stamp_count_ = 0;
  std::vector<uint32_t> of_stamp_;        // #F: contacts_of() tests a pair of two of its faces once
  uint32_t of_stamp_count_ = 0;
  std::vector<uint32_t> star_stamp_;      // #V: find_flat_stars() of some faces tests each star once
  std::vector<int> star_list_;
  uint32_t star_stamp_count_ = 0;
  std::mutex found_mutex_;                // contacts() fills found_ from several threads
  std::vector<int> held_in_any_;          // a staged limit(): vertices held in some stage
  std::vector<int> own_stages_;           // #V, a staged limit(): the stages of the vertex's own move
  std::vector<int> stage_faces_;          // a staged limit(): the faces around the vertices a stage moves
  int last_held_ = 0;
  bool last_staged_ = false;  // the last limit() took stages: its vertices are held_in_any_, else held_
  double denied_ = 0;
};

}  // namespace gauss
