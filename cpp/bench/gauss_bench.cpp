// gauss_bench MESH [--method gauss|cubic] [--style NAME] [--lambda L] [--sigma S] [--mu M] [--steps N]
//             [--admm N] [--until TOL] [--acceleration on|off] [--avoid-self-intersections [--contact-stiffness K]]
//             [--resolution-independent [--reference-face-area A]] [--square-flat-regions]
//             [--paper-step-any-sigma] [--threads N] [--out OUT.obj]   (defaults: the solver's, printed by usage())
// Times set-up and steps of the solver on one mesh and reports how far the style took hold.
// --lambda is the lambda of the chosen method (settings::lambda or settings::cubic_lambda); the cubic
// method uses the style's mu and rotation only, and its share is measured against the cube's normals.
// --until TOL steps until a step's reldV is below TOL (--steps N is then the cap) and reports the
// steps and milliseconds that took (steps_to_converge, ms_to_converge). --acceleration off runs the
// plain iteration of Algorithm 1 (to compare with the accelerated default). --avoid-self-intersections
// turns the solver's guard on (self_intersection.h). Every run prints intersecting_pairs: BEFORE ->
// AFTER, the pairs of faces that cross in the input and in the result (each pair once; Blender's
// BVHTree.overlap lists each twice), and step_held_vertices_max, the most vertices the guard held back
// in one step; with the guard also contact_springs_max and contact_iterations_median (contact_springs.h),
// whose stiffness --contact-stiffness sets (0: the guard alone). --resolution-independent tops the bending of a finer mesh up to
// the reference density's and weighs a coarser face's preference by its area
// (settings::resolution_independent, docs/resolution.md); --weigh-finer-faces adds that setting's rule
// before 2026-12-06 (settings::weigh_finer_faces); --reference-face-area sets its reference density
// (default settings::reference_face_area), to measure that choice.
// A preset's name may be written with '-' for '_' (--style sheet-metal); sheet_metal runs at
// settings::sheet_metal_lambda unless --lambda says otherwise. Every run prints
// developability: IN -> OUT (mesh/developability.h) and flat_vertices_share: IN -> OUT, the share of
// interior vertices whose angle defect is below 0.01 rad (mesh/flat_vertex_share.h).
// --square-flat-regions squares the outlines of large flat regions (settings::square_flat_regions,
// flat_regions.h). Every run on a mesh with a large flat region prints squareness: IN -> OUT, the
// squareness (mesh/squareness.h) of the faces facing along the largest region's normal.
// --paper-step-any-sigma takes the paper's normal step above settings::paper_step_max_sigma too, as
// before 2026-12-07 (settings::paper_step_any_sigma).
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iterator>
#include <string>
#include <vector>

#include "gauss/collision/self_intersection.h"
#include "gauss/mesh/alignment_share.h"
#include "gauss/solver/normal_step.h"
#include "gauss/mesh/developability.h"
#include "gauss/mesh/flat_vertex_share.h"
#include "gauss/mesh/mesh_topology.h"
#include "gauss/mesh/squareness.h"
#include "gauss/solver/flat_regions.h"
#include "gauss/solver/gauss_solver.h"
#include "gauss/mesh/mesh_io.h"
#include "gauss/util/parallel.h"
#include "gauss/style/presets.h"
#include "gauss/settings.h"

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

constexpr int kDefaultSteps = 50;
constexpr int kDefaultCap = 5000;  // with --until and no --steps

int usage() {
  namespace settings = gauss::settings;
  std::fprintf(stderr,
               "usage: gauss_bench MESH [--method %s] [--style %s] [--lambda %g (cubic: %g)] [--sigma %g] [--mu %g]\n"
               "                   [--steps %d] [--admm %d] [--until TOL (e.g. %g; then --steps is the cap, default %d)]\n"
               "                   [--acceleration %s] [--avoid-self-intersections [--contact-stiffness K (default %g)]]\n"
               "                   [--resolution-independent [--weigh-finer-faces]]\n"
               "                   [--reference-face-area A (default %g)] [--square-flat-regions]\n"
               "                   [--paper-step-any-sigma] [--threads N] [--out OUT.obj]\n",
               settings::default_method, settings::default_preset, settings::lambda.default_value,
               settings::cubic_lambda.default_value, settings::sigma.default_value, settings::mu.default_value,
               kDefaultSteps, static_cast<int>(settings::admm_iterations.default_value),
               settings::tolerance.default_value, kDefaultCap,
               settings::acceleration.default_value ? "on" : "off", gauss::ContactSprings::kDefaultStiffness,
               settings::reference_face_area);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage();
  std::string mesh_path = argv[1], style = gauss::settings::default_preset, out_path;
  std::string method_name = gauss::settings::default_method;
  namespace settings = gauss::settings;
  double lambda = -1, sigma = 0, mu = settings::mu.default_value;  // lambda < 0: the method's default
  bool sigma_given = false;  // otherwise the preset's
  int steps = -1, admm = static_cast<int>(settings::admm_iterations.default_value), threads = 0;
  bool until_converged = false;  // --until given; otherwise exactly `steps` steps
  double until = 0;
  bool acceleration = settings::acceleration.default_value;
  bool avoid_self_intersections = settings::avoid_self_intersections.default_value;
  bool resolution_independent = settings::resolution_independent.default_value;
  bool weigh_finer_faces = settings::weigh_finer_faces.default_value;
  double reference_face_area = settings::reference_face_area;
  double contact_stiffness = gauss::ContactSprings::kDefaultStiffness;
  bool square_flat_regions = settings::square_flat_regions.default_value;
  bool paper_step_any_sigma = settings::paper_step_any_sigma.default_value;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--avoid-self-intersections") {  // a flag without a value
      avoid_self_intersections = true;
      continue;
    }
    if (a == "--resolution-independent") {
      resolution_independent = true;
      continue;
    }
    if (a == "--weigh-finer-faces") {
      weigh_finer_faces = true;
      continue;
    }
    if (a == "--square-flat-regions") {
      square_flat_regions = true;
      continue;
    }
    if (a == "--paper-step-any-sigma") {
      paper_step_any_sigma = true;
      continue;
    }
    if (i + 1 >= argc) return usage();
    const char* v = argv[++i];
    if (a == "--method") method_name = v;
    else if (a == "--style") style = v, std::replace(style.begin(), style.end(), '-', '_');
    else if (a == "--lambda") lambda = std::atof(v);
    else if (a == "--sigma") sigma = std::atof(v), sigma_given = true;
    else if (a == "--mu") mu = std::atof(v);
    else if (a == "--steps") steps = std::atoi(v);
    else if (a == "--admm") admm = std::atoi(v);
    else if (a == "--threads") threads = std::atoi(v);
    else if (a == "--reference-face-area") reference_face_area = std::atof(v);
    else if (a == "--contact-stiffness") contact_stiffness = std::atof(v);
    else if (a == "--until") until_converged = true, until = std::atof(v);
    else if (a == "--acceleration" && (std::strcmp(v, "on") == 0 || std::strcmp(v, "off") == 0))
      acceleration = std::strcmp(v, "on") == 0;
    else if (a == "--out") out_path = v;
    else return usage();
  }
  int method_index = -1;
  for (size_t i = 0; i < std::size(settings::method_names); ++i)
    if (method_name == settings::method_names[i]) method_index = static_cast<int>(i);
  if (method_index < 0) return usage();
  const gauss::Method method = static_cast<gauss::Method>(method_index);
  const bool cubic = method == gauss::Method::cubic;
  const bool sheet_metal = style == "sheet_metal";
  if (lambda < 0)
    lambda = cubic ? settings::cubic_lambda.default_value
                   : sheet_metal ? settings::sheet_metal_lambda : settings::lambda.default_value;
  if (steps < 0) steps = until_converged ? kDefaultCap : kDefaultSteps;
  try {
    if (until_converged) settings::tolerance.check(until);
    if (threads > 0) gauss::parallel::set_max_threads(threads);
    std::printf("threads: %d\n", gauss::parallel::max_threads());
    std::printf("acceleration: %s\n", acceleration ? "on" : "off");
    gauss::TriangleMesh mesh = gauss::read_mesh(mesh_path);
    std::printf("mesh: %s (%d vertices, %d faces)\n", mesh_path.c_str(), mesh.num_vertices(), mesh.num_faces());
    gauss::StyleParams params = gauss::preset_style(style);
    if (sigma_given) params.sigma = sigma;
    params.mu = mu;
    gauss::PreferenceFunction g(params);

    const auto t0 = std::chrono::steady_clock::now();
    gauss::GaussSolver solver(mesh.V.data(), mesh.num_vertices(), mesh.F.data(), mesh.num_faces(), {},
                              nullptr, cubic ? settings::lambda.default_value : lambda);
    solver.set_styles({g});
    solver.set_admm_iterations(admm);
    if (cubic) solver.set_cubic_lambda(lambda);
    solver.set_method(method);
    solver.set_acceleration(acceleration);
    solver.set_avoid_self_intersections(avoid_self_intersections);
    solver.set_contact_stiffness(contact_stiffness);
    solver.set_resolution_independent(resolution_independent);
    solver.set_weigh_finer_faces(weigh_finer_faces);
    solver.set_reference_face_area(reference_face_area);
    solver.set_square_flat_regions(square_flat_regions);
    solver.set_paper_step_any_sigma(paper_step_any_sigma);
    const double setup_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

    if (until_converged) solver.set_tolerance(until);  // held_back() compares with it
    std::vector<double> step_ms, faces, rotations, admm_ms, rhs, solve, guard_ms, cubic_iterations;
    std::vector<double> contact_iterations;
    int multi_threaded_steps = 0, held_max = 0, springs_max = 0;
    double total_ms = 0;
    for (int s = 0; s < steps; ++s) {
      const auto t = std::chrono::steady_clock::now();
      solver.step();
      step_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count());
      total_ms += step_ms.back();
      const gauss::StepTimings& pt = solver.last_timings();
      faces.push_back(pt.faces);
      rotations.push_back(pt.rotations);
      admm_ms.push_back(pt.admm);
      rhs.push_back(pt.rhs);
      solve.push_back(pt.solve);
      guard_ms.push_back(pt.guard);
      multi_threaded_steps += pt.threads > 1;
      held_max = std::max(held_max, solver.held_vertices());
      springs_max = std::max(springs_max, solver.contact_springs());
      if (solver.contact_springs() > 0) contact_iterations.push_back(solver.contact_iterations());
      cubic_iterations.push_back(static_cast<double>(solver.cubic_admm_iterations()) / mesh.num_vertices());
      if (until_converged && solver.last_reldv() < until) break;
    }
    const int taken = static_cast<int>(step_ms.size());
    std::printf("method: %s\nlambda: %g\n", settings::method_names[method_index], lambda);
    std::printf("setup_ms: %.2f\n", setup_ms);
    std::printf("steps_on_all_threads: %d of %d\n", multi_threaded_steps, taken);
    std::printf("factor_nonzeros: %lld\n", solver.factor_nonzeros());
    std::printf("step_ms_median: %.3f\n", median(step_ms));
    std::printf("phase_faces_ms_median: %.3f\n", median(faces));
    std::printf("phase_rotations_ms_median: %.3f\n", median(rotations));
    std::printf("phase_admm_ms_median: %.3f\n", median(admm_ms));
    std::printf("phase_rhs_ms_median: %.3f\n", median(rhs));
    std::printf("phase_solve_ms_median: %.3f\n", median(solve));
    if (avoid_self_intersections) std::printf("phase_guard_ms_median: %.3f\n", median(guard_ms));
    if (cubic) std::printf("cubic_admm_iterations_per_vertex_median: %.3f\n", median(cubic_iterations));
    std::printf("last_reldv: %.4g\n", solver.last_reldv());
    std::printf("held_vertices_last_step: %d\n", solver.held_vertices());
    if (until_converged) {
      if (solver.held_back()) {  // at rest, but only because the guard holds it: not converged
        std::printf("steps_to_converge: held back by the guard after %d steps\n", taken);
        std::printf("ms_to_converge: held back after %.1f ms\n", total_ms);
      } else if (solver.last_reldv() < until) {
        std::printf("steps_to_converge: %d\n", taken);
        std::printf("ms_to_converge: %.1f\n", total_ms);
      } else {  // not a number: a table must not show the cap as if it were a result
        std::printf("steps_to_converge: not within %d steps\n", taken);
        std::printf("ms_to_converge: not within %.1f ms\n", total_ms);
      }
    }

    std::vector<double> result(mesh.V.size());
    solver.copy_vertices(result.data());
    // The cubic method's preferred normals are the cube's (the benchmark's style is not rotated).
    const gauss::PreferenceFunction cube(gauss::preset_style("cube"));
    const std::vector<Eigen::Vector3d>& share_normals = cubic ? cube.normals() : g.normals();
    if (cubic || (!params.normals.empty() && params.ring_offsets.empty())) {
      const double before = gauss::alignment_share(mesh.V.data(), mesh.F.data(), mesh.num_faces(), share_normals);
      const double after = gauss::alignment_share(result.data(), mesh.F.data(), mesh.num_faces(), share_normals);
      std::printf("axis_share_10deg: %.4f -> %.4f\n", before, after);
    }
    std::printf("developability: %.4g -> %.4g\n",
                gauss::developability(mesh.V.data(), mesh.num_vertices(), mesh.F.data(), mesh.num_faces()),
                gauss::developability(result.data(), mesh.num_vertices(), mesh.F.data(), mesh.num_faces()));
    std::printf("flat_vertices_share: %.4f -> %.4f\n",
                gauss::flat_vertex_share(mesh.V.data(), mesh.num_vertices(), mesh.F.data(), mesh.num_faces()),
                gauss::flat_vertex_share(result.data(), mesh.num_vertices(), mesh.F.data(), mesh.num_faces()));
    {
      // The largest flat region of the input (the solver's own search), whose normal is "up".
      const gauss::MeshTopology topo = gauss::build_mesh_topology(mesh.num_vertices(), mesh.F.data(), mesh.num_faces());
      std::vector<Eigen::Vector3d> rest(mesh.num_vertices());
      for (int v = 0; v < mesh.num_vertices(); ++v) rest[v] = Eigen::Vector3d(&mesh.V[3 * static_cast<size_t>(v)]);
      const gauss::SquareTargets regions = gauss::square_targets(topo, rest);
      std::printf("square_flat_regions: %s (%d large flat regions)\n", square_flat_regions ? "on" : "off",
                  static_cast<int>(regions.regions.size()));
      if (!regions.regions.empty()) {
        const auto largest = std::max_element(regions.regions.begin(), regions.regions.end(),
                                              [](const auto& a, const auto& b) { return a.area < b.area; });
        std::printf("squareness: %.4f -> %.4f\n", gauss::squareness(mesh.V.data(), mesh.F.data(), mesh.num_faces(), largest->normal),
                    gauss::squareness(result.data(), mesh.F.data(), mesh.num_faces(), largest->normal));
      }
    }
    std::vector<std::array<int, 3>> triangles;  // the input's faces without a repeated corner
    for (int f = 0; f < mesh.num_faces(); ++f) {
      const int64_t* t = &mesh.F[3 * static_cast<size_t>(f)];
      if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        triangles.push_back({static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])});
    }
    const auto points = [](const std::vector<double>& flat) {
      std::vector<Eigen::Vector3d> p(flat.size() / 3);
      for (size_t v = 0; v < p.size(); ++v) p[v] = Eigen::Vector3d(flat[3 * v], flat[3 * v + 1], flat[3 * v + 2]);
      return p;
    };
    std::printf("avoid_self_intersections: %s\n", avoid_self_intersections ? "on" : "off");
    std::printf("normal_step: %s\n", !cubic && gauss::takes_trust_region_step(g) && !paper_step_any_sigma
                                          ? "trust region on the sphere"
                                          : "the paper's");
    std::printf("resolution_independent: %s (reference face area %g%s)\n", resolution_independent ? "on" : "off",
                reference_face_area, weigh_finer_faces ? ", finer faces weighed" : "");
    std::printf("intersecting_pairs: %lld -> %lld\n",
                static_cast<long long>(gauss::count_self_intersections(triangles, points(mesh.V))),
                static_cast<long long>(gauss::count_self_intersections(triangles, points(result))));
    std::printf("step_held_vertices_max: %d\n", held_max);
    if (avoid_self_intersections) {
      std::printf("contact_stiffness: %g\n", contact_stiffness);
      std::printf("contact_springs_max: %d\n", springs_max);
      std::printf("contact_iterations_median: %g (%d steps with springs)\n",
                  contact_iterations.empty() ? 0.0 : median(contact_iterations), static_cast<int>(contact_iterations.size()));
    }
    if (cubic) std::printf("E_cubic: %.6g\n", solver.cubic_energy());
    else std::printf("E_g: %.6g\n", solver.g_energy());
    std::printf("E_ARAP: %.6g\n", solver.arap_energy());
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
