#pragma once
// A small, balanced vertex separator of a connected graph, found the multilevel way (Karypis & Kumar
// 1998): the graph is coarsened by merging heavy-edge matched pairs of vertices, the coarsest graph is
// split at a balanced thin level of a breadth-first level structure, and on the way back every level
// improves the separator by Fiduccia-Mattheyses passes (move a separator vertex to a side, pull its
// neighbours on the other side into the separator, keep the best state seen).
//
// Used by nested_dissection.cpp; the separator's size decides the fill of the Cholesky factor.
#include <cstdint>
#include <vector>

#include "gauss/util/progress.h"

namespace gauss {

// A graph with vertex and edge weights (coarse vertices stand for several fine ones).
struct WeightedGraph {
  int n = 0;
  std::vector<int> start, adj;  // neighbours of v: adj[start[v] .. start[v+1]) (symmetric, no self loops)
  std::vector<int> edge_weight;  // per adjacency entry
  std::vector<int> weight;       // per vertex
};

// side (g.n): 0 or 1 for the two parts, 2 for the separator; no edge joins part 0 and part 1, and
// neither part weighs more than about 60% of the graph (less balance would cost more fill than a
// smaller separator saves). Deterministic. g must be connected and have at least 3 vertices.
// progress: polled between levels; once it is cancelled the result is all separator (valid, useless:
// the caller stops).
std::vector<uint8_t> vertex_separator(const WeightedGraph& g, const Progress& progress);

}  // namespace gauss
