#pragma once
// A proxy of a large mesh for live stylization: a simplified copy of about `target_vertices` vertices
// that keeps the silhouette and the creases, and the map from every fine vertex onto it
// (proxy_transfer.h carries a deformation of the proxy back to the fine mesh through that map).
//
// The proxy is made by half-edge collapses (a vertex u merged into a neighbour v, which stays where it
// is), cheapest first by the quadric error of Garland and Heckbert: flat parts lose their vertices
// before curved ones, and a boundary loses vertices only along itself. So every proxy vertex is a
// vertex of the fine mesh. Collapses run in passes: each pass ranks every vertex's cheapest collapse
// and tries the cheap half of them (a vertex merged into is locked until the next pass, whose
// adjacency is rebuilt), refusing those that would make the surface non-manifold (the link
// condition), flip or crush a triangle, or duplicate a face. Chunks of space collapse in parallel
// (proxy_mesh.cpp); the result does not depend on the thread count. Vertices on non-manifold edges or of
// non-manifold fans never move; a connected part keeps at least a tetrahedron.
//
// Each fine vertex is mapped to the closest point of the proxy faces around the proxy vertex it was
// collapsed into (its faces, and its neighbours' too where that point lies on a face's rim): the face,
// the point's barycentric coordinates, and the offset from that point to the fine vertex (the sculpted
// detail), in rest coordinates.
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "gauss/util/progress.h"

namespace gauss {

struct ProxyMesh {
  std::vector<Eigen::Vector3d> vertices;   // #P rest positions of the proxy (those of fine vertices)
  std::vector<std::array<int, 3>> faces;   // #G proxy triangles, indices into `vertices`
  std::vector<int> fine_of_proxy;          // #P: the fine vertex each proxy vertex is
  // Per fine vertex (#V): the proxy face it rides on (-1: in no face of the input, it stays put), the
  // barycentric weights of that face's corners 1 and 2 (corner 0: 1 - b1 - b2), and the offset from
  // that point to the fine vertex (for a vertex in no face: its rest position).
  std::vector<int> fine_face;
  std::vector<std::array<float, 2>> fine_bary;
  std::vector<std::array<float, 3>> fine_offset;
};

// V: #V by 3 fine rest positions (row-major), F: #F by 3 vertex indices (row-major; faces with a
// repeated index are skipped), target_vertices >= 4: stop collapsing at this many vertices (fewer
// are never made; more remain when no allowed collapse is left). A mesh at or below the target
// comes back whole. Throws std::invalid_argument for an index out of range, a non-finite position or
// no usable face; Cancelled (progress.h) between passes once `progress` is cancelled.
ProxyMesh proxy_mesh(const double* V, int num_vertices, const int64_t* F, int num_faces, int target_vertices,
                     const Progress* progress = nullptr);

}  // namespace gauss
