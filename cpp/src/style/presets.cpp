#include "gauss/style/presets.h"
#include "gauss/util/constants.h"

#include <cmath>
#include <stdexcept>

namespace gauss {
namespace {

using Eigen::Vector3d;

// Face normals of a regular n-gon prism's sides, optionally tilted up by `elevation` radians.
std::vector<Vector3d> ring_of_normals(int n, double elevation, double phase = 0.0) {
  std::vector<Vector3d> out;
  for (int i = 0; i < n; ++i) {
    const double a = phase + 2.0 * kPi * i / n;
    out.emplace_back(std::cos(elevation) * std::cos(a), std::cos(elevation) * std::sin(a),
                     std::sin(elevation));
  }
  return out;
}

std::vector<Vector3d> with_caps(std::vector<Vector3d> v, bool top, bool bottom) {
  if (top) v.emplace_back(0, 0, 1);
  if (bottom) v.emplace_back(0, 0, -1);
  return v;
}

std::vector<Vector3d> all_signs(const std::vector<Vector3d>& base) {
  // Every sign combination of each base vector's non-zero coordinates, without duplicates.
  std::vector<Vector3d> out;
  for (const Vector3d& b : base)
    for (int m = 0; m < 8; ++m) {
      Vector3d v((m & 1) ? -b.x() : b.x(), (m & 2) ? -b.y() : b.y(), (m & 4) ? -b.z() : b.z());
      bool seen = false;
      for (const Vector3d& o : out) seen = seen || (o - v).norm() < 1e-12;
      if (!seen) out.push_back(v);
    }
  return out;
}

std::vector<Vector3d> cyclic(const Vector3d& v) {
  return {v, Vector3d(v.z(), v.x(), v.y()), Vector3d(v.y(), v.z(), v.x())};
}

StyleParams make(std::vector<Vector3d> normals) {
  StyleParams p;
  for (Vector3d& n : normals) n.normalize();
  p.normals = std::move(normals);
  return p;
}

StyleParams make_rings(std::vector<double> offsets) {
  StyleParams p;
  p.normals = {Vector3d(0, 0, 1), Vector3d(0, 0, -1)};  // the axis normals (bases of the solid)
  p.axis = Vector3d::UnitZ();
  p.ring_offsets = std::move(offsets);
  return p;
}

double golden_ratio() { return (1.0 + std::sqrt(5.0)) / 2.0; }

struct Preset {
  const char* name;
  StyleParams (*build)();
};

// The registry (see presets.h): append only, never reorder or rename.
const Preset kPresets[] = {
    {"cube", [] { return make(all_signs({Vector3d(1, 0, 0), Vector3d(0, 1, 0), Vector3d(0, 0, 1)})); }},
    // Flat base facing down, the other three faces leaning outwards (cos = 1/3 with the base).
    {"tetrahedron", [] { return make(with_caps(ring_of_normals(3, std::asin(1.0 / 3.0), kPi / 2), false, true)); }},
    {"octahedron", [] { return make(all_signs({Vector3d(1, 1, 1)})); }},
    // Face normals = icosahedron vertices.
    {"dodecahedron", [] { return make(all_signs(cyclic(Vector3d(0, 1, golden_ratio())))); }},
    // Face normals = dodecahedron vertices.
    {"icosahedron",
     [] {
       std::vector<Vector3d> base = cyclic(Vector3d(0, 1.0 / golden_ratio(), golden_ratio()));
       base.emplace_back(1, 1, 1);
       return make(all_signs(base));
     }},
    {"square_pyramid", [] { return make(with_caps(ring_of_normals(4, kPi / 4), false, true)); }},
    {"truncated_pyramid", [] { return make(with_caps(ring_of_normals(4, kPi / 4), true, true)); }},
    {"triangular_prism", [] { return make(with_caps(ring_of_normals(3, 0.0, kPi / 2), true, true)); }},
    {"hexagonal_prism", [] { return make(with_caps(ring_of_normals(6, 0.0), true, true)); }},
    {"plane", [] { return make({Vector3d(0, 0, 1), Vector3d(0, 0, -1)}); }},
    {"cylinder", [] { return make_rings({0.0}); }},
    {"cone", [] { return make_rings({0.5}); }},  // surface normals 30 degrees above the equator
    {"double_cone", [] { return make_rings({0.5, -0.5}); }},
    // No fixed directions: each face's preferred normal comes from its neighbours' (preference_function.h).
    {"sheet_metal",
     [] {
       StyleParams p;
       p.kind = StyleKind::developable;
       p.sigma = settings::sheet_metal_sigma;
       return p;
     }},
};

}  // namespace

const std::vector<std::string>& preset_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const Preset& p : kPresets) out.emplace_back(p.name);
    return out;
  }();
  return names;
}

StyleParams preset_style(const std::string& name) {
  for (const Preset& p : kPresets)
    if (name == p.name) return p.build();
  std::string valid;
  for (const Preset& p : kPresets) valid += (valid.empty() ? "" : ", ") + std::string(p.name);
  throw std::invalid_argument("unknown style preset '" + name + "'; valid presets: " + valid);
}

}  // namespace gauss
