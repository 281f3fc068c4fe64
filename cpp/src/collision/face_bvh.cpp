#include "gauss/collision/face_bvh.h"
#include "gauss/util/constants.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iterator>

#include "gauss/util/parallel.h"

namespace gauss {

using Eigen::Vector3d;

namespace {
// The angle between two vectors (pi if either is zero).
double angle_between(const Vector3d& a, const Vector3d& b) {
  const double la = a.norm(), lb = b.norm();
  if (!(la > 0 && lb > 0)) return kPi;
  return std::acos(std::clamp(a.dot(b) / (la * lb), -1.0, 1.0));
}
}  // namespace

FaceBvh::FaceBvh(const std::vector<std::array<int, 3>>& faces, const std::vector<Vector3d>& X0)
    : faces_(&faces), order_(faces.size()), face_box_(faces.size()), face_area_(faces.size()) {
  const int n = static_cast<int>(faces.size());
  std::vector<Vector3d> centroid(n);
  for (int f = 0; f < n; ++f) {
    centroid[f] = (X0[faces[f][0]] + X0[faces[f][1]] + X0[faces[f][2]]) / 3.0;
    order_[f] = f;
  }
  nodes_.reserve(2 * (n / kLeafSize + 1));
  if (n > 0) build(0, n, -1, centroid);
  position_.resize(n);
  leaf_of_.resize(n);
  for (int i = 0; i < n; ++i) position_[order_[i]] = i;
  for (int node = 0; node < static_cast<int>(nodes_.size()); ++node)
    if (nodes_[node].left < 0)
      for (int i = nodes_[node].begin; i < nodes_[node].end; ++i) leaf_of_[i] = node;
  find_connected_nodes();
  find_node_borders();
  find_refit_tasks();
  node_stamp_.assign(nodes_.size(), 0);
  if (!nodes_.empty()) tasks_ = tasks(kTasks);
}

void FaceBvh::find_connected_nodes() {
  // A leaf: its few faces linked through shared corners. A node: both children connected and
  // sharing a corner (marked by the node's index over the left child's corners).
  const std::vector<std::array<int, 3>>& faces = *faces_;
  int num_vertices = 0;
  for (const auto& f : faces) num_vertices = std::max({num_vertices, f[0] + 1, f[1] + 1, f[2] + 1});
  std::vector<int> mark(num_vertices, -1);
  for (int n = static_cast<int>(nodes_.size()) - 1; n >= 0; --n) {  // children first
    Node& node = nodes_[n];
    if (node.left >= 0) {
      const Node &l = nodes_[node.left], &r = nodes_[node.right];
      node.connected = false;
      if (!l.connected || !r.connected) continue;
      for (int i = l.begin; i < l.end; ++i)
        for (int v : faces[order_[i]]) mark[v] = n;
      for (int i = r.begin; i < r.end && !node.connected; ++i)
        for (int v : faces[order_[i]]) node.connected = node.connected || mark[v] == n;
      continue;
    }
    // Grow a patch from the leaf's first face until nothing is added.
    int joined = 1;
    std::vector<bool> in(node.end - node.begin, false);
    in[0] = true;
    for (bool grew = true; grew;) {
      grew = false;
      for (int i = 0; i < node.end - node.begin; ++i) {
        if (in[i]) continue;
        for (int j = 0; j < node.end - node.begin && !in[i]; ++j) {
          if (!in[j]) continue;
          for (int a : faces[order_[node.begin + i]])
            for (int b : faces[order_[node.begin + j]]) in[i] = in[i] || a == b;
        }
        if (in[i]) grew = true, ++joined;
      }
    }
    node.connected = joined == node.end - node.begin;
  }
}

void FaceBvh::find_node_borders() {
  const std::vector<std::array<int, 3>>& faces = *faces_;
  int num_vertices = 0;
  for (const auto& f : faces) num_vertices = std::max({num_vertices, f[0] + 1, f[1] + 1, f[2] + 1});
  // Each vertex's faces, by their place in tree order.
  std::vector<int> start(num_vertices + 1, 0), place(3 * faces.size());
  for (const auto& f : faces)
    for (int v : f) ++start[v + 1];
  for (int v = 0; v < num_vertices; ++v) start[v + 1] += start[v];
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (size_t i = 0; i < order_.size(); ++i)
    for (int v : faces[order_[i]]) place[fill[v]++] = static_cast<int>(i);
  const auto on_border = [&](int v, const Node& node) {
    for (int k = start[v]; k < start[v + 1]; ++k)
      if (place[k] < node.begin || place[k] >= node.end) return true;
    return false;
  };
  // Children first (they come after their parent): a node's border is among its children's.
  std::vector<std::vector<int>> border(nodes_.size());
  std::vector<int> joined;
  for (int n = static_cast<int>(nodes_.size()) - 1; n >= 0; --n) {
    const Node& node = nodes_[n];
    joined.clear();
    if (node.left < 0) {
      for (int i = node.begin; i < node.end; ++i) joined.insert(joined.end(), faces[order_[i]].begin(), faces[order_[i]].end());
      std::sort(joined.begin(), joined.end());
      joined.erase(std::unique(joined.begin(), joined.end()), joined.end());
    } else {
      const std::vector<int>&l = border[node.left], &r = border[node.right];
      std::set_union(l.begin(), l.end(), r.begin(), r.end(), std::back_inserter(joined));
    }
    for (int v : joined)
      if (on_border(v, node)) border[n].push_back(v);
  }
  border_start_.assign(nodes_.size() + 1, 0);
  for (size_t n = 0; n < nodes_.size(); ++n) border_start_[n + 1] = border_start_[n] + static_cast<int>(border[n].size());
  border_.resize(border_start_.back());
  for (size_t n = 0; n < nodes_.size(); ++n) std::copy(border[n].begin(), border[n].end(), border_.begin() + border_start_[n]);
}

void FaceBvh::find_refit_tasks() {
  if (nodes_.empty()) return;
  std::vector<int> end(nodes_.size());  // the end of each node's subtree
  for (int n = static_cast<int>(nodes_.size()) - 1; n >= 0; --n) end[n] = nodes_[n].left < 0 ? n + 1 : end[nodes_[n].right];
  // Breadth first from the root, splitting the subtrees until there are enough of them.
  std::vector<int> roots{0};
  for (size_t i = 0; i < roots.size() && static_cast<int>(roots.size()) < kRefitTasks;) {
    const Node& node = nodes_[roots[i]];
    if (node.left < 0) {
      ++i;
      continue;
    }
    refit_top_.push_back(roots[i]);
    roots[i] = node.left;
    roots.push_back(node.right);
  }
  for (int root : roots) refit_roots_.push_back({root, end[root]});
  std::sort(refit_top_.begin(), refit_top_.end(), std::greater<int>());
}

template <class Fit>
void FaceBvh::fit_nodes(Fit&& fit) {
  parallel::for_tasks(static_cast<int>(refit_roots_.size()), nodes_.size() > 2048, [&](int t) {
    for (int n = refit_roots_[t][1] - 1; n >= refit_roots_[t][0]; --n) fit(n);
  });
  for (int n : refit_top_) fit(n);
}

bool FaceBvh::join_flat(int a, int b) const {
  const Node &na = nodes_[a], &nb = nodes_[b];
  // The cone around both: half of the angle between their axes and both half-angles.
  if (!(angle_between(na.area, nb.area) + na.angle + nb.angle < 2 * kFlatAngle)) return false;
  const int *i = &border_[border_start_[a]], *i_end = &border_[border_start_[a + 1]];
  const int *j = &border_[border_start_[b]], *j_end = &border_[border_start_[b + 1]];
  while (i != i_end && j != j_end) {
    if (*i == *j) return true;
    if (*i < *j) ++i;
    else ++j;
  }
  return false;
}

std::vector<std::array<int, 2>> FaceBvh::tasks(int count) const {
  // within(root) expanded breadth first: within(n) = within(left) + within(right) + between(left,
  // right); a between task stays whole.
  std::vector<std::array<int, 2>> work{{0, 0}};
  size_t i = 0;
  while (i < work.size() && static_cast<int>(work.size()) < count) {
    const int n = work[i][0];
    if (work[i][1] != n || nodes_[n].left < 0) {
      ++i;
      continue;
    }
    work[i] = {nodes_[n].left, nodes_[n].left};  // expanded further on the next pass of the loop
    work.push_back({nodes_[n].right, nodes_[n].right});
    work.push_back({nodes_[n].left, nodes_[n].right});
  }
  return work;
}

int FaceBvh::build(int begin, int end, int parent, const std::vector<Vector3d>& centroid) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back(Node{Box{}, begin, end, -1, -1, parent, false, false, false, Vector3d::Zero(), kPi});
  if (end - begin > kLeafSize) {
    Vector3d lo = centroid[order_[begin]], hi = lo;
    for (int i = begin + 1; i < end; ++i) {
      lo = lo.cwiseMin(centroid[order_[i]]);
      hi = hi.cwiseMax(centroid[order_[i]]);
    }
    int axis;
    (hi - lo).maxCoeff(&axis);
    const int mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](int f, int g) { return centroid[f][axis] < centroid[g][axis]; });
    const int left = build(begin, mid, index, centroid);
    const int right = build(mid, end, index, centroid);
    nodes_[index].left = left;
    nodes_[index].right = right;
  }
  return index;
}

int64_t FaceBvh::bytes_needed(int64_t num_faces) {
  // A face's box (24 bytes), its place in the order and back and its leaf (12) and its centroid while
  // building (24), and its area vector (24); per leaf a share of the tree: 2 nodes, each with a stamp
  // and a place in a list. The nodes' borders: about 7 corners a face on the armadillos, Spot and the
  // camel head (room for 8), twice while they are made, with each vertex's faces (12 bytes a face),
  // and per node a list and its start.
  const int64_t nodes = 2 * (num_faces / kLeafSize + 1);
  return (84 + 2 * 32 + 12) * num_faces + nodes * static_cast<int64_t>(sizeof(Node) + 8 + sizeof(std::vector<int>) + 4);
}

namespace {
// A float at most x (below) or at least x (above), within 2^-22 of |x|: x moved outwards by more
// than the conversion's rounding (half a float step, at most 2^-24 |x|) before it is converted, so
// a box so rounded holds the double one. No branch: the conversion's rounding goes either way at
// random, and a branch on it (or std::nextafter, a call into libm) was a tenth of a check's time on
// the 43K armadillo. The tiny term keeps 0 on its side. Beyond the float's range (far outside the
// guard's frame, whose longest side is 1) a bound becomes infinite: such a box then overlaps every box
// that also reaches past the range, so no pair there is missed either.
constexpr double kOutwards = 1.0 / (1 << 23);
float below(double x) { return static_cast<float>(x - (std::abs(x) * kOutwards + 1e-30)); }
float above(double x) { return static_cast<float>(x + (std::abs(x) * kOutwards + 1e-30)); }
}  // namespace

void FaceBvh::fit_face_box(int i, const std::vector<Vector3d>& X, double margin) {
  const std::array<int, 3>& face = (*faces_)[order_[i]];
  const Vector3d& a = X[face[0]];
  const Vector3d& b = X[face[1]];
  const Vector3d& c = X[face[2]];
  const Vector3d lo = a.cwiseMin(b).cwiseMin(c).array() - margin, hi = a.cwiseMax(b).cwiseMax(c).array() + margin;
  for (int k = 0; k < 3; ++k) {
    face_box_[i].lo[k] = below(lo[k]);
    face_box_[i].hi[k] = above(hi[k]);
  }
}

void FaceBvh::fit_face(int i, const std::vector<Vector3d>& X, double margin) {
  fit_face_box(i, X, margin);
  const std::array<int, 3>& face = (*faces_)[order_[i]];
  const Vector3d& a = X[face[0]];
  face_area_[i] = (X[face[1]] - a).cross(X[face[2]] - a);
}


void FaceBvh::fit_node_box(int n) {
  Node& node = nodes_[n];
  if (node.left >= 0) {
    node.box = nodes_[node.left].box;
    node.box.merge(nodes_[node.right].box);
    return;
  }
  node.box = face_box_[node.begin];
  for (int i = node.begin + 1; i < node.end; ++i) node.box.merge(face_box_[i]);
}

void FaceBvh::fit_node(int n, const std::vector<uint8_t>& flat_corners) {
  Node& node = nodes_[n];
  fit_node_box(n);
  if (node.left >= 0) {
    const Node &l = nodes_[node.left], &r = nodes_[node.right];
    node.unfolded = l.unfolded && r.unfolded;
    node.area = l.area + r.area;
    node.angle = std::min(kPi, std::max(angle_between(node.area, l.area) + l.angle,
                                        angle_between(node.area, r.area) + r.angle));
  } else {
    node.unfolded = true;
    for (int i = node.begin; i < node.end; ++i)
      for (int v : (*faces_)[order_[i]]) node.unfolded = node.unfolded && flat_corners[v];
    node.area = face_area_[node.begin];
    for (int i = node.begin + 1; i < node.end; ++i) node.area += face_area_[i];
    // The widest angle from the smallest cosine: one arc cosine a leaf.
    double least = 1;
    const double length = node.area.norm();
    for (int i = node.begin; i < node.end; ++i) {
      const double cosine = node.area.dot(face_area_[i]) / (length * face_area_[i].norm());
      if (!(cosine > -1)) {  // opposite, or a zero area (NaN): pi, as angle_between() takes it
        least = -1;
        break;
      }
      least = std::min(least, cosine);
    }
    node.angle = std::acos(least);
  }
  node.flat = node.connected && node.unfolded && node.angle < kFlatAngle;
}

void FaceBvh::refit(const std::vector<Vector3d>& X, double margin, const std::vector<uint8_t>& flat_corners) {
  parallel::for_each(static_cast<int>(face_box_.size()), parallel::kMinParallelItems,
                     [&](int i) { fit_face(i, X, margin); });
  fit_nodes([&](int n) { fit_node(n, flat_corners); });
}

void FaceBvh::refit_boxes(const std::vector<Vector3d>& X, double margin) {
  parallel::for_each(static_cast<int>(face_box_.size()), parallel::kMinParallelItems,
                     [&](int i) { fit_face_box(i, X, margin); });
  fit_nodes([&](int n) { fit_node_box(n); });
}

void FaceBvh::refit_faces(const std::vector<int>& faces, const std::vector<Vector3d>& X, double margin) {
  for (int f : faces) fit_face_box(position_[f], X, margin);
  // Each node above them once, children first (they come after their parent). Their boxes alone:
  // the normal cones serve for_overlapping_pairs(), which comes after a whole refit().
  const uint32_t stamp = ++stamp_count_;
  stamped_.clear();
  for (int f : faces)
    for (int n = leaf_of_[position_[f]]; n >= 0 && node_stamp_[n] != stamp; n = nodes_[n].parent) {
      node_stamp_[n] = stamp;
      stamped_.push_back(n);
    }
  std::sort(stamped_.begin(), stamped_.end(), std::greater<int>());
  for (int n : stamped_) fit_node_box(n);
}

}  // namespace gauss
