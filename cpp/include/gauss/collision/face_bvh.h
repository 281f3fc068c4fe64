#pragma once
// A bounding-volume hierarchy over a mesh's faces, built once and refitted to new positions: the
// faces' axis-aligned boxes, and a binary tree built top-down on the faces' centroids at X0 (split at
// the median of the longest side). A stylization moves every vertex a little, so after a run each
// node is still a compact patch: the tree stays tight without a rebuild, and a refit costs one pass
// over the faces.
//
// Flat patches (Volino and Magnenat-Thalmann's normal cones): a connected patch whose face normals all
// lie within less than a right angle of one axis is a height field over the plane normal to it, so
// two of its faces can only meet where their projections overlap: around a corner whose star folds
// (which the caller tests: self_intersection.h), or where the patch winds around the axis like a
// spiral ramp, which the contour test of Volino and Magnenat-Thalmann would catch and which a node of
// this tree (a compact cluster, rest-shape neighbours) does not form. for_overlapping_pairs(fn, true)
// skips the pairs inside such nodes; most neighbouring faces on a smooth or stylized surface are.
//
// Usage:
//   FaceBvh bvh(topo.faces, X0);             // once (allocates); X0 #V by 3
//   bvh.refit(X, margin);                    // per check: boxes of the faces at X (#V by 3), grown by margin
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

  void refit(const std::vector<Eigen::Vector3d>& X, double margin);
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

 private:
  struct Node {
    Box box;
    int begin, end;   // the faces order_[begin, end)
    int left, right;  // child nodes, -1 for a leaf
    int parent;       // -1 for the root
    bool connected;   // its faces form one patch (through shared corners)
    bool flat;        // connected, and its normal cone's half-angle is below kFlatAngle (at the last refit)
    Eigen::Vector3d area;  // sum of its faces' area vectors (the cone's axis)
    double angle;          // the cone's half-angle (pi when unknown)
  };
  static constexpr double kFlatAngle = 1.4;  // radians (80 degrees): a right angle, less a margin
  static constexpr int kLeafSize = 4;

  int build(int begin, int end, int parent, const std::vector<Eigen::Vector3d>& centroid);
  void fit_face(int i, const std::vector<Eigen::Vector3d>& X, double margin);  // i: place in tree order
  void fit_face_box(int i, const std::vector<Eigen::Vector3d>& X, double margin);  // its box alone
  void fit_node(int n);      // its box and its normal cone
  void fit_node_box(int n);  // its box alone
  // The pairs within node n (a != b: between nodes a and b), depth first.
  template <class Fn>
  void within(int n, Fn& fn, bool skip_flat) const;
  template <class Fn>
  void between(int a, int b, Fn& fn) const;
  template <class Fn>
  void with_box(int face, int n, Fn& fn) const;
  // Node pairs (n, n) and (a, b) whose pairs together are all pairs, about `count` of them, for
  // threads to share.
  std::vector<std::array<int, 2>> tasks(int count) const;
  void find_connected_nodes();

  const std::vector<std::array<int, 3>>* faces_ = nullptr;
  std::vector<int> order_;     // #F: the faces in tree order
  std::vector<int> position_;  // #F: each face's place in order_
  std::vector<int> leaf_of_;   // #F (tree order): the leaf that holds it
  // tasks(kTasks), fixed with the tree. Threads take them round-robin and their sizes differ widely,
  // so there are many (docs/performance.md#avoiding-self-intersections).
  static constexpr int kTasks = 512;
  std::vector<std::array<int, 2>> tasks_;
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
  between(node.left, node.right, fn);
}

template <class Fn>
void FaceBvh::between(int a, int b, Fn& fn) const {
  const Node& na = nodes_[a];
  const Node& nb = nodes_[b];
  if (!na.box.overlaps(nb.box)) return;
  if (na.left < 0 && nb.left < 0) {
    for (int i = na.begin; i < na.end; ++i) {
      if (!face_box_[i].overlaps(nb.box)) continue;
      for (int j = nb.begin; j < nb.end; ++j)
        if (face_box_[i].overlaps(face_box_[j])) fn(order_[i], order_[j]);
    }
    return;
  }
  if (nb.left < 0 || (na.left >= 0 && na.end - na.begin >= nb.end - nb.begin)) {  // split the larger
    between(na.left, b, fn);
    between(na.right, b, fn);
  } else {
    between(a, nb.left, fn);
    between(a, nb.right, fn);
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
    else between(tasks_[t][0], tasks_[t][1], pair);
  });
}

}  // namespace gauss
