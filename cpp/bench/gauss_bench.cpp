// gauss_bench MESH [--style NAME] [--lambda L] [--sigma S] [--mu M] [--steps N] [--admm N]
//             [--threads N] [--out OUT.obj]        (defaults: the solver's, printed by usage())
// Times set-up and steps of the solver on one mesh and reports how far the style took hold.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "gauss/alignment_share.h"
#include "gauss/gauss_solver.h"
#include "gauss/mesh_io.h"
#include "gauss/parallel.h"
#include "gauss/presets.h"
#include "gauss/settings.h"

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

constexpr int kDefaultSteps = 50;

int usage() {
  namespace settings = gauss::settings;
  std::fprintf(stderr,
               "usage: gauss_bench MESH [--style %s] [--lambda %g] [--sigma %g] [--mu %g] [--steps %d]\n"
               "                   [--admm %d] [--threads N] [--out OUT.obj]\n",
               settings::default_preset, settings::lambda.default_value, settings::sigma.default_value,
               settings::mu.default_value, kDefaultSteps, static_cast<int>(settings::admm_iterations.default_value));
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage();
  std::string mesh_path = argv[1], style = gauss::settings::default_preset, out_path;
  namespace settings = gauss::settings;
  double lambda = settings::lambda.default_value, sigma = settings::sigma.default_value,
         mu = settings::mu.default_value;
  int steps = kDefaultSteps, admm = static_cast<int>(settings::admm_iterations.default_value), threads = 0;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) return usage();
    const char* v = argv[++i];
    if (a == "--style") style = v;
    else if (a == "--lambda") lambda = std::atof(v);
    else if (a == "--sigma") sigma = std::atof(v);
    else if (a == "--mu") mu = std::atof(v);
    else if (a == "--steps") steps = std::atoi(v);
    else if (a == "--admm") admm = std::atoi(v);
    else if (a == "--threads") threads = std::atoi(v);
    else if (a == "--out") out_path = v;
    else return usage();
  }
  try {
    if (threads > 0) gauss::parallel::set_max_threads(threads);
    std::printf("threads: %d\n", gauss::parallel::max_threads());
    gauss::TriangleMesh mesh = gauss::read_mesh(mesh_path);
    std::printf("mesh: %s (%d vertices, %d faces)\n", mesh_path.c_str(), mesh.num_vertices(), mesh.num_faces());
    gauss::StyleParams params = gauss::preset_style(style);
    params.sigma = sigma;
    params.mu = mu;
    gauss::PreferenceFunction g(params);

    const auto t0 = std::chrono::steady_clock::now();
    gauss::GaussSolver solver(mesh.V.data(), mesh.num_vertices(), mesh.F.data(), mesh.num_faces(), {},
                              nullptr, lambda);
    solver.set_styles({g});
    solver.set_admm_iterations(admm);
    const double setup_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

    std::vector<double> step_ms, faces, rotations, admm_ms, rhs, solve;
    int multi_threaded_steps = 0;
    for (int s = 0; s < steps; ++s) {
      const auto t = std::chrono::steady_clock::now();
      solver.step();
      step_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count());
      const gauss::StepTimings& pt = solver.last_timings();
      faces.push_back(pt.faces);
      rotations.push_back(pt.rotations);
      admm_ms.push_back(pt.admm);
      rhs.push_back(pt.rhs);
      solve.push_back(pt.solve);
      multi_threaded_steps += pt.threads > 1;
    }
    std::printf("setup_ms: %.2f\n", setup_ms);
    std::printf("steps_on_all_threads: %d of %d\n", multi_threaded_steps, steps);
    std::printf("factor_nonzeros: %lld\n", solver.factor_nonzeros());
    std::printf("step_ms_median: %.3f\n", median(step_ms));
    std::printf("phase_faces_ms_median: %.3f\n", median(faces));
    std::printf("phase_rotations_ms_median: %.3f\n", median(rotations));
    std::printf("phase_admm_ms_median: %.3f\n", median(admm_ms));
    std::printf("phase_rhs_ms_median: %.3f\n", median(rhs));
    std::printf("phase_solve_ms_median: %.3f\n", median(solve));

    std::vector<double> result(mesh.V.size());
    solver.copy_vertices(result.data());
    if (!params.normals.empty() && params.ring_offsets.empty()) {
      const double before = gauss::alignment_share(mesh.V.data(), mesh.F.data(), mesh.num_faces(), g.normals());
      const double after = gauss::alignment_share(result.data(), mesh.F.data(), mesh.num_faces(), g.normals());
      std::printf("axis_share_10deg: %.4f -> %.4f\n", before, after);
    }
    std::printf("E_g: %.6g\nE_ARAP: %.6g\n", solver.g_energy(), solver.arap_energy());
    if (!out_path.empty()) {
      gauss::TriangleMesh out = mesh;
      out.V = result;
      gauss::write_obj(out_path, out);
      std::printf("wrote: %s\n", out_path.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gauss_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
