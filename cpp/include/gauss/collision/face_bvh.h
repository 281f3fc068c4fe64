#pragma once
// A bounding-volume hierarchy over a mesh's faces, built once and refitted to new positions: the
// faces' axis-aligned boxes, and a binary tree built top-down on the faces' centroids at X0 (split at
// the median of the longest side). A stylization moves every vertex a little, so after a run each
// node is still a compact patch: the tree stays tight without a rebuild, and a refit costs one pass
// over the faces.
//
// Flat patches (Volino and Magnenat-Thalmann's normal cones): a connected patch whose face normals all
// lie within less than a right angle of one axis, and whose corners' stars each cover no point twice
// seen along it, is a height field over the plane normal to it, unless it winds around the axis like
// a spiral ramp (which the contour test of Volino and Magnenat-Thalmann would catch, and which a
// compact cluster of rest-shape neighbours, as this tree's nodes are, does not form). Two of its faces
// that share no corner then do not cross, and they do not come closer than the caller's margin if its
// faces are not too thin for the cone (the caller marks the corners whose stars qualify:
// self_intersection.h, kThinFace). for_overlapping_pairs(fn, true) skips the pairs inside such a node,
// and the pairs between two such nodes that share a corner and whose cones fit in one of half-angle
// kFlatAngle: most pairs of neighbouring faces on a smooth or stylized surface, and most of those a
// non-flat node's two halves have along their seam.
//
// Usage:
//   FaceBvh bvh(topo.faces, X0);             // once (allocates); X0 #V by 3
//   bvh.refit(X, margin, flat_corners);      // per check: boxes of the faces at X (#V by 3), grown by
//                                            // margin, and the flat patches
//   bvh.for_overlapping_pairs(fn, skip_flat); // fn(t, f, g) once for every pair of faces f != g whose
//                                            // boxes overlap (in either order; skip_flat: not inside
//                                            // a flat patch), from several threads at once (fn must
//                                            // be thread-safe); t < num_tasks() is the task that
//                                            // found the pair: a caller that collects per task
//                                            // needs no lock
//   bvh.refit_boxes(X, margin);              // the boxes alone: the flat patches stay the last refit()'s
//   bvh.pairs_with(f, fn);                   // fn(f, g) for every face g != f whose box overlaps f's
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "gauss/util/parallel.h"

namespace gauss {

class FaceBvh {
 public:
  FaceBvh() = default;
  // faces: #F by 3 vertex indices.
  FaceBvh(const std::vector<std::array<int, 3>>& faces, const std::vector<Eigen::Vector3d>& X0);

  // flat_corners: #V, nonzero where the vertex's star qualifies for a flat patch (see above): a node is
  // flat only where all its corners' stars do.
  void refit(const std::vector<Eigen::Vector3d>& X, double margin, const std::vector<uint8_t>& flat_corners);
  void refit_boxes(const std::vector<Eigen::Vector3d>& X, double margin);
  // The boxes of the given faces only (and of the nodes above them), when no other face moved.
  void refit_faces(const std::vector<int>& faces, const std::vector<Eigen::Vector3d>& X, double margin);

  template <class Fn>
  void for_overlapping_pairs(Fn&& fn, bool skip_flat) const;
  int num_tasks() const { return static_cast<int>(tasks_.size()); }
  template <class Fn>
  void pairs_with(int face, Fn&& fn) const {
    if (!nodes_.empty()) with_box(face, 0, fn);
  }
  bool boxes_overlap(int f, int g) const { return face_box_[position_[f]].overlaps(face_box_[position_[g]]); }

  // Bytes a FaceBvh of num_faces faces holds.
  static int64_t bytes_needed(int64_t num_faces);

  // In float, rounded outwards: half the memory to stream through per overlap test, and never a
  // missed overlap.
  struct Box {
    float lo[3], hi[3];
    bool overlaps(const Box& o) const {
      return lo[0] <= o.hi[0] && o.lo[0] <= hi[0] && lo[1] <= o.hi[1] && o.lo[1] <= hi[1] && lo[2] <= o.hi[2] &&
             o.lo[2] <= hi[2];
    }
    void merge(const Box& o) {
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], o.lo[k]);
        hi[k] = std::max(hi[k], o.hi[k]);
      }
    }
  };

  // Radians (57 degrees): seen along the axis, a face's least altitude is then at least cos(1) = 0.54
  // of its own, which keeps the faces of a flat patch that share no corner apart (self_intersection.h,
  // kThinFace, checks the two at compile time). It was 80 degrees while the pairs between two nodes
  // were all searched.
  static constexpr double kFlatAngle = 1.0;

 private:
  struct Node {
    Box box;
    int begin, end;   // the faces order_[begin, end)
    int left, right;  // child nodes, -1 for a leaf
    int parent;       // -1 for the root
    bool connected;   // its faces form one patch (through shared corners)
    bool unfolded;    // all its corners are flat_corners (at the last refit)
    bool flat;        // connected, unfolded, and its normal cone's half-angle is below kFlatAngle (at the last refit)
    Eigen::Vector3d area;  // sum of its faces' area vectors (the cone's axis)
    double angle;          // the cone's half-angle (pi when unknown)
  };
  static constexpr int kLeafSize = 4;

  int build(int begin, int end, int parent, const std::vector<Eigen::Vector3d>& centroid);
  void fit_face(int i, const std::vector<Eigen::Vector3d>& X, double margin);  // i: place in tree order
  void fit_face_box(int i, const std::vector<Eigen::Vector3d>& X, double margin);  // its box alone
  void fit_node(int n, const std::vector<uint8_t>& flat_corners);  // its box, its normal cone, whether flat
  void fit_node_box(int n);  // its box alone
  // The pairs within node n (a != b: between nodes a and b), depth first.
  template <class Fn>
  void within(int n, Fn& fn, bool skip_flat) const;
  template <class Fn>
  void between(int a, int b, Fn& fn, bool skip_flat) const;
  // Whether nodes a and b (disjoint, both flat) make one flat patch: their normal cones fit in one of
  // half-angle kFlatAngle, and they share a corner (each is connected, so their union is).
  bool join_flat(int a, int b) const;
  template <class Fn>
  void with_box(int face, int n, Fn& fn) const;
  // Node pairs (n, n) and (a, b) whose pairs together are all pairs, about `count` of them, for
  // threads to share.
  std::vector<std::array<int, 2>> tasks(int count) const;
  void find_connected_nodes();
  void find_node_borders();
  void find_refit_tasks();
  // fit(n) for every node, children first: the subtrees of refit_roots_ on several threads, then the
  // nodes above them.
  template <class Fit>
  void fit_nodes(Fit&& fit);

  const std::vector<std::array<int, 3>>* faces_ = nullptr;
  std::vector<int> order_;     // #F: the faces in tree order
  std::vector<int> position_;  // #F: each face's place in order_
  std::vector<int> leaf_of_;   // #F (tree order): the leaf that holds it
  // Each node's border: the corners of its faces that also belong to a face outside it, sorted; node
  // n's are border_[border_start_[n], border_start_[n + 1]). Two disjoint nodes share a corner only
  // on both their borders.
  std::vector<int> border_start_;
  std::vector<int> border_;
  // tasks(kTasks), fixed with the tree. Threads take them round-robin and their sizes differ widely,
  // so there are many (docs/performance.md#avoiding-self-intersections).
  static constexpr int kTasks = 512;
  std::vector<std::array<int, 2>> tasks_;
  // Subtrees a refit shares among threads (about kRefitTasks), each the nodes [root, end) (a subtree
  // is a run of nodes: they are numbered depth first), and the nodes above them, children first.
  static constexpr int kRefitTasks = 64;
  std::vector<std::array<int, 2>> refit_roots_;
  std::vector<int> refit_top_;
  std::vector<Box> face_box_;  // #F, in tree order
  std::vector<Eigen::Vector3d> face_area_;  // #F, in tree order: area vectors (twice the area, along the normal)
  std::vector<Node> nodes_;    // children after their parent (refit runs backwards)
  std::vector<uint32_t> node_stamp_;  // #nodes: refit_faces() fits each node above its faces once
  std::vector<int> stamped_;
  uint32_t stamp_count_ = 0;
};

template <class Fn>
void FaceBvh::within(int n, Fn& fn, bool skip_flat) const {
  const Node& node = nodes_[n];
  if (skip_flat && node.flat) return;
  if (node.left < 0) {
    for (int i = node.begin; i < node.end; ++i)
      for (int j = i + 1; j < node.end; ++j)
        if (face_box_[i].overlaps(face_box_[j])) fn(order_[i], order_[j]);
    return;
  }
  within(node.left, fn, skip_flat);
  within(node.right, fn, skip_flat);
  between(node.left, node.right, fn, skip_flat);
}

template <class Fn>
void FaceBvh::between(int a, int b, Fn& fn, bool skip_flat) const {
  const Node& na = nodes_[a];
  const Node& nb = nodes_[b];
  if (!na.box.overlaps(nb.box)) return;
  if (skip_flat && na.flat && nb.flat && join_flat(a, b)) return;
  if (na.left < 0 && nb.left < 0) {
    for (int i = na.begin; i < na.end; ++i) {
      if (!face_box_[i].overlaps(nb.box)) continue;
      for (int j = nb.begin; j < nb.end; ++j)
        if (face_box_[i].overlaps(face_box_[j])) fn(order_[i], order_[j]);
    }
    return;
  }
  if (nb.left < 0 || (na.left >= 0 && na.end - na.begin >= nb.end - nb.begin)) {  // split the larger
    between(na.left, b, fn, skip_flat);
    between(na.right, b, fn, skip_flat);
  } else {
    between(a, nb.left, fn, skip_flat);
    between(a, nb.right, fn, skip_flat);
  }
}

template <class Fn>
void FaceBvh::with_box(int face, int n, Fn& fn) const {
  const Node& node = nodes_[n];
  const Box& box = face_box_[position_[face]];
  if (!node.box.overlaps(box)) return;
  if (node.left >= 0) {
    with_box(face, node.left, fn);
    with_box(face, node.right, fn);
    return;
  }
  for (int j = node.begin; j < node.end; ++j)
    if (order_[j] != face && box.overlaps(face_box_[j])) fn(face, order_[j]);
}

template <class Fn>
void FaceBvh::for_overlapping_pairs(Fn&& fn, bool skip_flat) const {
  if (nodes_.empty()) return;
  parallel::for_tasks(static_cast<int>(tasks_.size()), nodes_.size() > 2048, [&](int t) {
    const auto pair = [&](int f, int g) { fn(t, f, g); };
    if (tasks_[t][0] == tasks_[t][1]) within(tasks_[t][0], pair, skip_flat);
    else between(tasks_[t][0], tasks_[t][1], pair, skip_flat);
  });
}

}  // namespace gauss
