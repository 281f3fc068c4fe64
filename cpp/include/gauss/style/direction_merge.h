#pragma once
// Merging near-parallel directions on the unit sphere: greedy clustering around seeds.
//
// Seeds are taken in order of decreasing weight (ties: smaller direction first, lexicographically);
// each seed claims every not yet claimed direction within max_angle of it. So every input lies within
// max_angle of its cluster's seed, any two seeds are more than max_angle apart, and the result depends
// on the inputs as a set, not on their order (identical inputs are interchangeable). A 3D grid of
// cells of the seed's reach keeps it O(K log K).
//
// Used by PreferenceFunction for styles with many normals (normal_field.h) and by
// gauss_core.merge_directions for the add-on's "From Selected Faces".
#include <Eigen/Core>
#include <vector>

namespace gauss {

struct MergedDirections {
  std::vector<Eigen::Vector3d> directions;  // #M unit vectors: each cluster's weighted mean direction
  std::vector<double> weights;              // #M: summed input weights of each cluster
  std::vector<int> cluster_of;              // #K: cluster of each input (seed order)
};

// Below this angle (radians) only identical directions merge: a finer grid would not fit its keys.
constexpr double kMinMergeAngle = 1e-6;

// D: #K unit directions (finite, length 1 up to rounding); weights: #K finite values >= 0, or empty
// for all 1; max_angle: radians in [0, pi/2]. Throws std::invalid_argument otherwise.
// A cluster's direction is its members' weighted mean, normalized (its seed if all weights are 0).
MergedDirections merge_directions(const std::vector<Eigen::Vector3d>& D, const std::vector<double>& weights,
                                  double max_angle);

// The same clustering restricted to the inputs listed in `subset` (indices into D); cluster_of has
// one entry per subset item.
MergedDirections merge_directions(const std::vector<Eigen::Vector3d>& D, const std::vector<double>& weights,
                                  const std::vector<int>& subset, double max_angle);

}  // namespace gauss
