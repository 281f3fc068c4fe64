#pragma once
// How stylized a mesh is: the area-weighted share of faces whose unit normal lies within
// `max_degrees` of one of the preferred normals. Used by the benchmark and the tests.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace gauss {

// V: #V*3 row-major; F: #F*3 row-major; normals: preferred unit normals. Returns a value in [0, 1]
// (0 for a mesh with zero total area).
double alignment_share(const double* V, const int64_t* F, int num_faces,
                       const std::vector<Eigen::Vector3d>& normals, double max_degrees = 10.0);

}  // namespace gauss
