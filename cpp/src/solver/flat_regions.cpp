#include "gauss/solver/flat_regions.h"
#include "gauss/util/constants.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace gauss {
namespace {

using Eigen::Vector3d;

// The axes' search: rectangles every kAngleStep degrees over a quarter turn; rectangles within
// kTieShare of the smallest's area count as equally small (a 32-gon's differ by 0.5%).
constexpr double kAngleStep = 0.25;
constexpr double kTieShare = 0.01;
// A region of fewer faces has an outline of a few straight edges: nothing to square, and pulling it
// would only hold a coarse mesh back from its style.
constexpr int kMinFlatFaces = 12;
// A face whose normal has less than this part in the region's plane takes its outline's direction.
constexpr double kMinWallShare = 0.1;

// A unit vector orthogonal to n.
Vector3d any_orthogonal(const Vector3d& n) {
  const Vector3d a = std::abs(n.x()) < 0.9 ? Vector3d::UnitX() : Vector3d::UnitY();
  return (a - a.dot(n) * n).normalized();
}

// The axes of the region's outline (points in its plane's basis e1, e2), as an angle in [0, 90).
double outline_angle(const std::vector<Eigen::Vector2d>& points, double reference_angle) {
  const int steps = static_cast<int>(90.0 / kAngleStep);
  std::vector<double> area(steps);
  double smallest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < steps; ++i) {
    const double a = i * kAngleStep * kPi / 180.0;
    const Eigen::Vector2d x(std::cos(a), std::sin(a)), y(-std::sin(a), std::cos(a));
    double lo_x = INFINITY, hi_x = -INFINITY, lo_y = INFINITY, hi_y = -INFINITY;
    for (const auto& p : points) {
      const double px = p.dot(x), py = p.dot(y);
      lo_x = std::min(lo_x, px), hi_x = std::max(hi_x, px), lo_y = std::min(lo_y, py), hi_y = std::max(hi_y, py);
    }
    area[i] = (hi_x - lo_x) * (hi_y - lo_y);
    smallest = std::min(smallest, area[i]);
  }
  // Of the smallest rectangles, the one whose axes lie closest to the reference (modulo a quarter turn).
  double best = 0, best_gap = INFINITY;
  for (int i = 0; i < steps; ++i) {
    if (!(area[i] <= smallest * (1 + kTieShare))) continue;
    double gap = std::fmod(std::abs(i * kAngleStep - reference_angle), 90.0);
    gap = std::min(gap, 90.0 - gap);
    if (gap < best_gap) best_gap = gap, best = i * kAngleStep;
  }
  return best;
}

}  // namespace

SquareTargets square_targets(const MeshTopology& topo, const std::vector<Vector3d>& X) {
  SquareTargets out;
  const int nF = static_cast<int>(topo.faces.size()), nV = topo.num_vertices;
  std::vector<Vector3d> normal(nF, Vector3d::Zero());
  std::vector<double> area(nF, 0.0);
  double total = 0;
  for (int f = 0; f < nF; ++f) {
    const auto& t = topo.faces[f];
    const Vector3d c = (X[t[1]] - X[t[0]]).cross(X[t[2]] - X[t[0]]);
    const double len = c.norm();
    if (!(len > 0) || !std::isfinite(len)) continue;  // degenerate: in no region, no target
    normal[f] = c / len;
    area[f] = 0.5 * len;
    total += area[f];
  }
  if (!(total > 0)) return out;

  // Regions: edge-connected faces (manifold edges only) within kFlatDegrees of the seed and of the
  // face they were reached from.
  const double cos_flat = std::cos(kFlatDegrees * kPi / 180.0);
  std::vector<int> region_of(nF, -1);
  std::vector<int> members, stack;
  std::vector<std::vector<int>> region_faces;
  for (int seed = 0; seed < nF; ++seed) {
    if (region_of[seed] != -1 || area[seed] == 0) continue;
    const int label = static_cast<int>(region_faces.size());
    members.clear();
    stack.assign(1, seed);
    region_of[seed] = label;
    double region_area = 0;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      members.push_back(f);
      region_area += area[f];
      for (int k = 0; k < 3; ++k) {
        const int e = topo.face_edge[f][k];
        if (topo.edge_slot_start[e + 1] - topo.edge_slot_start[e] != 2) continue;
        for (int i = topo.edge_slot_start[e]; i < topo.edge_slot_start[e + 1]; ++i) {
          const int g = topo.edge_slots[i] / 3;
          if (g == f || region_of[g] != -1 || area[g] == 0) continue;
          if (normal[g].dot(normal[seed]) < cos_flat || normal[g].dot(normal[f]) < cos_flat) continue;
          region_of[g] = label;
          stack.push_back(g);
        }
      }
    }
    region_faces.push_back(members);
    if (region_area < kMinAreaShare * total || static_cast<int>(members.size()) < kMinFlatFaces) {  // in none (-2)
      for (int f : members) region_of[f] = -2;
      region_faces.back().clear();
    }
  }

  // Per large region: normal, axes, and the band's distances along edges from the outline.
  std::vector<int> vertex_start(nV + 1, 0), neighbours;  // vertex adjacency (CSR) from the edges
  for (const auto& e : topo.edges) ++vertex_start[e[0] + 1], ++vertex_start[e[1] + 1];
  for (int v = 0; v < nV; ++v) vertex_start[v + 1] += vertex_start[v];
  neighbours.resize(vertex_start[nV]);
  {
    std::vector<int> fill(vertex_start.begin(), vertex_start.end() - 1);
    for (const auto& e : topo.edges) neighbours[fill[e[0]]++] = e[1], neighbours[fill[e[1]]++] = e[0];
  }
  std::vector<double> distance(nV, INFINITY), best_face_distance(nF, INFINITY);
  std::vector<int> source(nV, -1);                       // the outline vertex nearest each band vertex
  std::vector<double> turn(nV, 0.0);                      // per outline vertex: its edges' mean turn
  std::vector<int> turn_count(nV, 0);
  std::vector<std::pair<std::array<int, 2>, Vector3d>> outline;  // outline edges and their outward directions
  std::vector<int> touched, target_of(nF, -1);  // target_of: index into out's face lists
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (size_t r = 0; r < region_faces.size(); ++r) {
    const std::vector<int>& faces = region_faces[r];
    if (faces.empty()) continue;
    FlatRegion region;
    Vector3d sum = Vector3d::Zero();
    for (int f : faces) sum += area[f] * normal[f], region.area += area[f];
    region.normal = sum.normalized();
    // The outline: edges with one face of the region, each with its outward direction in the plane
    // (edge x normal, the face running the edge forwards).
    touched.clear();
    outline.clear();
    for (int f : faces)
      for (int k = 0; k < 3; ++k) {
        const int e = topo.face_edge[f][k];
        int inside = 0;
        for (int i = topo.edge_slot_start[e]; i < topo.edge_slot_start[e + 1]; ++i)
          inside += region_of[topo.edge_slots[i] / 3] == static_cast<int>(r);
        if (inside != 1) continue;
        const int a = topo.faces[f][k], b = topo.faces[f][(k + 1) % 3];
        outline.push_back({{a, b}, (X[b] - X[a]).cross(region.normal)});
        for (int v : {a, b})
          if (distance[v] != 0.0) distance[v] = 0.0, source[v] = v, touched.push_back(v), queue.push({0.0, v});
      }
    const Vector3d e1 = any_orthogonal(region.normal), e2 = region.normal.cross(e1);
    // The reference: the object's axis that lies most in the plane.
    Vector3d reference = Vector3d::Zero();
    for (int a = 0; a < 3; ++a) {
      const Vector3d axis = Vector3d::Unit(a), in_plane = axis - axis.dot(region.normal) * region.normal;
      if (in_plane.norm() > reference.norm() + 1e-9) reference = in_plane;
    }
    const double reference_angle =
        std::fmod(std::atan2(reference.dot(e2), reference.dot(e1)) * 180.0 / kPi + 360.0, 90.0);
    double angle = reference_angle;
    if (!touched.empty()) {  // a closed flat region (a whole plane's both sides) has no outline
      std::vector<Eigen::Vector2d> points;
      points.reserve(touched.size());
      for (int v : touched) points.emplace_back(X[v].dot(e1), X[v].dot(e2));
      angle = outline_angle(points, reference_angle);
    }
    const double a = angle * kPi / 180.0;
    region.u = std::cos(a) * e1 + std::sin(a) * e2;
    region.v = region.normal.cross(region.u);
    // The turn about the normal that takes a direction in the plane onto the nearest of +-u, +-v.
    const auto turn_to_axes = [&](const Vector3d& dir) {
      Vector3d axis = region.u;
      for (const Vector3d& c : {Vector3d(-region.u), region.v, Vector3d(-region.v)})
        if (c.dot(dir) > axis.dot(dir)) axis = c;
      return std::atan2(dir.cross(axis).dot(region.normal), dir.dot(axis));
    };
    // Each outline vertex turns by its edges' mean turn: a corner of two edges that already lie along
    // the axes does not turn (its own outward direction, their diagonal, would be a tie).
    for (const auto& [ends, dir] : outline) {
      if (!(dir.norm() > 0)) continue;
      const double t = turn_to_axes(dir);
      for (int v : ends) turn[v] += t, ++turn_count[v];
    }

    // The band: Dijkstra from the outline along edges, up to its width.
    const double width = kBandWidth * std::sqrt(region.area);
    while (!queue.empty()) {
      const auto [d, v] = queue.top();
      queue.pop();
      if (d > distance[v]) continue;
      for (int i = vertex_start[v]; i < vertex_start[v + 1]; ++i) {
        const int w = neighbours[i];
        const double dw = d + (X[w] - X[v]).norm();
        if (dw < distance[w] && dw < width) {
          if (distance[w] == INFINITY) touched.push_back(w);
          distance[w] = dw;
          source[w] = source[v];
          queue.push({dw, w});
        }
      }
    }
    out.regions.push_back(region);
    const auto add = [&](int f, const Eigen::Matrix3d& rotation, double weight, double d) {
      // A face in two bands takes the nearer region's target.
      if (target_of[f] < 0) {
        target_of[f] = static_cast<int>(out.face.size());
        out.face.push_back(f);
        out.rotation.push_back(rotation);
        out.weight.push_back(weight);
      } else if (d < best_face_distance[f]) {
        out.rotation[target_of[f]] = rotation;
        out.weight[target_of[f]] = weight;
      } else {
        return;
      }
      best_face_distance[f] = d;
    };
    for (int v : touched)
      for (int i = topo.vertex_corner_start[v]; i < topo.vertex_corner_start[v + 1]; ++i) {
        const int f = topo.vertex_corners[i] / 3;
        if (area[f] == 0 || (region_of[f] >= 0 && region_of[f] != static_cast<int>(r))) continue;  // another region's
        const auto& t = topo.faces[f];
        const double d = (distance[t[0]] + distance[t[1]] + distance[t[2]]) / 3.0;
        if (!(d < width) || !(d < best_face_distance[f])) continue;
        // The turn: a wall's own, from its normal in the plane; a face of the region (or one nearly
        // parallel to it) its nearest outline's.
        const Vector3d& n = normal[f];
        const Vector3d dir = n - n.dot(region.normal) * region.normal;
        double angle = 0;
        if (region_of[f] == static_cast<int>(r) || dir.norm() < kMinWallShare) {
          int count = 0;
          for (int c : t)
            if (source[c] >= 0 && turn_count[source[c]] > 0) angle += turn[source[c]] / turn_count[source[c]], ++count;
          if (count == 0) continue;
          angle /= count;
        } else {
          angle = turn_to_axes(dir);
        }
        add(f, Eigen::AngleAxisd(angle, region.normal).toRotationMatrix(), area[f] * (1.0 - d / width), d);
      }
    for (int v : touched) distance[v] = INFINITY, source[v] = -1, turn[v] = 0, turn_count[v] = 0;
  }
  return out;
}

}  // namespace gauss
