#pragma once
// A cache-friendly numbering of a mesh: vertices along a Morton (Z-order) curve of their positions,
// faces by their first vertex in that numbering. The solver's passes gather from neighbours; with
// scanned meshes stored in acquisition order, renumbering turns most of those gathers into cache hits.
#include <cstdint>
#include <vector>

namespace gauss {

// V: #V*3 row-major; F: #F*3 row-major (indices already range-checked).
// new_of_old_vertex: #V, a permutation. face_order: #F, old face index of each new face.
void spatial_order(const double* V, int num_vertices, const int64_t* F, int num_faces,
                   std::vector<int>& new_of_old_vertex, std::vector<int>& face_order);

// The vertices' numbering alone (spatial_order's first output), for callers that keep their faces.
void spatial_vertex_order(const double* V, int num_vertices, std::vector<int>& new_of_old_vertex);

}  // namespace gauss
