#pragma once
// Carries a deformation of a proxy (proxy_mesh.h) to the fine mesh, every live tick.
//
// A fine vertex i rides on proxy face t at barycentric weights b with rest offset d_i (proxy_mesh.h):
//   x_i = sum_k b_k p_k + (sum_k b_k R_k) d_i,
// p_k the deformed proxy corners and R_k their rotations: each proxy face's rotation from its rest
// frame (first edge, normal) to its deformed one, averaged over a vertex's faces by their rest areas
// (as quaternions, normalized). So sculpted detail turns with the surface it sits on instead of
// being smeared, and the blend of the three corners' rotations keeps it continuous across faces.
// At the rest shape, and under a rigid motion of the proxy, the fine mesh comes out exactly (up to
// float rounding) at its rest shape moved the same way.
//
// proxy_transfer_precomputation once, then proxy_transfer per tick: no allocation, parallel on the
// solver's thread pool (util/parallel.h).
#include <array>
#include <vector>

#include <Eigen/Core>

#include "gauss/proxy/proxy_mesh.h"

namespace gauss {

struct ProxyTransfer {
  int num_proxy_vertices = 0;
  std::vector<std::array<int, 3>> faces;           // #G proxy faces
  std::vector<Eigen::Matrix3f> rest_frame;         // #G: columns first edge, second axis, normal (rest)
  std::vector<int> vertex_face_start, vertex_face; // proxy vertex -> its faces (CSR)
  std::vector<float> vertex_face_weight;           // the faces' rest areas, in the same order
  std::vector<int> fine_face;                      // #V, as ProxyMesh
  std::vector<std::array<float, 2>> fine_bary;     // #V
  std::vector<std::array<float, 3>> fine_offset;   // #V
  // Scratch of proxy_transfer, sized here so that a tick allocates nothing.
  std::vector<Eigen::Vector4f> face_rotation;      // #G quaternions (w, x, y, z)
  std::vector<Eigen::Matrix3f> vertex_rotation;    // #P
  std::vector<Eigen::Vector3f> proxy_position;     // #P
  int num_fine_vertices() const { return static_cast<int>(fine_face.size()); }
};

// proxy: proxy_mesh's result (its map is copied). Throws std::invalid_argument if it is inconsistent.
ProxyTransfer proxy_transfer_precomputation(const ProxyMesh& proxy);

// P: #P by 3 deformed proxy positions (row-major, float or double); out: #V by 3 fine positions
// (row-major float), written. data's scratch is overwritten, so one ProxyTransfer serves one caller
// at a time.
void proxy_transfer(ProxyTransfer& data, const float* P, float* out);
void proxy_transfer(ProxyTransfer& data, const double* P, float* out);

}  // namespace gauss
