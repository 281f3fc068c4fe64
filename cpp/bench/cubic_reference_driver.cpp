// Timing driver for the reference Cubic Stylization (github HTDerekLiu/CubicStylization_Cpp, libigl):
// our own code, calling only the reference's public functions, so that its per-iteration time can be
// set against gauss_bench --method cubic. Not part of the project's build; built by hand against a
// clone of the reference (docs/performance.md, "Per iteration against the cubic reference") and run
// by cpp/bench/compare_cubic_reference.py.
//
// Usage: cubic_reference_driver MESH LAMBDA [CAP] [EVERY]
//   Runs the reference's iteration on MESH (normalized to a unit bounding box and centred, as the
//   reference's own main does, with vertex F(0,0) pinned) until its reldV < 1e-3 or CAP iterations
//   (default 1000), tracing reldV and the axis share every EVERY iterations (default 50).
//   Threads: libigl's parallel_for reads IGL_NUM_THREADS.
// Output: "trace ..." lines, then one line
//   stopped after N reldv R share S ms_per_iter MEAN ms_per_iter_median MEDIAN
// with the times of cube_style_single_iteration alone (local and global step; no I/O, no set-up).
#include <igl/readOBJ.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <cube_style_data.h>
#include <cube_style_precomputation.h>
#include <cube_style_single_iteration.h>
#include <normalize_unitbox.h>

namespace {

// Area share of faces whose unit normal lies within 10 degrees of a coordinate axis (the same
// measure as gauss_bench's axis_share_10deg).
double axis_share(const Eigen::MatrixXd& U, const Eigen::MatrixXi& F) {
  const double cos10 = std::cos(10.0 * M_PI / 180.0);
  double total = 0, aligned = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = U.row(F(f, 1)) - U.row(F(f, 0)), b = U.row(F(f, 2)) - U.row(F(f, 0));
    const Eigen::Vector3d n = a.cross(b);
    const double area = n.norm();
    if (area == 0) continue;
    total += area;
    if ((n / area).cwiseAbs().maxCoeff() >= cos10) aligned += area;
  }
  return total > 0 ? aligned / total : 0.0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s MESH LAMBDA [CAP] [EVERY]\n", argv[0]);
    return 2;
  }
  Eigen::MatrixXd V, U;
  Eigen::MatrixXi F;
  cube_style_data data;
  if (!igl::readOBJ(argv[1], V, F) || V.rows() == 0 || F.rows() == 0) {
    std::fprintf(stderr, "cannot read a triangle mesh from %s\n", argv[1]);
    return 1;
  }
  data.lambda = std::atof(argv[2]);
  const int cap = argc > 3 ? std::atoi(argv[3]) : 1000;
  const int every = argc > 4 ? std::max(1, std::atoi(argv[4])) : 50;
  normalize_unitbox(V);
  const Eigen::RowVector3d mean = V.colwise().mean();
  V = V.rowwise() - mean;
  U = V;
  data.bc.resize(1, 3);
  data.bc << V.row(F(0, 0));
  data.b.resize(1);
  data.b << F(0, 0);
  cube_style_precomputation(V, F, data);
  std::printf("share before %.4f\n", axis_share(V, F));
  std::vector<double> ms;
  int it = 0;
  while (it < cap) {
    const auto start = std::chrono::steady_clock::now();
    cube_style_single_iteration(V, U, data);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    ++it;
    if (it % every == 0 || it <= 3) std::printf("trace %d reldv %.4e share %.4f\n", it, data.reldV, axis_share(U, F));
    if (data.reldV < 1e-3) break;
  }
  double sum = 0;
  for (double t : ms) sum += t;
  std::vector<double> sorted = ms;
  std::sort(sorted.begin(), sorted.end());
  const size_t n = sorted.size();
  const double median = n == 0 ? 0.0 : (n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]));
  std::printf("stopped after %d reldv %.4e share %.4f ms_per_iter %.2f ms_per_iter_median %.2f\n", it, data.reldV,
              axis_share(U, F), n ? sum / n : 0.0, median);
  return 0;
}
