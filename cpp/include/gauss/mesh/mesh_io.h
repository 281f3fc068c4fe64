#pragma once
// Minimal triangle-mesh reading/writing for the benchmark and the C++ tests (the add-on gets its
// arrays from Blender). OBJ: v and f lines (polygons fan-triangulated, v/vt/vn and negative indices
// handled, indices by position only). PLY: ascii or binary little/big endian, vertex x y z, face
// vertex_indices lists. Throws std::runtime_error with the file name on anything unreadable.
#include <cstdint>
#include <string>
#include <vector>

namespace gauss {

struct TriangleMesh {
  std::vector<double> V;   // #V*3, row-major
  std::vector<int64_t> F;  // #F*3, row-major
  int num_vertices() const { return static_cast<int>(V.size() / 3); }
  int num_faces() const { return static_cast<int>(F.size() / 3); }
};

TriangleMesh read_mesh(const std::string& path);  // by extension: .obj or .ply
void write_obj(const std::string& path, const TriangleMesh& mesh);

}  // namespace gauss
