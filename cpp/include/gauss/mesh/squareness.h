#pragma once
// How square a flat region's outline is (Square Flat Regions, docs/styles.md#square-flat-regions): the
// area of the faces whose normals lie within `degrees` of `up`, over the area of the smallest square
// (any orientation about `up`) that holds their vertices, projected along `up`. 1 for a square cap,
// pi/4 = 0.785 for a round one. Used by the benchmark and the tests.
#include <Eigen/Core>
#include <cstdint>

namespace gauss {

// V: #V*3 row-major; F: #F*3 row-major vertex indices in [0, #V); up: unit. Returns 0 when no face
// faces up.
double squareness(const double* V, const int64_t* F, int num_faces, const Eigen::Vector3d& up,
                  double degrees = 10.0);

}  // namespace gauss
