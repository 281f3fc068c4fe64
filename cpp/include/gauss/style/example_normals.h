#pragma once
// An example's Gauss map as a style (the "gauss_map" kind, docs/styles.md#gauss-map): the example's
// face normals with their areas, and a nearest-normal query on the sphere (a k-d tree over the unit
// vectors: the nearest in chord length is the nearest in angle). Built once when the style is made;
// a query allocates nothing and is safe from many threads at once.
//
// Each normal's pull is its share of the example's area density: the area of the example's normals
// within kDensityRadius of it, over the largest such area, square-rooted. A face of the
// stylized mesh that snaps to a direction the example barely has is pulled less than one that snaps to
// a direction it has much of (Liu & Jacobson's Normal-Driven Spherical Shape Analogies snap every face
// alike; docs/styles.md#gauss-map says what the weighting gains).
#include <Eigen/Core>
#include <vector>

namespace gauss {

class ExampleNormals {
 public:
  static constexpr double kDensityRadius = 0.2;  // radians (about 11 degrees)

  // normals  #K unit vectors (checked by the caller);  areas  #K values >= 0 with a positive sum, or
  //   empty for equal areas. Throws std::invalid_argument on a bad area.
  ExampleNormals(const std::vector<Eigen::Vector3d>& normals, const std::vector<double>& areas);

  // Index of the normal nearest to x (any non-zero length); ties go to the lower index.
  int nearest(const Eigen::Vector3d& x) const;
  // The min(count, size()) normals nearest to x, nearest first, into index (count entries; count <=
  // kMaxNearest). Returns how many were written.
  static constexpr int kMaxNearest = 16;
  int nearest(const Eigen::Vector3d& x, int count, int* index) const;

  int size() const { return static_cast<int>(normals_.size()); }
  const std::vector<Eigen::Vector3d>& normals() const { return normals_; }
  const std::vector<double>& areas() const { return areas_; }  // normalized: sum 1
  const std::vector<double>& pull() const { return pull_; }    // in (0, 1], the largest 1

 private:
  // Normals within `radius` (chord) of x: f(index) for each.
  template <class F>
  void within(const Eigen::Vector3d& x, double radius, F&& f) const;

  std::vector<Eigen::Vector3d> normals_;
  std::vector<double> areas_, pull_;
  // The k-d tree: order_ holds normal indices; node [begin, end) splits at its middle on axis_[mid].
  std::vector<int> order_;
  std::vector<signed char> axis_;
};

}  // namespace gauss
