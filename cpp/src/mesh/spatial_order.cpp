#include "gauss/mesh/spatial_order.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gauss {
namespace {

uint64_t spread_bits(uint64_t x) {  // 21 bits -> every third bit of 63
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

}  // namespace

void spatial_vertex_order(const double* V, int nV, std::vector<int>& new_of_old) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (int v = 0; v < nV; ++v)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], V[3 * v + k]);
      hi[k] = std::max(hi[k], V[3 * v + k]);
    }
  // (code, vertex) pairs sorted: the stable sort by code, without the indirection through code[].
  std::vector<std::pair<uint64_t, int>> code(nV);
  for (int v = 0; v < nV; ++v) {
    uint64_t c = 0;
    for (int k = 0; k < 3; ++k) {
      // Halved so that the extent of finite coordinates cannot overflow (exact otherwise); the NaN-safe
      // clamp keeps the integer conversion defined whatever the input.
      const double ext = 0.5 * hi[k] - 0.5 * lo[k];
      const double t = ext > 0 ? (0.5 * V[3 * v + k] - 0.5 * lo[k]) / ext : 0.0;
      c |= spread_bits(static_cast<uint64_t>((t > 0 ? std::min(t, 1.0) : 0.0) * 2097151.0)) << k;
    }
    code[v] = {c, v};
  }
  std::sort(code.begin(), code.end());
  new_of_old.resize(nV);
  for (int i = 0; i < nV; ++i) new_of_old[code[i].second] = i;
}

void spatial_order(const double* V, int nV, const int64_t* F, int nF, std::vector<int>& new_of_old,
                   std::vector<int>& face_order) {
  spatial_vertex_order(V, nV, new_of_old);

  std::vector<std::pair<int, int>> first(nF);  // (first vertex, face): sorted, ties in face order
  for (int f = 0; f < nF; ++f)
    first[f] = {std::min({new_of_old[F[3 * f]], new_of_old[F[3 * f + 1]], new_of_old[F[3 * f + 2]]}), f};
  std::sort(first.begin(), first.end());
  face_order.resize(nF);
  for (int f = 0; f < nF; ++f) face_order[f] = first[f].second;
}

}  // namespace gauss
