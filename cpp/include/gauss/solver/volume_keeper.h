#pragma once
// Keep Volume: stylization shrinks a mesh (the paper lists it as a limitation); after each
// step this scales every component uniformly about its vertex centroid back to its rest size.
//
// Size: a closed component (no boundary edge) keeps its signed volume (sum over its triangles of
// a . (b x c) / 6, about its centroid), an open one its surface area. Left alone: components with a pin
// (scaling would move the pins), components whose rest size is degenerate (a flat closed surface has
// no volume to keep), and, in a step, a component whose size is not within kMaxRatio of its rest size
// (turned inside out or collapsed: scaling it would divide by ~0 or blow it up). So the scale factor
// of a step lies within [kMaxRatio^-1/2, kMaxRatio^1/2] for areas, its cube root for volumes.
//
// Usage (positions in the solver's numbering and frame):
//   VolumeKeeper keeper(topo, rest, pinned);   // rest sizes, O(#F)
//   keeper.restore(topo, X);                   // per step, no allocation
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "gauss/mesh/mesh_topology.h"

namespace gauss {

class VolumeKeeper {
 public:
  // A size is degenerate below this fraction of the component's bounding-box extent (cubed for
  // volumes, squared for areas).
  static constexpr double kDegenerate = 1e-9;
  // Largest ratio between a component's size in a step and its rest size that is still corrected.
  static constexpr double kMaxRatio = 8.0;

  VolumeKeeper() = default;
  // topo  the mesh (faces, edges with their face slots, component of every vertex)
  // rest  #V by 3 rest positions;  pinned  #P vertex indices (components containing one are left alone)
  VolumeKeeper(const MeshTopology& topo, const std::vector<Eigen::Vector3d>& rest, const std::vector<int64_t>& pinned);

  // Scales each kept component of X (#V by 3) about its vertex centroid to its rest size.
  // topo: the one this was built with.
  void restore(const MeshTopology& topo, std::vector<Eigen::Vector3d>& X);

  // Components this keeps (not pinned, not degenerate), and how many of them are closed.
  int num_kept() const { return num_kept_; }
  int num_closed() const { return num_closed_; }

 private:
  // Volumes (closed) or areas (open) of every component of X, about its vertex centroid; fills
  // centroid_ and size_.
  void measure(const MeshTopology& topo, const std::vector<Eigen::Vector3d>& X);

  std::vector<uint8_t> closed_;          // #C
  std::vector<double> rest_size_;        // #C: rest volume or area; 0 = left alone
  int num_kept_ = 0, num_closed_ = 0;
  // Per-step buffers.
  std::vector<Eigen::Vector3d> centroid_;  // #C
  std::vector<int> count_;                 // #C vertices
  std::vector<double> size_;               // #C
  std::vector<double> factor_;             // #C: scale factor of this step (1 = untouched)
};

}  // namespace gauss
