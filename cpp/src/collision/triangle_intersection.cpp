#include "gauss/collision/triangle_intersection.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gauss {

using Eigen::Vector3d;

namespace {

// Signed distances (scaled by |n|) of t's corners from the plane through `origin` with normal n. The
// first `shared` corners lie on the plane by construction (they are corners of the plane's triangle):
// they get an exact 0, which a product of rounded coordinates would not give; so does a corner within
// `on_plane` (rounding: two faces of one flat region are coplanar, not crossing by 1e-17).
Vector3d plane_sides(const Vector3d& n, const Vector3d& origin, const Triangle& t, int shared, double on_plane) {
  Vector3d d;
  for (int i = 0; i < 3; ++i) {
    d[i] = i < shared ? 0.0 : n.dot(t.col(i) - origin);
    if (std::abs(d[i]) <= on_plane) d[i] = 0.0;
  }
  return d;
}

// How far off a plane counts as on it, for sides scaled by |n| (n a triangle's area vector): a
// relative 1e-12 of the pair's size, a thousand roundings of the coordinates.
double on_plane_tolerance(const Vector3d& n, const Triangle& a, const Triangle& b) {
  double size = 0;
  for (int i = 0; i < 3; ++i)
    size = std::max({size, (a.col(i) - a.col(0)).cwiseAbs().maxCoeff(), (b.col(i) - a.col(0)).cwiseAbs().maxCoeff()});
  return 1e-12 * size * n.norm();
}

bool one_side(const Vector3d& d) { return (d.array() > 0).all() || (d.array() < 0).all(); }

// The interval the triangle covers on the line of direction u through `origin`: the points where its
// edges cross the other plane (sides d) and its corners on it, as parameters along u from origin.
void line_interval(const Triangle& t, const Vector3d& d, const Vector3d& u, const Vector3d& origin, double& lo,
                   double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  double p[3];
  for (int i = 0; i < 3; ++i) p[i] = u.dot(t.col(i) - origin);
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0) {
      lo = std::min(lo, p[i]);
      hi = std::max(hi, p[i]);
    }
    const int j = (i + 1) % 3;
    if ((d[i] > 0 && d[j] < 0) || (d[i] < 0 && d[j] > 0)) {
      const double x = p[i] + (p[j] - p[i]) * (d[i] / (d[i] - d[j]));
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
  }
}

// Closest distance between segments p0-p1 and q0-q1 (Ericson, Real-Time Collision Detection, 5.1.9).
double segment_distance(const Vector3d& p0, const Vector3d& p1, const Vector3d& q0, const Vector3d& q1) {
  const Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0, t = 0;
  if (a <= 0 && e <= 0) return r.norm();
  if (a <= 0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= 0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return ((p0 + s * d1) - (q0 + t * d2)).norm();
}

// Distance from p to the triangle (Ericson 5.1.5, closest point by Voronoi regions).
double point_triangle_distance(const Vector3d& p, const Triangle& t) {
  const Vector3d a = t.col(0), b = t.col(1), c = t.col(2);
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + ab * (d1 / (d1 - d3)))).norm();
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + ac * (d2 / (d2 - d6)))).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm();
  const double denom = va + vb + vc;
  if (!(denom > 0)) return std::min({ap.norm(), bp.norm(), cp.norm()});  // degenerate triangle
  return (p - (a + ab * (vb / denom) + ac * (vc / denom))).norm();
}

}  // namespace

bool triangles_cross(const Triangle& a, const Triangle& b, int shared) {
  if (shared >= 2) return false;
  const Vector3d na = (a.col(1) - a.col(0)).cross(a.col(2) - a.col(0));
  const Vector3d nb = (b.col(1) - b.col(0)).cross(b.col(2) - b.col(0));
  const Vector3d db = plane_sides(na, a.col(0), b, shared, on_plane_tolerance(na, a, b));
  if (one_side(db) || db.isZero(0.0)) return false;  // apart, or coplanar (not counted, as in Blender)
  const Vector3d da = plane_sides(nb, b.col(0), a, shared, on_plane_tolerance(nb, a, b));
  if (one_side(da) || da.isZero(0.0)) return false;
  // Planes within kParallel radians of each other are one plane: a corner within rounding of the other
  // plane (plane_sides) could then lie anywhere across their common line, far from it, and two faces
  // of one gently curved region, sharing a corner, would cross by rounding.
  constexpr double kParallel = 1e-9;
  const Vector3d u = na.cross(nb);
  if (!(u.norm() > kParallel * na.norm() * nb.norm())) return false;
  // Both intervals on the planes' common line, measured from one point; a shared corner lies on the
  // line at 0 in both.
  double lo_a, hi_a, lo_b, hi_b;
  line_interval(a, da, u, a.col(0), lo_a, hi_a);
  line_interval(b, db, u, a.col(0), lo_b, hi_b);
  return std::min(hi_a, hi_b) > std::max(lo_a, lo_b);
}

double triangle_distance(const Triangle& a, const Triangle& b) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    best = std::min(best, point_triangle_distance(a.col(i), b));
    best = std::min(best, point_triangle_distance(b.col(i), a));
    for (int j = 0; j < 3; ++j)
      best = std::min(best, segment_distance(a.col(i), a.col((i + 1) % 3), b.col(j), b.col((j + 1) % 3)));
  }
  return best;
}

bool triangles_closer_than(const Triangle& a, const Triangle& b, int shared, double margin) {
  if (shared > 0) return triangles_cross(a, b, shared);  // they meet in their shared corner by construction
  // Apart by more than the margin along some direction: neither crossing nor closer. First along the
  // line between their centroids, which separates most neighbours' neighbours with six products.
  const Vector3d axis = b.rowwise().sum() - a.rowwise().sum();
  const double length = axis.norm();
  if (length > 0) {
    const Vector3d u = axis / length;
    const double a_far = std::max({u.dot(a.col(0)), u.dot(a.col(1)), u.dot(a.col(2))});
    const double b_near = std::min({u.dot(b.col(0)), u.dot(b.col(1)), u.dot(b.col(2))});
    if (b_near - a_far > margin) return false;
  }
  // Then along each one's normal: most other candidate pairs end here.
  for (int side = 0; side < 2; ++side) {
    const Triangle& s = side == 0 ? a : b;
    const Triangle& t = side == 0 ? b : a;
    const Vector3d n = (s.col(1) - s.col(0)).cross(s.col(2) - s.col(0));
    const double length = n.norm();
    if (!(length > 0)) continue;
    const Vector3d d = plane_sides(n / length, s.col(0), t, 0, 0.0);
    if ((d.array() > margin).all() || (d.array() < -margin).all()) return false;
  }
  if (triangles_cross(a, b, shared)) return true;
  return triangle_distance(a, b) < margin;
}

}  // namespace gauss
