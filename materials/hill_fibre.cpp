#include "materials/hill_fibre.hpp"

#include <algorithm>
#include <cmath>

#include "materials/series_element_update.hpp"

namespace isomuscle::materials {

namespace {
constexpr double kMaxExponent = 600.0;  // as in series_element_update.cpp
}

// Appendix E, first call: RSS = 1, RSP = 1, RSM = (1 + k) RSP - k = 1, DRSM = 0.
void HillFibre::initial_history(std::span<double> history) const {
  history[kLambdaS] = 1.0;
  history[kLambdaM] = 1.0;
  history[kDeltaLambdaM] = 0.0;
  history[kLambdaF] = 1.0;
}

// Thesis 3.40–3.41 (5.37 with A = 4); Pa.
double HillFibre::parallel_stress(double lambda_f, double* slope) const {
  const double e = std::max(lambda_f - 1.0, 0.0);
  if (slope != nullptr)
    *slope = 2.0 * p_.sigma0 * p_.A * e;
  return p_.sigma0 * p_.A * e * e;
}

// Thesis 3.23; Pa.
double HillFibre::series_stress(std::span<const double> history) const {
  return p_.beta * std::expm1(p_.alpha * (history[kLambdaS] - 1.0));
}

// Thesis 3.22–3.39 with the readings listed in the header; stresses Pa, stretches dimensionless.
FibreResponse HillFibre::update(double lambda_f, double time, double dt,
                                std::span<const double> history, std::span<double> trial,
                                bool tangent) const {
  FibreResponse out;
  const double ls0 = history[kLambdaS], lm0 = history[kLambdaM];
  const double dlm0 = history[kDeltaLambdaM], lf0 = history[kLambdaF];
  std::copy(history.begin(), history.end(), trial.begin());
  if (!std::isfinite(ls0) || !std::isfinite(lm0) || !std::isfinite(dlm0) || !std::isfinite(lf0) ||
      !std::isfinite(lambda_f) || !(lambda_f > 0.0) || !std::isfinite(time) || !std::isfinite(dt) ||
      dt < 0.0)
    return out;

  const double k = p_.k;
  out.sigma_pe = parallel_stress(lambda_f, &out.dsigma_pe);

  // s = σ0 f_t(t + Δt) f_λ (3.25); f_λ at the current stretch unless explicit_lag.
  const double ft = p_.activation(time);
  double fl_slope = 0.0;
  const double fl = force_length(p_.explicit_lag ? lf0 : lambda_f, p_.lambda_opt, &fl_slope);
  if (p_.explicit_lag)
    fl_slope = 0.0;
  const double s = p_.sigma0 * ft * fl;
  const double ds = p_.sigma0 * ft * fl_slope;
  // k_c constant (3.29) or k_c = σ0 f_λ / a_v (5.39).
  const double k_c = p_.a_v > 0.0 ? p_.sigma0 * fl / p_.a_v : p_.k_c;
  const double dk_c = p_.a_v > 0.0 ? p_.sigma0 * fl_slope / p_.a_v : 0.0;
  const double alpha1 = (1.0 + k) * lambda_f - lm0 - k * ls0;  // 3.39 / D.9

  double ls = 1.0, dls = 0.0;
  if (!(s > 0.0)) {
    // Inactive: no force in CE and SEE, the CE slides freely (SPEC §2).
    ls = 1.0;
    out.sigma_see = 0.0;
    out.dsigma_see = 0.0;
    dls = ls - ls0;
  } else if (dt == 0.0) {
    // No time to move the CE: Δλm = 0, Δλs = α1/k (D.8), the Δt -> 0 limit of the solve.
    dls = alpha1 / k;
    ls = ls0 + dls;
    const double x = p_.alpha * (ls - 1.0);
    if (!(x < kMaxExponent))
      return out;
    out.sigma_see = p_.beta * std::expm1(x);
    out.dsigma_see = p_.alpha * p_.beta * std::exp(x) * (1.0 + k) / k;
  } else {
    SeriesElementProblem prob;
    prob.alpha = p_.alpha;
    prob.beta = p_.beta;
    prob.k = k;
    prob.lambda_s_prev = ls0;
    prob.alpha1 = alpha1;
    prob.s = s;
    prob.k_c = k_c;
    prob.k_e = p_.k_e;
    prob.d = p_.d;
    prob.r = dt * p_.v_max;
    prob.fixed_branch = p_.explicit_lag;
    prob.branch = dlm0 > 0.0 ? FvBranch::lengthening : FvBranch::shortening;  // Fortran: DRSM > 0
    const SeriesElementSolution sol = solve_series_element(prob);
    out.iterations = sol.iterations;
    if (!sol.converged)
      return out;
    dls = sol.delta_lambda_s;
    ls = ls0 + dls;
    out.sigma_see = sol.sigma_see;
    if (tangent) {
      const double dsigma_dls = sol.dsigma_ddls;
      if (p_.frozen_ce_tangent) {
        // Thesis 5.54: U''_SE = αβ (1 + k)/k exp(α(λs - 1)), the CE length frozen in the step.
        out.dsigma_see = dsigma_dls * (1.0 + k) / k;
      } else {
        // Implicit function theorem on g(Δλs; λ̄f) = σ_SEE(Δλs) - s(λ̄f) f_v(α1(λ̄f) - kΔλs;
        // k_c(λ̄f)) = 0 with dα1/dλ̄f = 1 + k: dΔλs/dλ̄f = -g_λ / g_Δλs.
        const double g_lambda =
            -ds * sol.fv.f - s * sol.fv.df_ddlm * (1.0 + k) - s * sol.fv.df_dkc * dk_c;
        out.dsigma_see = dsigma_dls * (-g_lambda / sol.dg_ddls);
      }
    }
  }
  const double dlm = alpha1 - k * dls;  // D.8
  trial[kLambdaS] = ls;
  trial[kLambdaM] = lm0 + dlm;
  trial[kDeltaLambdaM] = dlm;
  trial[kLambdaF] = lambda_f;
  out.ok = std::isfinite(out.sigma_see) && std::isfinite(out.dsigma_see) &&
           std::isfinite(trial[kLambdaM]);
  if (!out.ok)
    std::copy(history.begin(), history.end(), trial.begin());
  return out;
}

}  // namespace isomuscle::materials
