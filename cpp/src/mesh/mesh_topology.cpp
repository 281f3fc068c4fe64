#include "gauss/mesh/mesh_topology.h"

#include <algorithm>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace gauss {
namespace {

int find_root(std::vector<int>& parent, int v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

// Counting-sort style CSR: `keys[i]` says which row item i belongs to; items keep their order.
void build_csr(int rows, const std::vector<int>& keys, std::vector<int>& start, std::vector<int>& items) {
  start.assign(rows + 1, 0);
  for (int k : keys) ++start[k + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  items.assign(keys.size(), 0);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (size_t i = 0; i < keys.size(); ++i) items[fill[keys[i]]++] = static_cast<int>(i);
}

}  // namespace

MeshTopology build_mesh_topology(int num_vertices, const int64_t* F, int num_input_faces,
                                 const Progress* progress) {
  auto check = [progress] {
    if (progress) progress->check();
  };
  MeshTopology t;
  t.num_vertices = num_vertices;
  for (int f = 0; f < num_input_faces; ++f) {
    std::array<int, 3> tri;
    for (int k = 0; k < 3; ++k) {
      const int64_t idx = F[3 * f + k];
      if (idx < 0 || idx >= num_vertices) {
        std::ostringstream msg;
        msg << "face " << f << " refers to vertex " << idx << ", but the mesh has " << num_vertices
            << " vertices (valid indices are 0.." << num_vertices - 1 << ")";
        throw std::invalid_argument(msg.str());
      }
      tri[k] = static_cast<int>(idx);
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) continue;  // no normal: ignore
    t.faces.push_back(tri);
    t.input_face.push_back(f);
  }
  if (t.faces.empty())
    throw std::invalid_argument("the mesh has no usable triangle (no faces, or every face repeats a vertex)");
  const int nF = static_cast<int>(t.faces.size());

  // Unique undirected edges, numbered in (lo, hi) order so the numbering is deterministic: slots are
  // bucketed by their lower vertex (counting sort), each small bucket sorted by the higher one.
  const int nS = 3 * nF;
  std::vector<int> slot_lo(nS), slot_hi(nS);
  for (int f = 0; f < nF; ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = t.faces[f][k], b = t.faces[f][(k + 1) % 3];
      slot_lo[3 * f + k] = std::min(a, b);
      slot_hi[3 * f + k] = std::max(a, b);
    }
  check();
  std::vector<int> bucket_start, bucket_slots;
  build_csr(num_vertices, slot_lo, bucket_start, bucket_slots);
  std::vector<int> slot_edge(nS);
  t.face_edge.resize(nF);
  t.face_edge_sign.resize(nF);
  for (int v = 0; v < num_vertices; ++v) {
    int* begin = bucket_slots.data() + bucket_start[v];
    int* end = bucket_slots.data() + bucket_start[v + 1];
    std::sort(begin, end, [&](int x, int y) { return slot_hi[x] != slot_hi[y] ? slot_hi[x] < slot_hi[y] : x < y; });
    for (int* it = begin; it != end; ++it) {
      if (it == begin || slot_hi[*it] != slot_hi[*(it - 1)]) t.edges.push_back({v, slot_hi[*it]});
      slot_edge[*it] = static_cast<int>(t.edges.size()) - 1;
    }
  }
  for (int f = 0; f < nF; ++f)
    for (int k = 0; k < 3; ++k) {
      t.face_edge[f][k] = slot_edge[3 * f + k];
      t.face_edge_sign[f][k] = (t.faces[f][k] < t.faces[f][(k + 1) % 3]) ? 1 : -1;
    }
  check();
  build_csr(static_cast<int>(t.edges.size()), slot_edge, t.edge_slot_start, t.edge_slots);

  std::vector<int> corner_vertex(3 * nF);
  for (int f = 0; f < nF; ++f)
    for (int k = 0; k < 3; ++k) corner_vertex[3 * f + k] = t.faces[f][k];
  build_csr(num_vertices, corner_vertex, t.vertex_corner_start, t.vertex_corners);

  check();
  std::vector<int> parent(num_vertices);
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& tri : t.faces)
    for (int k = 1; k < 3; ++k) {
      const int a = find_root(parent, tri[0]), b = find_root(parent, tri[k]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  t.component.assign(num_vertices, -1);
  std::vector<int> root_component(num_vertices, -1);
  for (int v = 0; v < num_vertices; ++v) {
    if (t.vertex_corner_start[v] == t.vertex_corner_start[v + 1]) continue;  // unreferenced
    const int r = find_root(parent, v);
    if (root_component[r] < 0) root_component[r] = t.num_components++;
    t.component[v] = root_component[r];
  }
  return t;
}

}  // namespace gauss
