#pragma once
// Square Flat Regions (settings::square_flat_regions): the large flat regions of the rest mesh, the
// axes their outlines should square to, and for the faces around each one the turn that squares it.
//
// A flat region is a set of edge-connected faces whose normals lie within kFlatDegrees of the first
// face's (and of the face they were reached from), of at least kMinAreaShare of the mesh's area (and a
// dozen faces). Its axes u, v are those of the smallest rectangle around its outline, in its plane; an outline with no
// clear smallest rectangle (a circle, a regular polygon) takes the one closest to the object's own
// axes. Each face within a band around the region (kBandWidth times the square root of the region's
// area, measured along edges from its outline, on both sides of it) is asked to turn about the
// region's normal N by the angle that takes its direction in the plane onto the nearest of +-u, +-v:
// a wall's own normal in the plane, a face of the region (or one nearly parallel to it) the outward
// direction of its nearest outline. Walls turn square (a sloping shoulder too, its slope kept), and
// the region's rim turns with them, so its outline straightens. This is what the Gauss Cube style does
// to a cap at high lambda: the walls turn to the axes.
//
// Everything is found once, on the rest mesh: the regions are what the user modelled flat, and targets
// that do not move with the iterate keep each method's step one fixed map (convergence, replay).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "gauss/mesh/mesh_topology.h"

namespace gauss {

// Why these values: docs/styles.md#square-flat-regions.
inline constexpr double kFlatDegrees = 5.0;    // normals of one region agree within this
inline constexpr double kMinAreaShare = 0.03;  // a region holds at least this share of the mesh's area
inline constexpr double kBandWidth = 0.5;     // the band's width over sqrt(region area)

struct FlatRegion {
  Eigen::Vector3d normal;  // unit, area-weighted mean of its faces' normals
  Eigen::Vector3d u, v;    // unit, orthogonal to normal and to each other: the outline's axes
  double area = 0;
};

struct SquareTargets {
  std::vector<FlatRegion> regions;
  // The faces with a target (topo.faces numbering), each with the rotation about its region's normal
  // that squares it, and its weight: its area times a fall-off from 1 at the outline to 0 at the
  // band's edge.
  std::vector<int> face;
  std::vector<Eigen::Matrix3d> rotation;
  std::vector<double> weight;
};

//   topo  the mesh;  X  #V rest positions (any frame; the solver's is normalized)
// Returns no region (and no target) for a mesh without a large flat part.
SquareTargets square_targets(const MeshTopology& topo, const std::vector<Eigen::Vector3d>& X);

}  // namespace gauss
