// The cache-friendly renumbering of a mesh (spatial_order.h): both outputs are permutations, vertices
// follow the Morton (Z-order) curve, faces follow their first vertex, and degenerate positions (all
// equal, NaN) still give permutations.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "gauss/mesh/spatial_order.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_spatial_order {

namespace {

bool is_permutation(const std::vector<int>& p, int n) {
  if (static_cast<int>(p.size()) != n) return false;
  std::vector<int> sorted = p;
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < n; ++i)
    if (sorted[i] != i) return false;
  return true;
}

// Random faces over n vertices (distinct corners).
std::vector<int64_t> random_faces(int n, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<int64_t> F;
  for (int f = 0; f < count; ++f) {
    std::array<int64_t, 3> c;
    do {
      for (auto& v : c) v = static_cast<int64_t>(rng() % n);
    } while (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]);
    F.insert(F.end(), c.begin(), c.end());
  }
  return F;
}

}  // namespace

TEST(SpatialOrder, GridVerticesFollowTheZOrderCurve) {
  // The 8 x 8 x 8 lattice points, given in a shuffled order, coordinates scaled unevenly per axis.
  std::vector<std::array<int, 3>> cell;
  for (int x = 0; x < 8; ++x)
    for (int y = 0; y < 8; ++y)
      for (int z = 0; z < 8; ++z) cell.push_back({x, y, z});
  std::shuffle(cell.begin(), cell.end(), std::mt19937(4));
  const int n = static_cast<int>(cell.size());
  std::vector<double> V;
  for (const auto& c : cell) V.insert(V.end(), {0.3 * c[0] - 1.0, 5.0 * c[1], 1e-3 * c[2] + 7.0});
  const std::vector<int64_t> F = random_faces(n, 300, 5);
  std::vector<int> new_of_old, face_order;
  gauss::spatial_order(V.data(), n, F.data(), 300, new_of_old, face_order);
  ASSERT_TRUE(is_permutation(new_of_old, n));
  ASSERT_TRUE(is_permutation(face_order, 300));
  // The vertices' numbering alone (what the proxy uses) is spatial_order's.
  std::vector<int> alone;
  gauss::spatial_vertex_order(V.data(), n, alone);
  EXPECT_EQ(alone, new_of_old);

  // On the Z-order curve every aligned run of 8^j consecutive vertices fills an aligned cube of side
  // 2^j (j = 1, 2), and the curve starts at the lowest corner.
  std::vector<std::array<int, 3>> at(n);
  for (int v = 0; v < n; ++v) at[new_of_old[v]] = cell[v];
  EXPECT_EQ(at[0], (std::array<int, 3>{0, 0, 0}));
  for (int side : {2, 4}) {
    const int run = side * side * side;
    for (int first = 0; first < n; first += run)
      for (int k = 0; k < 3; ++k) {
        int lo = 8, hi = -1;
        for (int i = first; i < first + run; ++i) lo = std::min(lo, at[i][k]), hi = std::max(hi, at[i][k]);
        EXPECT_EQ(lo % side, 0) << "run at " << first << ", axis " << k;
        EXPECT_EQ(hi - lo, side - 1) << "run at " << first << ", axis " << k;
      }
  }

  // Faces by their first vertex in the new numbering, ties in their old order.
  auto first_vertex = [&](int f) {
    return std::min({new_of_old[F[3 * f]], new_of_old[F[3 * f + 1]], new_of_old[F[3 * f + 2]]});
  };
  for (int k = 1; k < 300; ++k) {
    const int a = first_vertex(face_order[k - 1]), b = first_vertex(face_order[k]);
    EXPECT_LE(a, b) << "face " << k;
    if (a == b) EXPECT_LT(face_order[k - 1], face_order[k]) << "face " << k;
  }
}

TEST(SpatialOrder, DegeneratePositionsStillGivePermutations) {
  const int n = 50;
  const std::vector<int64_t> F = random_faces(n, 60, 6);
  std::vector<int> new_of_old, face_order;
  // All vertices at one point: nothing to sort by, the order stays as given.
  std::vector<double> same(3 * n, 2.5);
  gauss::spatial_order(same.data(), n, F.data(), 60, new_of_old, face_order);
  ASSERT_TRUE(is_permutation(new_of_old, n));
  for (int v = 0; v < n; ++v) EXPECT_EQ(new_of_old[v], v);
  std::vector<int> alone;
  gauss::spatial_vertex_order(same.data(), n, alone);
  EXPECT_EQ(alone, new_of_old);  // ties keep the given order there too
  ASSERT_TRUE(is_permutation(face_order, 60));
  // NaN and infinite coordinates, and huge finite ones whose extent overflows unless halved.
  std::vector<double> odd(3 * n);
  std::mt19937 rng(7);
  for (double& x : odd) x = std::uniform_real_distribution<double>(-1e308, 1e308)(rng);
  odd[0] = std::numeric_limits<double>::quiet_NaN();
  odd[4] = std::numeric_limits<double>::infinity();
  odd[8] = -std::numeric_limits<double>::infinity();
  gauss::spatial_order(odd.data(), n, F.data(), 60, new_of_old, face_order);
  EXPECT_TRUE(is_permutation(new_of_old, n));
  EXPECT_TRUE(is_permutation(face_order, 60));
}

}  // namespace test_spatial_order
