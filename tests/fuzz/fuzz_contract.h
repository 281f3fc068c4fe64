#pragma once
// The checks every read-out of a fuzzed session must pass (the contract is stated in fuzz_harness.h):
// finite coordinates and energies, bounded within kGrowth extents, float and double read-outs equal,
// pinned vertices exactly at their targets, unreferenced vertices untouched. A violation aborts.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include <Eigen/Core>

#include "fuzz_inputs.h"
#include "fuzz_reader.h"
#include "gauss/solver/gauss_solver.h"

namespace gauss_fuzz {

// How far results may spread, in extents of the rest mesh and pin targets, from their centre.
constexpr double kGrowth = 10.0;

// The read-outs, checked against the contract (fuzz_harness.h).
inline void check(const gauss::GaussSolver& s, const Mesh& m, const std::vector<uint8_t>& referenced,
                  const Pins& pins) {
  const int nv = m.nv();
  std::vector<double> out(3 * static_cast<size_t>(nv));
  std::vector<float> out_f(3 * static_cast<size_t>(nv));
  s.copy_vertices(out.data());
  s.copy_vertices(out_f.data());
  for (size_t i = 0; i < out.size(); ++i) {
    if (!std::isfinite(out[i])) fail("a vertex coordinate is NaN or infinite");
    if (!(out_f[i] == static_cast<float>(out[i]))) fail("float and double read-outs differ");
  }
  // Bounded: the box of the referenced rest vertices and the pin targets, the session's earlier ones
  // included, grown kGrowth times.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (int v = 0; v < nv; ++v)
    if (referenced[v])
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], m.V[3 * v + k]), hi[k] = std::max(hi[k], m.V[3 * v + k]);
  for (size_t i = 0; i < pins.index.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const double t = pins.target.empty() ? m.V[3 * pins.index[i] + k] : pins.target[3 * i + k];
      lo[k] = std::min(lo[k], t), hi[k] = std::max(hi[k], t);
    }
  for (size_t i = 0; i < pins.earlier.size(); ++i)
    lo[i % 3] = std::min(lo[i % 3], pins.earlier[i]), hi[i % 3] = std::max(hi[i % 3], pins.earlier[i]);
  const Eigen::Vector3d centre = 0.5 * lo + 0.5 * hi;  // halves first: no overflow near DBL_MAX
  const double extent = (0.5 * hi - 0.5 * lo).maxCoeff() * 2.0;
  for (int v = 0; v < nv; ++v)
    if (referenced[v])
      for (int k = 0; k < 3; ++k)
        if (!(std::abs(out[3 * v + k] - centre[k]) <= kGrowth * extent + 1e-300)) fail("the mesh blew up");
  std::vector<uint8_t> pinned(nv, 0);
  for (size_t i = 0; i < pins.index.size(); ++i) {
    const int64_t v = pins.index[i];
    pinned[v] = 1;
    for (int k = 0; k < 3; ++k) {
      const double target = pins.target.empty() ? m.V[3 * v + k] : pins.target[3 * i + k];
      if (std::memcmp(&out[3 * v + k], &target, sizeof(double)) != 0) fail("a pinned vertex is off its target");
    }
  }
  for (int v = 0; v < nv; ++v)
    if (!referenced[v] && !pinned[v] && std::memcmp(&out[3 * v], &m.V[3 * v], 3 * sizeof(double)) != 0)
      fail("an unreferenced vertex moved");
  if (!std::isfinite(s.arap_energy())) fail("E_ARAP is NaN or infinite");
  if (!std::isfinite(s.g_energy())) fail("E_g is NaN or infinite");
  if (!std::isfinite(s.cubic_energy())) fail("E_cubic is NaN or infinite");
}

}  // namespace gauss_fuzz
