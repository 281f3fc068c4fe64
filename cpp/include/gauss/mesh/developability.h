#pragma once
// How far a mesh is from developable (bending in one direction at a time): at each vertex, the
// smallest eigenvalue of the area-weighted second moment of its faces' unit normals,
//   C_v = sum_f A_f n_f n_f^T / sum_f A_f   over the faces f around v,
// averaged over the vertices that faces use. 0 where the normals around a vertex lie on one great
// circle (flat, or folded or rolled about one axis); at most 1/3 (normals spread evenly over three
// directions, as at a cube's corner). Used by the benchmark and the tests.
#include <cstdint>

namespace gauss {

// V: #V*3 row-major; F: #F*3 row-major vertex indices in [0, #V). Faces of zero area are skipped;
// vertices without a face of non-zero area are not counted. Returns 0 when no vertex counts.
double developability(const double* V, int num_vertices, const int64_t* F, int num_faces);

}  // namespace gauss
