#include "gauss/proxy/proxy_mesh.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>

#include "gauss/mesh/spatial_order.h"
#include "gauss/util/parallel.h"

namespace gauss {

namespace {

using Eigen::Vector3d;

// A symmetric 4x4 quadric, its upper triangle: the squared distance to a set of planes is x^T Q x.
struct Quadric {
  double a[10] = {};
  void add_plane(const Vector3d& n, double d, double w) {
    const double p[4] = {n.x(), n.y(), n.z(), d};
    int k = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i; j < 4; ++j) a[k++] += w * p[i] * p[j];
  }
  void add(const Quadric& q) {
    for (int k = 0; k < 10; ++k) a[k] += q.a[k];
  }
  double error(const Vector3d& x) const {
    const double p[4] = {x.x(), x.y(), x.z(), 1.0};
    double e = 0.0;
    int k = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i; j < 4; ++j) e += (i == j ? 1.0 : 2.0) * a[k++] * p[i] * p[j];
    return e;
  }
};

// A boundary edge counts as this many times its length squared of plane, so that boundaries keep
// their outline as faces keep their planes.
constexpr double kBoundaryWeight = 10.0;
// Refuse a collapse that leaves a triangle whose normal turned by more than about 80 degrees, or whose
// shape (4 sqrt(3) area / sum of squared edges: 1 equilateral, 0 flat) falls below this and below
// what it was.
constexpr double kMinNormalCos = 0.2;
constexpr double kMinShape = 0.05;
// A pass makes collapses from the cheapest this share of the candidates, so that costly ones wait
// until the cheap ones around them changed their costs.
constexpr double kPassShare = 0.5;
// Chunks of space that collapse in parallel, and the fewest vertices a chunk has (below it: serial).
constexpr int kChunks = 8;
constexpr int kMinChunk = 4096;

struct Candidate {
  double cost;
  int u, v;
  bool operator<(const Candidate& o) const { return cost < o.cost || (cost == o.cost && u < o.u); }
};

double shape(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const double area2 = (b - a).cross(c - a).norm();  // twice the area
  const double edges = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  return edges > 0.0 ? 2.0 * std::sqrt(3.0) * area2 / edges : 0.0;
}

// Closest point of triangle (a, b, c) to p, as barycentric weights (Ericson, Real-Time Collision
// Detection, 5.1.5).
Vector3d closest_barycentric(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = va + vb + vc;
  if (!(std::abs(denom) > 0)) return {1, 0, 0};  // a degenerate triangle: its first corner
  const double v = vb / denom, w = vc / denom;
  return {1 - v - w, v, w};
}

// A collapse kills a face by setting its first corner to -1: the face's own load says whether it
// lives, where a separate flag would cost a second random read (the passes wait on memory: perf).
inline bool live(const std::array<int, 3>& t) { return t[0] >= 0; }

// Vertex -> incident faces (indices into `faces`, live ones only) in CSR form.
void vertex_faces(int nv, const std::vector<std::array<int, 3>>& faces,
                  std::vector<int>& start, std::vector<int>& list) {
  start.assign(nv + 1, 0);
  for (size_t f = 0; f < faces.size(); ++f)
    if (live(faces[f]))
      for (int k = 0; k < 3; ++k) ++start[faces[f][k] + 1];
  for (int i = 0; i < nv; ++i) start[i + 1] += start[i];
  list.resize(start[nv]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (size_t f = 0; f < faces.size(); ++f)
    if (live(faces[f]))
      for (int k = 0; k < 3; ++k) list[fill[faces[f][k]]++] = static_cast<int>(f);
}

// The ring of u: (neighbour, faces on edge u-neighbour) sorted by neighbour, from u's faces fs[0, count)
// that live. Returns false if they do not form one manifold fan (an edge in more than two faces,
// or more than one boundary).
bool ring_of(int u, const std::vector<std::array<int, 3>>& faces, const int* fs,
             int count, std::vector<std::pair<int, int>>& ring, bool& boundary) {
  ring.clear();
  int fan = 0;  // u's live faces
  for (int i = 0; i < count; ++i) {
    const auto& t = faces[fs[i]];
    if (!live(t)) continue;
    ++fan;
    for (int k = 0; k < 3; ++k)
      if (t[k] != u) ring.push_back({t[k], 1});
  }
  // Sorted by neighbour by insertion: a ring has about a dozen entries, all still counting 1, so the
  // neighbour alone orders them (std::sort compared both members through a call; 3% of the time at 2M).
  for (size_t i = 1; i < ring.size(); ++i) {
    const std::pair<int, int> r = ring[i];
    size_t j = i;
    for (; j > 0 && ring[j - 1].first > r.first; --j) ring[j] = ring[j - 1];
    ring[j] = r;
  }
  size_t out = 0;
  for (size_t i = 0; i < ring.size(); ++i) {
    if (out > 0 && ring[out - 1].first == ring[i].first)
      ++ring[out - 1].second;
    else
      ring[out++] = ring[i];
  }
  ring.resize(out);
  int boundary_edges = 0;
  for (const auto& r : ring) {
    if (r.second > 2) return false;
    if (r.second == 1) ++boundary_edges;
  }
  boundary = boundary_edges > 0;
  if (fan == 0) return false;
  // A single fan: as many faces as neighbours (closed), or one fewer with two boundary edges (open).
  if (boundary_edges == 0) return fan == static_cast<int>(ring.size());
  return boundary_edges == 2 && fan == static_cast<int>(ring.size()) - 1;
}

}  // namespace

ProxyMesh proxy_mesh(const double* V, int num_vertices, const int64_t* F, int num_faces, int target_vertices,
                     const Progress* progress) {
  if (num_vertices < 0 || num_faces < 0) throw std::invalid_argument("negative vertex or face count");
  if (target_vertices < 4) throw std::invalid_argument("target_vertices must be at least 4");
  const int nv = num_vertices;
  std::vector<Vector3d> X(nv);
  for (int i = 0; i < nv; ++i) {
    X[i] = Vector3d(V[3 * i], V[3 * i + 1], V[3 * i + 2]);
    if (!X[i].allFinite()) {
      std::ostringstream msg;
      msg << "vertex " << i << " has a NaN or infinite coordinate";
      throw std::invalid_argument(msg.str());
    }
  }
  std::vector<std::array<int, 3>> faces;
  faces.reserve(num_faces);
  for (int f = 0; f < num_faces; ++f) {
    const int64_t* t = F + 3 * static_cast<int64_t>(f);
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || t[k] >= nv) {
        std::ostringstream msg;
        msg << "face " << f << " refers to vertex " << t[k] << "; valid: 0 to " << nv - 1;
        throw std::invalid_argument(msg.str());
      }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    faces.push_back({static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])});
  }
  if (faces.empty()) throw std::invalid_argument("the mesh has no face with three different vertices");

  // Quadrics: every face's plane weighted by its area, boundary edges' perpendicular planes. Each
  // vertex gathers its own (in parallel; the serial scatter was 8% of the time at 2M), adding
  // them in the order the scatter did: its faces by index, then its boundary edges by the other end.
  std::vector<Quadric> Q(nv);
  std::vector<int> start, list;
  vertex_faces(nv, faces, start, list);
  const auto face_plane = [&](const std::array<int, 3>& t, Quadric& q) {
    const Vector3d n2 = (X[t[1]] - X[t[0]]).cross(X[t[2]] - X[t[0]]);
    const double area2 = n2.norm();
    if (!(area2 > 0)) return false;
    const Vector3d n = n2 / area2;
    q.add_plane(n, -n.dot(X[t[0]]), 0.5 * area2);
    return true;
  };
  // The plane through boundary edge u-v (u < v), perpendicular to u's first face on it.
  const auto edge_plane = [&](int u, int v, Quadric& q) {
    for (int i = start[u]; i < start[u + 1]; ++i) {
      const auto& t = faces[list[i]];
      if (t[0] != v && t[1] != v && t[2] != v) continue;
      const Vector3d normal = (X[t[1]] - X[t[0]]).cross(X[t[2]] - X[t[0]]);
      const Vector3d edge = X[v] - X[u];
      Vector3d n = edge.cross(normal);
      const double len = n.norm();
      if (!(len > 0)) return false;
      n /= len;
      q.add_plane(n, -n.dot(X[u]), kBoundaryWeight * edge.squaredNorm());
      return true;
    }
    return false;
  };
  parallel::for_ranges(nv, parallel::kMinParallelItems, [&](int begin, int end) {
    std::vector<std::pair<int, int>> ring;
    for (int x = begin; x < end; ++x) {
      const int count = start[x + 1] - start[x];
      if (count == 0) continue;
      for (int i = start[x]; i < start[x + 1]; ++i) {
        Quadric q;
        if (face_plane(faces[list[i]], q)) Q[x].add(q);
      }
      bool boundary = false;
      ring_of(x, faces, &list[start[x]], count, ring, boundary);
      for (const auto& r : ring) {
        if (r.second != 1) continue;
        Quadric q;
        if (edge_plane(std::min(x, r.first), std::max(x, r.first), q)) Q[x].add(q);
      }
    }
  });

  std::vector<int> into(nv, -1);  // the vertex each collapsed vertex went into
  int remaining = 0;
  for (int u = 0; u < nv; ++u) remaining += start[u + 1] > start[u];
  std::vector<Candidate> best(nv);
  // Within a pass the adjacency (start, list) stays right for every vertex but those merged into:
  // a collapse u -> v only rewrites u's faces (u becomes v) and kills the two on edge u-v, which ring_of
  // skips; v gains faces its list lacks, so v is locked until the next pass.
  std::vector<char> locked(nv);
  // Chunks of space (kChunks runs of the Morton order) collapse on their own in parallel: a collapse
  // whose vertices and their rings lie in one chunk reads and writes only faces and vertices of that
  // chunk, so chunks never touch each other's data; the rest wait for a serial sweep after them. The
  // chunks are fixed by the mesh, never by the thread count, so the proxy is the same for any.
  std::vector<int> chunk_of(nv, 0);
  if (nv >= kChunks * kMinChunk) {
    std::vector<int> rank;
    spatial_vertex_order(V, nv, rank);
    for (int i = 0; i < nv; ++i) chunk_of[i] = static_cast<int>(static_cast<int64_t>(rank[i]) * kChunks / nv);
  }
  // Is every vertex of `ring` in chunk `chunk` (-1: the serial sweep, anything goes)?
  const auto inside = [&](const std::vector<std::pair<int, int>>& ring, int chunk) {
    if (chunk < 0) return true;
    for (const auto& r : ring)
      if (chunk_of[r.first] != chunk) return false;
    return true;
  };
  struct Scratch {
    std::vector<std::pair<int, int>> ring_u, ring_v;
    std::vector<std::pair<double, int>> partners;
  };
  // Can u go into v (both unlocked, ring_u from ring_of)? v's ring in the chunk, the link condition
  // (the common neighbours are exactly the corners opposite edge u-v), no flipped or crushed face, no
  // face twice.
  const auto allowed = [&](int u, int v, bool boundary_u, int chunk, Scratch& w) {
    const auto& ring_u = w.ring_u;
    auto& ring_v = w.ring_v;
    bool boundary_v = false;
    if (!ring_of(v, faces, &list[start[v]], start[v + 1] - start[v], ring_v, boundary_v)) return false;
    if (!inside(ring_v, chunk)) return false;
    int common = 0, opposite = 0;
    for (size_t i = 0, j = 0; i < ring_u.size() && j < ring_v.size();) {
      if (ring_u[i].first < ring_v[j].first) {
        ++i;
      } else if (ring_v[j].first < ring_u[i].first) {
        ++j;
      } else {
        ++common;
        ++i;
        ++j;
      }
    }
    for (int i = start[u]; i < start[u + 1]; ++i) {
      const auto& t = faces[list[i]];
      opposite += live(t) && (t[0] == v || t[1] == v || t[2] == v);
    }
    if (common != opposite) return false;
    // A part that is a tetrahedron (or a lone triangle) keeps its vertices.
    if (ring_u.size() + ring_v.size() <= static_cast<size_t>(boundary_u ? 4 : 6)) return false;
    for (int i = start[u]; i < start[u + 1]; ++i) {
      const auto& t = faces[list[i]];
      if (!live(t)) continue;
      if (t[0] == v || t[1] == v || t[2] == v) continue;
      Vector3d before[3], after[3];
      int others[2], m = 0;
      for (int k = 0; k < 3; ++k) {
        before[k] = X[t[k]];
        after[k] = t[k] == u ? X[v] : X[t[k]];
        if (t[k] != u) others[m++] = t[k];
      }
      const Vector3d n0 = (before[1] - before[0]).cross(before[2] - before[0]);
      const Vector3d n1 = (after[1] - after[0]).cross(after[2] - after[0]);
      const double l0 = n0.norm(), l1 = n1.norm();
      if (!(l1 > 0) || (l0 > 0 && n0.dot(n1) < kMinNormalCos * l0 * l1)) return false;
      const double s1 = shape(after[0], after[1], after[2]);
      if (s1 < kMinShape && s1 < shape(before[0], before[1], before[2])) return false;
      for (int j = start[v]; j < start[v + 1]; ++j) {  // would (v, x, y) exist twice?
        const auto& g = faces[list[j]];
        if (!live(g)) continue;
        const bool has_x = g[0] == others[0] || g[1] == others[0] || g[2] == others[0];
        const bool has_y = g[0] == others[1] || g[1] == others[1] || g[2] == others[1];
        if (has_x && has_y) return false;
      }
    }
    return true;
  };
  // Makes the collapses of `order` (cheapest first) that are allowed, at most `budget`, within
  // chunk `chunk` (-1: anywhere); the candidates it leaves because they reach out of the chunk go to
  // `border`. Returns how many it made.
  const auto collapse = [&](const std::vector<Candidate>& order, int chunk, int budget,
                            std::vector<Candidate>* border) {
    Scratch w;
    int made = 0;
    for (const Candidate& c : order) {
      if (made >= budget) break;
      const int u = c.u;
      bool boundary_u = false;
      if (locked[u] || !ring_of(u, faces, &list[start[u]], start[u + 1] - start[u], w.ring_u, boundary_u))
        continue;
      if (!inside(w.ring_u, chunk)) {
        border->push_back(c);
        continue;
      }
      // Its partners now, cheapest first: the first one allowed takes it.
      w.partners.clear();
      for (const auto& r : w.ring_u) {
        if (locked[r.first] || (boundary_u && r.second != 1)) continue;
        Quadric q = Q[u];
        q.add(Q[r.first]);
        w.partners.push_back({q.error(X[r.first]), r.first});
      }
      std::sort(w.partners.begin(), w.partners.end());
      int v = -1;
      bool out_of_chunk = false;
      for (const auto& partner : w.partners) {
        if (allowed(u, partner.second, boundary_u, chunk, w)) {
          v = partner.second;
          break;
        }
        out_of_chunk |= chunk >= 0 && !inside(w.ring_v, chunk);
      }
      if (v < 0) {
        if (out_of_chunk) border->push_back(c);
        continue;
      }
      for (int i = start[u]; i < start[u + 1]; ++i) {
        auto& t = faces[list[i]];
        if (!live(t)) continue;
        if (t[0] == v || t[1] == v || t[2] == v) {
          t[0] = -1;
          continue;
        }
        for (int k = 0; k < 3; ++k)
          if (t[k] == u) t[k] = v;
      }
      Q[v].add(Q[u]);
      into[u] = v;
      locked[u] = locked[v] = 1;
      ++made;
    }
    return made;
  };
  std::vector<std::vector<Candidate>> chunk_order(kChunks), chunk_border(kChunks);
  std::vector<int> chunk_made(kChunks);
  while (remaining > target_vertices) {
    if (progress) progress->check();
    // The dead faces dropped, in order (so every vertex's list keeps its order and the proxy is the
    // same): a pass removes about a quarter of them, and what stays is all the passes read.
    {
      size_t kept = 0;
      for (size_t f = 0; f < faces.size(); ++f)
        if (live(faces[f])) faces[kept++] = faces[f];
      faces.resize(kept);
    }
    vertex_faces(nv, faces, start, list);
    // Every vertex's cheapest partner, in parallel (each thread its own ring buffer): the pass's order.
    parallel::for_ranges(nv, parallel::kMinParallelItems, [&](int begin, int end) {
      std::vector<std::pair<int, int>> ring;
      for (int u = begin; u < end; ++u) {
        best[u] = {HUGE_VAL, u, -1};
        const int count = start[u + 1] - start[u];
        bool boundary = false;
        if (count == 0 || !ring_of(u, faces, &list[start[u]], count, ring, boundary)) continue;
        for (const auto& r : ring) {
          if (boundary && r.second != 1) continue;  // a boundary vertex moves only along its boundary
          Quadric q = Q[u];
          q.add(Q[r.first]);
          const double cost = q.error(X[r.first]);
          if (cost < best[u].cost) best[u] = {cost, u, r.first};
        }
      }
    });
    std::vector<Candidate> order;
    for (int u = 0; u < nv; ++u)
      if (best[u].v >= 0) order.push_back(best[u]);
    if (order.empty()) break;
    // The cheapest share (candidates are totally ordered: the same set whatever the selection's
    // course), each chunk's part then sorted by the chunk's own task: what a full sort did, serially.
    const size_t share = std::max<size_t>(1, static_cast<size_t>(kPassShare * order.size()));
    std::nth_element(order.begin(), order.begin() + (share - 1), order.end());
    order.resize(share);
    std::fill(locked.begin(), locked.end(), 0);
    const int wanted = remaining - target_vertices;
    for (auto& c : chunk_order) c.clear();
    for (const Candidate& c : order) chunk_order[chunk_of[c.u]].push_back(c);
    // Each chunk may make its share of the collapses still wanted, the serial sweep the rest.
    parallel::for_tasks(kChunks, nv >= kChunks * kMinChunk, [&](int chunk) {
      std::sort(chunk_order[chunk].begin(), chunk_order[chunk].end());
      chunk_border[chunk].clear();
      const int budget = static_cast<int>(static_cast<int64_t>(wanted) * chunk_order[chunk].size() / order.size());
      chunk_made[chunk] = collapse(chunk_order[chunk], nv >= kChunks * kMinChunk ? chunk : -1, budget,
                                   &chunk_border[chunk]);
    });
    int collapsed = 0;
    std::vector<Candidate> border;
    for (int chunk = 0; chunk < kChunks; ++chunk) {
      collapsed += chunk_made[chunk];
      border.insert(border.end(), chunk_border[chunk].begin(), chunk_border[chunk].end());
    }
    std::sort(border.begin(), border.end());
    std::vector<Candidate> none;  // the serial sweep leaves nothing for later
    collapsed += collapse(border, -1, wanted - collapsed, &none);
    if (collapsed == 0) break;
    remaining -= collapsed;
  }

  // The proxy: the vertices live faces still use, renumbered in order.
  ProxyMesh proxy;
  std::vector<int> proxy_of(nv, -1);
  for (size_t f = 0; f < faces.size(); ++f)
    if (live(faces[f]))
      for (int k = 0; k < 3; ++k) proxy_of[faces[f][k]] = 0;
  for (int i = 0; i < nv; ++i)
    if (proxy_of[i] == 0) {
      proxy_of[i] = static_cast<int>(proxy.vertices.size());
      proxy.vertices.push_back(X[i]);
      proxy.fine_of_proxy.push_back(i);
    }
  for (size_t f = 0; f < faces.size(); ++f)
    if (live(faces[f]))
      proxy.faces.push_back({proxy_of[faces[f][0]], proxy_of[faces[f][1]], proxy_of[faces[f][2]]});

  // Each fine vertex's proxy vertex: the end of its chain of collapses (chains are short-cut).
  std::vector<int> root(nv);
  for (int i = 0; i < nv; ++i) {
    int r = i;
    while (into[r] >= 0) r = into[r];
    root[i] = r;
  }
  // Proxy vertex -> its faces and its neighbours' faces (the two-ring), sorted and unique.
  const int np = static_cast<int>(proxy.vertices.size());
  std::vector<int> pstart, plist;
  vertex_faces(np, proxy.faces, pstart, plist);
  // Gathered in parallel, each proxy vertex's into its own list, then joined in order.
  std::vector<std::vector<int>> two_ring(np);
  parallel::for_ranges(np, parallel::kMinParallelItems, [&](int begin, int end) {
    for (int p = begin; p < end; ++p) {
      std::vector<int>& gathered = two_ring[p];
      for (int i = pstart[p]; i < pstart[p + 1]; ++i)
        for (int k = 0; k < 3; ++k) {
          const int q = proxy.faces[plist[i]][k];
          gathered.insert(gathered.end(), plist.begin() + pstart[q], plist.begin() + pstart[q + 1]);
        }
      std::sort(gathered.begin(), gathered.end());
      gathered.erase(std::unique(gathered.begin(), gathered.end()), gathered.end());
    }
  });
  std::vector<int> two_start(np + 1, 0), two_list;
  for (int p = 0; p < np; ++p) two_start[p + 1] = two_start[p] + static_cast<int>(two_ring[p].size());
  two_list.reserve(two_start[np]);
  for (auto& gathered : two_ring) {
    two_list.insert(two_list.end(), gathered.begin(), gathered.end());
    std::vector<int>().swap(gathered);
  }
  proxy.fine_face.assign(nv, -1);
  proxy.fine_bary.assign(nv, {0.f, 0.f});
  proxy.fine_offset.resize(nv);
  parallel::for_ranges(nv, parallel::kMinParallelItems, [&](int begin, int end) {
    for (int i = begin; i < end; ++i) {
      const int p = proxy_of[root[i]];
      if (p < 0) {  // in no face: stays where it is
        proxy.fine_offset[i] = {static_cast<float>(X[i].x()), static_cast<float>(X[i].y()),
                                static_cast<float>(X[i].z())};
        continue;
      }
      double best_d2 = HUGE_VAL;
      Vector3d best_w(1, 0, 0);
      const auto nearest = [&](const int* faces_begin, const int* faces_end) {
        for (const int* g = faces_begin; g != faces_end; ++g) {
          const auto& t = proxy.faces[*g];
          const Vector3d& a = proxy.vertices[t[0]];
          const Vector3d& b = proxy.vertices[t[1]];
          const Vector3d& c = proxy.vertices[t[2]];
          const Vector3d w = closest_barycentric(X[i], a, b, c);
          const Vector3d point = w[0] * a + w[1] * b + w[2] * c;
          const double d2 = (X[i] - point).squaredNorm();
          if (d2 < best_d2) {
            best_d2 = d2;
            best_w = w;
            proxy.fine_face[i] = *g;
            proxy.fine_bary[i] = {static_cast<float>(w[1]), static_cast<float>(w[2])};
            const Vector3d d = X[i] - point;
            proxy.fine_offset[i] = {static_cast<float>(d.x()), static_cast<float>(d.y()), static_cast<float>(d.z())};
          }
        }
      };
      // The proxy vertex's own faces first; their neighbours' too only where the nearest point found
      // lies on the rim of a face (the vertex may then be nearer to a face beyond).
      nearest(plist.data() + pstart[p], plist.data() + pstart[p + 1]);
      if (!(best_w.minCoeff() > 0.0)) nearest(two_list.data() + two_start[p], two_list.data() + two_start[p + 1]);
    }
  });
  return proxy;
}

}  // namespace gauss
