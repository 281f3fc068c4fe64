#pragma once
// Combinatorics the solver needs, built once per mesh in flat arrays (CSR), so that the per-step
// loops never search or allocate.
#include <array>
#include <cstdint>
#include <vector>

#include "gauss/util/progress.h"

namespace gauss {

struct MeshTopology {
  int num_vertices = 0;
  // Triangles the solver works on: the input faces without a repeated vertex index.
  std::vector<std::array<int, 3>> faces;   // #F by 3
  std::vector<int> input_face;             // #F: index of each face in the caller's face array
  // Slot k of face f is its directed edge faces[f][k] -> faces[f][(k+1)%3].
  std::vector<std::array<int, 2>> edges;   // #E by 2, undirected edges stored as (lo, hi)
  std::vector<std::array<int, 3>> face_edge;       // #F by 3: edge index of each slot
  std::vector<std::array<int8_t, 3>> face_edge_sign;  // +1 if the slot runs lo -> hi, else -1
  // Edge -> face slots (face*3 + k), sorted, in CSR form.
  std::vector<int> edge_slot_start, edge_slots;
  // Vertex -> incident faces, as face*3 + corner, sorted, in CSR form.
  std::vector<int> vertex_corner_start, vertex_corners;
  // Face-connected component of every vertex (-1 for vertices no face references).
  std::vector<int> component;
  int num_components = 0;
};

// F: #F_in by 3 vertex indices (row-major, int64 for generality), each in [0, num_vertices).
// Throws std::invalid_argument if an index is out of range or no usable face remains, Cancelled
// (progress.h) between its stages once `progress` is cancelled.
MeshTopology build_mesh_topology(int num_vertices, const int64_t* F, int num_input_faces,
                                 const Progress* progress = nullptr);

}  // namespace gauss
