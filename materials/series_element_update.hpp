#pragma once
// The local problem of the Hill fibre (thesis 3.22–3.39, Appendix D, Kojic et al. 1998): find the
// series-element stretch increment Δλs such that the SEE and CE stresses agree (3.24),
//   g(Δλs) = σ_SEE(Δλs) - s·f_v(Δλm(Δλs)) = 0,
//   σ_SEE = β[exp(α(^tλs + Δλs - 1)) - 1] (3.22–3.23),  Δλm = α1 - k Δλs (D.8),
// with s = σ0 f_t f_λ > 0 and α1 = (1 + k) λ̄f - ^tλm - k ^tλs (3.39). Multiplying g by the
// denominator of f_v gives the thesis form (3.30) f = (a2 + a3 Δλs) e^(α Δλs) - a4 Δλs - a5 with
// the exponent α (SPEC erratum: 3.30 prints α4); g is solved instead because it is strictly
// increasing in Δλs on the branch's domain, so its root is unique and can be bracketed in closed
// form, which the polynomial-exponential form (with spurious roots behind the poles of f_v) is not.
#include <limits>

#include "materials/hill_curves.hpp"

namespace isomuscle::materials {

struct SeriesElementProblem {
  double alpha = 10.0;         // α, SEE exponent (3.23), dimensionless
  double beta = 1.0e3;         // β, SEE stress scale (3.23), Pa
  double k = 0.3;              // L_SEE0 / L_CE0 (D.2)
  double lambda_s_prev = 1.0;  // ^tλs
  double alpha1 = 0.0;         // (1 + k) λ̄f - ^tλm - k ^tλs (3.39)
  double s = 0.0;              // σ0 f_t f_λ, Pa, must be > 0 (an inactive fibre needs no solve)
  double k_c = 5.0;            // force–velocity shape (3.29)
  double k_e = 5.0;            // force–velocity shape (3.29)
  double d = 1.5;              // eccentric offset (3.29), >= 1
  double r = 0.0;              // Δt·v_max > 0 (v_max = -λ̇min), stretch
  // false: the force–velocity branch is the one of the solution's own Δλm (implicit; g is then
  // continuous across Δλm = 0). true: `branch` is used whatever the sign of Δλm (the Fortran picks
  // it from the previous step's Δλm).
  bool fixed_branch = false;
  FvBranch branch = FvBranch::shortening;
  // A starting point for Newton (e.g. the previous substep's Δλs), NaN for none: plain Newton
  // from it first, then the bracketed solve from it when it lies inside the bracket. It changes
  // the iterations, not the root (unique on the bracket).
  double initial_guess = std::numeric_limits<double>::quiet_NaN();
};

struct SeriesElementSolution {
  bool converged = false;
  int iterations = 0;
  double delta_lambda_s = 0.0;  // Δλs
  double sigma_see = 0.0;       // σ_SEE at t + Δt, Pa
  double residual = 0.0;        // g at the solution, Pa
  double tolerance = 0.0;       // |g| accepted as converged: 1e-10 (β + s + |σ_SEE|), Pa
  FvBranch branch = FvBranch::shortening;  // force–velocity branch at the solution
  ForceVelocity fv;                        // f_v and its derivatives at the solution
  double dg_ddls = 0.0;                    // ∂g/∂Δλs at the solution, Pa
  double dsigma_ddls = 0.0;                // dσ_SEE/dΔλs = αβ exp(α(λs - 1)), Pa
};

// g(Δλs) on a given branch (the residual above), Pa; +-infinity beyond the branch's pole.
double series_element_residual(const SeriesElementProblem& p, FvBranch branch,
                               double delta_lambda_s);

// g(Δλs) = 0. With an initial guess, plain Newton from it first, each iterate on the branch of its
// own Δλm (at most 8 steps, each one reducing |g|, within the branch's domain); that is all a
// close guess needs, and it skips the bracket's log1p and exp. Otherwise, or when that fails:
// safeguarded Newton (bracketed, bisection fallback). The bracket is closed-form:
// between Δλs_iso = α1/k (Δλm = 0, f_v = 1) and Δλs_s (σ_SEE = s), since f_v <= 1 for Δλm <= 0
// and f_v >= 1 for Δλm >= 0. Converged when |g| <= tolerance, or when the bracket has shrunk to a
// few doubles with σ_SEE equal at both ends to tolerance (g then jumps across the root because f_v
// is ill-conditioned: next to a pole of a lagged branch, or for a vanishing step, where the answer
// is the frozen-CE limit). Never returns NaN: invalid input (non-finite values, s <= 0, r <= 0,
// α, β, k <= 0, d < 1) or an overflowing σ_SEE gives converged = false.
SeriesElementSolution solve_series_element(const SeriesElementProblem& p);

}  // namespace isomuscle::materials
