#pragma once
// Fill-reducing ordering of a sparse symmetric matrix by nested dissection (George 1973): a small set
// of vertices of the matrix's graph, the separator, splits it in two; both halves are ordered first
// (recursively) and the separator last, so eliminating one half never fills into the other. On a mesh
// Laplacian the separators are rings of vertices around the surface, and on most big meshes the
// factor comes out much sparser than with minimum degree, though not on every one (the fill of both:
// docs/performance.md#set-up-at-scale).
//
// Separators come from graph_bisection.h (multilevel). Graphs of at most 50,000 vertices, and the
// pieces of at most 1,000 vertices the dissection ends in, are ordered by approximate minimum degree
// (Eigen's AMD), because at those sizes dissecting further saves little or no fill for much more
// time (measured: docs/performance.md#set-up-at-scale).
//
// Input:  n vertices; the neighbours of v are adj[adj_start[v] .. adj_start[v+1]) (symmetric, no self
//         loops).
// Output: old_of_new (n): the vertex eliminated at position k.
// Deterministic: the top pieces are ordered on several threads, each by the same operations whatever
// thread runs it. Reports SetupPhase::ordering progress; throws Cancelled when cancelled.
#include <vector>

#include "gauss/util/progress.h"

namespace gauss {

std::vector<int> nested_dissection(int n, const std::vector<int>& adj_start, const std::vector<int>& adj,
                                   Progress& progress);

}  // namespace gauss
