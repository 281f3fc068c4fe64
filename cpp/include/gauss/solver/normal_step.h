#pragma once
// The per-face normal update of Algorithm 1's ADMM round (paper Eqs. 17-22), and the symmetric 3x3
// solve it and the edge update (Eq. 24) share. Pure functions of their arguments: no allocation, safe
// to call from many threads at once.
#include <Eigen/Core>

#include "gauss/style/preference_function.h"

namespace gauss {

// Solves H x = b for a symmetric 3 by 3 H (by cofactors).
//   H  3 by 3 symmetric;  b  3;  x  3 (output, written only on success)
// Returns false, leaving x unspecified, if H is numerically singular (|det H| <= 1e-12 max|H_ij|^3),
// holds NaN or infinity, or the solution is not finite.
bool solve_symmetric3(const Eigen::Matrix3d& H, const Eigen::Vector3d& b, Eigen::Vector3d& x);

// One Newton update of a face's auxiliary normal n* for
//   L_n(n) = -g(n) + sum_k lw_k / 2 (u_k + n . es_k)^2   over unit n   (Eq. 18),
// projected onto the tangent plane at n and normalized (Eq. 22). When the Newton direction is not
// defined, only rescales n, or points uphill, a projected gradient step of size 0.1 is taken instead
// (the paper's fallback).
//   style  g (Eqs. 9-15);  n  3, unit: the current n*
//   es  3 by 3: the face's three auxiliary edges e*_ij;  lw  3: lambda * w_ij of each
//   u   3: the scaled duals u_fij
//   preferred  3, unit, or nullptr: the normal the face's neighbourhood prefers, which a developable
//              style's g is centred on (PreferenceFunction::evaluate); other styles ignore it
// Returns the new unit normal (n itself if the update is not finite).
Eigen::Vector3d newton_normal(const PreferenceFunction& style, const Eigen::Vector3d& n, const Eigen::Vector3d* es,
                              const double* lw, const double* u, const Eigen::Vector3d* preferred = nullptr);

// One style of a face that blends several: the face's preference is sum_k share_k g_k(n), where
// share_k = w_k mu_k / sum_j w_j mu_j (w: the face's weight for the style). The paper's rho = mu lambda,
// taken with the face's summed mu, keeps the normal's local problem independent of mu.
struct StyleShare {
  int style;  // index into the style list
  double share;
};

// newton_normal for the blend of `count` >= 1 styles (shares[k].style indexes `styles`): the same
// update with g, its gradient and its Hessian summed over the styles, each scaled by its share.
Eigen::Vector3d newton_normal(const PreferenceFunction* styles, const StyleShare* shares, int count,
                              const Eigen::Vector3d& n, const Eigen::Vector3d* es, const double* lw, const double* u,
                              const Eigen::Vector3d* preferred = nullptr);

// Does a face of this style take trust_region_normal (unless the solver's paper_step_any_sigma says
// otherwise)? Above settings::paper_step_max_sigma, for styles of fixed directions without rings whose
// bumps stand apart (PreferenceFunction::separation() above settings::trust_region_min_separation).
// Sheet Metal's one bump moves with the face's neighbourhood, and the step left the corpus less
// developable; rings and close bumps: docs/high_sigma.md.
bool takes_trust_region_step(const PreferenceFunction& style);

// The update of newton_normal for the same L_n(n), taken on the sphere: one Newton step with the
// Riemannian gradient and Hessian (the 3D Hessian projected, less the radial part of the gradient), kept
// within one bump's width of g (1 / sqrt(sigma); the blend's: its sharpest style's) and only where it
// lowers L_n (retried at smaller radii, else n stays). The paper's step solves with the 3D Hessian, whose
// tangent part is the edge coupling less the other bumps' pull: above settings::paper_step_max_sigma the
// two cancel for the styles takes_trust_region_step names, its steps turn huge or uphill, faces jump
// between bumps and switch between Newton and the fallback at every step, and a run never settles; this
// one settles there (docs/high_sigma.md). Arguments as newton_normal's.
Eigen::Vector3d trust_region_normal(const PreferenceFunction& style, const Eigen::Vector3d& n, const Eigen::Vector3d* es,
                                    const double* lw, const double* u, const Eigen::Vector3d* preferred = nullptr);
Eigen::Vector3d trust_region_normal(const PreferenceFunction* styles, const StyleShare* shares, int count,
                                    const Eigen::Vector3d& n, const Eigen::Vector3d* es, const double* lw,
                                    const double* u, const Eigen::Vector3d* preferred = nullptr);

}  // namespace gauss
