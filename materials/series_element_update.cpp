#include "materials/series_element_update.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace isomuscle::materials {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// exp() argument beyond which σ_SEE is taken as overflowed (e^600 ~ 4e260).
constexpr double kMaxExponent = 600.0;
// |g| <= kTolerance·(β + s + |σ_SEE|) is converged; the iteration tries for kTarget·(...) first so
// that stresses used in finite-difference tangent checks are accurate to round-off.
constexpr double kTolerance = 1e-10;
constexpr double kTarget = 1e-14;
constexpr int kMaxIterations = 200;

// The pole of the chosen formula in Δλs, if any, and on which side the valid domain lies.
struct Domain {
  double lo = -kInf, hi = kInf;
};

Domain branch_domain(const SeriesElementProblem& p, FvBranch branch) {
  Domain dom;
  if (branch == FvBranch::shortening && p.k_c > 0.0) {
    // r - k_c Δλm > 0  <=>  Δλm < r/k_c  <=>  Δλs > (α1 - r/k_c)/k.
    dom.lo = (p.alpha1 - p.r / p.k_c) / p.k;
  } else if (branch == FvBranch::lengthening && p.k_c * p.k_e > 0.0) {
    // r + k_c k_e Δλm > 0  <=>  Δλs < (α1 + r/(k_c k_e))/k.
    dom.hi = (p.alpha1 + p.r / (p.k_c * p.k_e)) / p.k;
  }
  return dom;
}

// σ_SEE(Δλs) = β[exp(α(^tλs + Δλs - 1)) - 1] (3.22–3.23) and dσ/dΔλs; Pa. One exp() (the
// absolute rounding error of β(e - 1) near λs = 1 is β·1e-16, far below the solve tolerance).
void see_stress(const SeriesElementProblem& p, double dls, double& sigma, double& dsigma) {
  const double e = std::exp(std::min(p.alpha * (p.lambda_s_prev - 1.0 + dls), kMaxExponent));
  sigma = p.beta * (e - 1.0);
  dsigma = p.alpha * p.beta * e;
}

// The converged (or best) point of the solve: Δλs, g, dg/dΔλs, σ_SEE and f_v there.
struct SeriesElementPoint {
  double x = 0.0, g = 0.0, dg = 0.0, sigma = 0.0;
  ForceVelocity fv;
  FvBranch branch = FvBranch::shortening;
};

SeriesElementSolution solution_at(const SeriesElementProblem& p, const SeriesElementPoint& at,
                                  int iterations, bool resolved) {
  SeriesElementSolution sol;
  sol.iterations = iterations;
  sol.tolerance = kTolerance * (p.beta + p.s + std::abs(at.sigma));
  sol.delta_lambda_s = at.x;
  sol.sigma_see = at.sigma;
  sol.residual = at.g;
  sol.branch = at.branch;
  sol.fv = at.fv;
  sol.dg_ddls = at.dg;
  sol.dsigma_ddls = at.dg - p.s * p.k * at.fv.df_ddlm;
  sol.converged = (std::abs(at.g) <= sol.tolerance || resolved) &&
                  p.alpha * (p.lambda_s_prev - 1.0 + at.x) < kMaxExponent;
  return sol;
}

// g, dg/dΔλs, σ_SEE and f_v at Δλs = x on `branch` (3.24–3.25 with D.8).
SeriesElementPoint evaluate_at(const SeriesElementProblem& p, FvBranch branch, double x) {
  SeriesElementPoint at;
  double dsigma = 0.0;
  see_stress(p, x, at.sigma, dsigma);
  at.fv = force_velocity(branch, p.alpha1 - p.k * x, p.r, p.k_c, p.k_e, p.d);
  at.g = at.sigma - p.s * at.fv.f;
  at.dg = dsigma + p.s * p.k * at.fv.df_ddlm;
  at.x = x;
  at.branch = branch;
  return at;
}

}  // namespace

// g(Δλs) = σ_SEE - s f_v(α1 - k Δλs) (3.24–3.25 with D.8), Pa.
double series_element_residual(const SeriesElementProblem& p, FvBranch branch, double dls) {
  const Domain dom = branch_domain(p, branch);
  if (dls <= dom.lo)
    return -kInf;
  if (dls >= dom.hi)
    return kInf;
  return evaluate_at(p, branch, dls).g;
}

namespace {

// At most this many Newton steps from the initial guess before the bracketed solve takes over.
constexpr int kGuessIterations = 8;

// Plain Newton from the caller's guess (the previous substep's Δλs, which is close): each iterate
// on its own force–velocity branch, the one of its Δλm (g is continuous across Δλm = 0 and
// strictly increasing, so a root found this way is the unique root of the implicit problem). It
// needs no bracket, which costs a log1p and an exp, more than the one or two Newton steps a good
// guess needs. Gives up (false) at the first step that leaves the branch's domain or does not
// reduce |g|; the bracketed solve then starts from the guess again.
bool newton_from_guess(const SeriesElementProblem& p, SeriesElementPoint& at, int& iterations) {
  double x = p.initial_guess;
  double last_g = kInf;
  for (int it = 0; it < kGuessIterations; ++it) {
    const FvBranch branch = p.fixed_branch             ? p.branch
                            : p.alpha1 - p.k * x > 0.0 ? FvBranch::lengthening
                                                       : FvBranch::shortening;
    const Domain dom = branch_domain(p, branch);
    if (!(x > dom.lo && x < dom.hi) || !(p.alpha * (p.lambda_s_prev - 1.0 + x) < kMaxExponent))
      return false;
    ++iterations;
    at = evaluate_at(p, branch, x);
    if (!std::isfinite(at.g) || !std::isfinite(at.dg) || !(std::abs(at.g) < std::abs(last_g)))
      return false;
    if (std::abs(at.g) <= kTarget * (p.beta + p.s + std::abs(at.sigma)))
      return true;
    if (!(at.dg > 0.0))
      return false;
    last_g = at.g;
    x -= at.g / at.dg;
  }
  return false;
}

}  // namespace

// Newton from the guess, else bracketed Newton on g (see header); Δλs dimensionless, stresses Pa.
SeriesElementSolution solve_series_element(const SeriesElementProblem& p) {
  SeriesElementSolution sol;
  const bool valid =
      std::isfinite(p.alpha) && p.alpha > 0.0 && std::isfinite(p.beta) && p.beta > 0.0 &&
      std::isfinite(p.k) && p.k > 0.0 && std::isfinite(p.lambda_s_prev) &&
      std::isfinite(p.alpha1) && std::isfinite(p.s) && p.s > 0.0 && std::isfinite(p.r) &&
      p.r > 0.0 && std::isfinite(p.k_c) && p.k_c >= 0.0 && std::isfinite(p.k_e) && p.k_e >= 0.0 &&
      std::isfinite(p.d) && p.d >= 1.0 && p.alpha * (p.lambda_s_prev - 1.0) < kMaxExponent;
  if (!valid)
    return sol;

  int guess_iterations = 0;
  if (std::isfinite(p.initial_guess)) {
    SeriesElementPoint at;
    if (newton_from_guess(p, at, guess_iterations))
      return solution_at(p, at, guess_iterations, false);
  }

  // Δλs_iso: CE holds its length (f_v = 1 in both formulas); Δλs_s: σ_SEE = s.
  const double dls_iso = p.alpha1 / p.k;
  const double dls_s = std::log1p(p.s / p.beta) / p.alpha - (p.lambda_s_prev - 1.0);
  double sigma_iso = 0.0, dsigma_iso = 0.0;
  see_stress(p, dls_iso, sigma_iso, dsigma_iso);
  const double g_iso = sigma_iso - p.s;
  // g_iso > 0: the root has Δλm > 0 (lengthening side), otherwise Δλm <= 0 (shortening side).
  FvBranch branch = g_iso > 0.0 ? FvBranch::lengthening : FvBranch::shortening;
  if (p.fixed_branch)
    branch = p.branch;
  double lo = std::min(dls_iso, dls_s), hi = std::max(dls_iso, dls_s);
  const Domain dom = branch_domain(p, branch);
  lo = std::max(lo, dom.lo);
  hi = std::min(hi, dom.hi);

  // g at the bracket ends without another exp(): g(Δλs_iso) = σ_iso - s (f_v = 1), g(Δλs_s) =
  // s (1 - f_v), -+inf at a pole.
  const auto end_value = [&](double x) {
    if (x <= dom.lo)
      return -kInf;
    if (x >= dom.hi)
      return kInf;
    if (x == dls_iso)
      return g_iso;
    return p.s * (1.0 - force_velocity(branch, p.alpha1 - p.k * x, p.r, p.k_c, p.k_e, p.d).f);
  };
  const double g_lo = end_value(lo);
  const double g_hi = end_value(hi);
  if (std::isnan(g_lo) || std::isnan(g_hi))
    return sol;
  // Start from the finite end with the smaller |g| (the iso end when it is the root).
  double x =
      (std::isfinite(g_lo) && (!std::isfinite(g_hi) || std::abs(g_lo) <= std::abs(g_hi))) ? lo : hi;
  if (!std::isfinite(g_lo) && !std::isfinite(g_hi))
    x = 0.5 * (lo + hi);
  if (std::isfinite(p.initial_guess) && p.initial_guess > lo && p.initial_guess < hi)
    x = p.initial_guess;

  // Tolerances scale with the stresses in the equation: β + s + |σ_SEE| (σ_SEE exceeds s only
  // when f_v > 1).
  SeriesElementPoint best, at;
  best.g = kInf;  // until a point is evaluated
  double step_before = hi - lo;
  bool resolved = false;
  int iterations = guess_iterations;
  for (int it = 0; it < kMaxIterations; ++it) {
    ++iterations;
    at = evaluate_at(p, branch, x);
    if (std::isnan(at.g))
      break;
    if (std::abs(at.g) < std::abs(best.g))
      best = at;
    if (std::abs(at.g) <= kTarget * (p.beta + p.s + std::abs(at.sigma)))
      break;
    if (at.g < 0.0) {
      lo = x;
    } else {
      hi = x;
    }
    if (hi - lo <=
        4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(lo), std::abs(hi))) {
      // The bracket is down to a few doubles: near a pole of f_v (lagged branch) or for a step so
      // short that Δλm cannot be resolved, g jumps across the root. The output σ_SEE is smooth in
      // Δλs, so the solve has succeeded when σ_SEE is the same at both ends to tolerance (and
      // σ_CE = σ_SEE by 3.24); f_v alone is then ill-conditioned.
      double s_lo = 0.0, s_hi = 0.0, unused = 0.0;
      see_stress(p, lo, s_lo, unused);
      see_stress(p, hi, s_hi, unused);
      resolved = std::abs(s_hi - s_lo) <= kTolerance * (p.beta + p.s + std::abs(s_hi));
      best = at;  // x is one of the two ends
      break;
    }
    // Newton if it stays inside the bracket and the last steps shrank fast enough, else bisect.
    // The Newton step is at least a few doubles long, so that a root closer than g can resolve is
    // crossed and the bracket collapses onto it.
    const double min_step = 4.0 * std::numeric_limits<double>::epsilon() *
                            std::max(std::abs(x), std::numeric_limits<double>::min());
    double newton = x - at.g / at.dg;
    if (std::abs(newton - x) < min_step)
      newton = x - std::copysign(min_step, at.g);
    const double step = std::abs(newton - x);
    if (std::isfinite(newton) && newton > lo && newton < hi && step <= 0.5 * step_before) {
      step_before = step;
      x = newton;
    } else {
      step_before = 0.5 * (hi - lo);
      x = 0.5 * (lo + hi);
    }
  }
  if (!std::isfinite(best.g) || !std::isfinite(best.dg))
    return sol;
  return solution_at(p, best, iterations, resolved);
}

}  // namespace isomuscle::materials
