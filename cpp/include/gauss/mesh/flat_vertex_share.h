#pragma once
// The share of a mesh's interior vertices that are intrinsically flat: whose angle defect
// 2 pi - (sum of the corner angles around the vertex) is below `max_defect` radians in magnitude. A
// developable surface has zero defect everywhere (its Gaussian curvature is zero) except at the
// creases' ends and cone tips. Boundary vertices (on an edge with one face) are not counted, nor
// vertices no face uses. Used by the benchmark and the tests.
#include <cstdint>

namespace gauss {

// V: #V*3 row-major; F: #F*3 row-major vertex indices in [0, #V). Faces with a repeated corner are
// skipped. Returns a value in [0, 1] (0 when no vertex counts).
double flat_vertex_share(const double* V, int num_vertices, const int64_t* F, int num_faces,
                         double max_defect = 0.01);

}  // namespace gauss
