#pragma once
// The normal each face prefers under a developable ("sheet metal") style: its own normal turned onto
// the great circle its neighbours' normals lie closest to, so that the surface bends about one axis
// at a time, as rolled or folded sheet does (a developable surface's normals around a point lie on a
// curve of the sphere with no spread across it).
//
// At each vertex v the ruling direction a_v is the eigenvector of the smallest eigenvalue of
// sum area n n^T over v's two rings of faces (each face around v adds the stars of its three corners;
// one ring alone gave rulings too noisy to agree between neighbours, docs/styles.md#sheet-metal):
// the direction the normals there spread least along. A
// face's preferred normal is its normal with the part along the ruling of each of its three corners
// removed (their mean, normalized): each star's normals are pulled onto one great circle, which is
// what makes it developable. On a flat or rolled patch n_f has no part along any ruling, so the face
// prefers its own normal. Four passes over faces and vertices; no allocation.
#include <Eigen/Core>
#include <vector>

#include "gauss/mesh/mesh_topology.h"

namespace gauss {

//   topo  the mesh (#F faces, #V vertices);  X  #V positions
//   moment  #V (scratch, sized by the caller): sum over each vertex's faces of 2 area n n^T
//   ruling  #V (output, sized by the caller): unit a_v; 0 at a vertex without a face of non-zero area
//   preferred  #F (output, sized by the caller): unit; a degenerate face gets +Z (it is never styled)
void developable_normals(const MeshTopology& topo, const std::vector<Eigen::Vector3d>& X,
                         std::vector<Eigen::Matrix3d>& moment, std::vector<Eigen::Vector3d>& ruling,
                         std::vector<Eigen::Vector3d>& preferred);

}  // namespace gauss
