#pragma once
// Whether two triangles of one mesh pass through each other, in the sense Blender's 3D-Print toolbox
// counts (mathutils.bvhtree.BVHTree.overlap of a mesh with itself): the triangles cross along a
// segment of positive length. Touching in a shared vertex or edge is not crossing, nor is lying in one
// plane (Blender's test skips coplanar pairs too; planes less than 1e-9 radians apart count as one).
//
//   a, b   the two triangles' corners (3 each), in one frame
//   shared the number of corners they share (0, 1 or 2; found by index by the caller): a shared
//          corner is a[0] and b[0], two shared corners a[0] = b[0] and a[1] = b[1]
//
// triangles_cross(a, b, shared): whether they cross. Two triangles sharing an edge never cross (they
// meet along it; folding one onto the other makes them coplanar). Two sharing a corner cross when
// their planes' common line leaves the corner into both triangles.
//
// triangles_closer_than(a, b, shared, margin): whether they cross, or (sharing no corner) come
// closer than `margin`. The guard that keeps a run free of new crossings (self_intersection.h) keeps
// pairs apart by this margin, so that rounding (Blender stores float32) cannot turn a near contact
// into a crossing.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace gauss {

using Triangle = Eigen::Matrix3d;  // columns: the three corners

bool triangles_cross(const Triangle& a, const Triangle& b, int shared);

bool triangles_closer_than(const Triangle& a, const Triangle& b, int shared, double margin);

// The distance between two triangles (0 if they meet), sharing no corner.
double triangle_distance(const Triangle& a, const Triangle& b);

}  // namespace gauss
