#pragma once
// Sets of unit vectors the C++ tests of many-normal styles share.
#include <Eigen/Core>
#include <random>
#include <vector>

namespace gauss_test {

// n directions uniformly distributed on the unit sphere (normalized Gaussian vectors), reproducible
// from the seed.
inline std::vector<Eigen::Vector3d> random_directions(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::vector<Eigen::Vector3d> out(n);
  for (Eigen::Vector3d& d : out) d = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
  return out;
}

}  // namespace gauss_test
