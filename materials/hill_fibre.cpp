#include "materials/hill_fibre.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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
  history[kSeeRate] = 0.0;
  history[kFibreRate] = 0.0;
  history[kSeeStress] = 0.0;
  history[kSeeStiffness] = 0.0;
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

namespace {

// y = Δλm / (Δt v_max) at which f_v = f (3.29 / 5.39 inverted; f_v is a Möbius function of y on
// each branch): shortening f = (1 + y)/(1 - k_c y), lengthening f = d - (d - 1)(1 - y)/(1 + k_c
// k_e y). NaN beyond the eccentric plateau (f >= d: no finite velocity).
double inverse_force_velocity(double f, double k_c, double k_e, double d) {
  if (f <= 1.0)
    return (std::max(f, 0.0) - 1.0) / (1.0 + std::max(f, 0.0) * k_c);
  if (f >= d)
    return std::numeric_limits<double>::quiet_NaN();
  return (f - 1.0) / ((d - f) * k_c * k_e + d - 1.0);
}

}  // namespace

// Number of substeps (header): m = ceil(α E / substep_see_strain) from the committed state, with E
// the a-priori bound or the estimate; dimensionless.
int HillFibre::substep_count(std::span<const double> history, double time, double dt) const {
  if (p_.explicit_lag || !(dt > 0.0))
    return 1;
  if (p_.substeps > 0)
    return p_.substeps;
  const double ft_now = p_.activation(time), ft_before = p_.activation(time - dt);
  const double ft = std::max(ft_now, ft_before);
  const double fl = force_length(history[kLambdaF], p_.lambda_opt);
  if (!(ft > 0.0) || !(fl > 0.0))
    return 1;  // inactive over the whole step (f_λ at the committed stretch)
  // Δλs_s: σ_SEE = σ0 f_t(t + Δt) f_λ(^tλ̄f) (3.23 inverted). The bound alone was the first rule:
  // the explicit-Euler estimate alone misses the start of the deactivation and of the shortening,
  // where the curves then differ by 0.6 % of the peak; E_see and E_act cover those.
  const double s = p_.sigma0 * ft_now * fl;
  const double dls_s = std::log1p(s / p_.beta) / p_.alpha - (history[kLambdaS] - 1.0);
  const double bound = std::min(std::abs(dls_s), dt * p_.v_max / p_.k);
  double E = bound;
  if (p_.substep_rule == SubstepRule::estimate) {
    // E_act: the SEE follows s = σ0 f_t f_λ; a switch from or to zero is a front (the bound).
    double e_act = 0.0;
    if (ft_now != ft_before)
      e_act = ft_now > 0.0 && ft_before > 0.0 ? std::abs(std::log(ft_now / ft_before)) / p_.alpha
                                              : bound;
    // E_ee: the CE velocity the committed SEE stress asks for (3.25 with σ_CE = σ_SEE), the fibre
    // at its last rate (D.8).
    double e_ee = bound;
    if (s > 0.0) {
      const double k_c = p_.a_v > 0.0 ? p_.sigma0 * fl / p_.a_v : p_.k_c;
      const double y = inverse_force_velocity(series_stress(history) / s, k_c, p_.k_e, p_.d);
      if (std::isfinite(y))
        e_ee = std::abs(((1.0 + p_.k) * history[kFibreRate] * dt - y * dt * p_.v_max) / p_.k);
    }
    const double e_see = std::abs(history[kSeeRate]) * dt;
    E = std::min(bound, std::max({e_ee, e_see, e_act}));
  }
  const double m = std::ceil(p_.alpha * E / p_.substep_see_strain);
  if (!(m > 1.0))
    return 1;
  return m < p_.max_substeps ? static_cast<int>(m) : p_.max_substeps;
}

// One backward-Euler substep of 3.22–3.39 (Appendix D) with forward sensitivities; stresses Pa.
bool HillFibre::substep(double lambda_j, double w, double lf_prev, double time_j, double h,
                        SubstepState& st, double& sigma_see, double& dsigma_dls,
                        int& iterations) const {
  const double k = p_.k;
  // s = σ0 f_t f_λ (3.25); f_λ at the substep's stretch unless explicit_lag.
  const double ft = p_.activation(time_j);
  double fl_slope = 0.0;
  const double fl = force_length(p_.explicit_lag ? lf_prev : lambda_j, p_.lambda_opt, &fl_slope);
  if (p_.explicit_lag)
    fl_slope = 0.0;
  const double s = p_.sigma0 * ft * fl;
  const double ds = p_.sigma0 * ft * fl_slope;
  // k_c constant (3.29) or k_c = σ0 f_λ / a_v (5.39).
  const double k_c = p_.a_v > 0.0 ? p_.sigma0 * fl / p_.a_v : p_.k_c;
  const double dk_c = p_.a_v > 0.0 ? p_.sigma0 * fl_slope / p_.a_v : 0.0;
  const double alpha1 = (1.0 + k) * lambda_j - st.lm - k * st.ls;  // 3.39 / D.9
  // dα1/dλ̄f through λ_j = lf0 + w (λ̄f - lf0) and the previous substep's λm, λs.
  const double dalpha1 = (1.0 + k) * w - st.dlm_dlf - k * st.dls_dlf;

  double dls = 0.0, ddls = 0.0;  // Δλs and dΔλs/dλ̄f
  if (!(s > 0.0)) {
    // Inactive: no force in CE and SEE, the CE slides freely (SPEC §2): λs = 1.
    dls = 1.0 - st.ls;
    ddls = -st.dls_dlf;
    sigma_see = 0.0;
    dsigma_dls = 0.0;
  } else if (h == 0.0) {
    // No time to move the CE: Δλm = 0, Δλs = α1/k (D.8), the Δt -> 0 limit of the solve.
    dls = alpha1 / k;
    ddls = dalpha1 / k;
    const double x = p_.alpha * (st.ls + dls - 1.0);
    if (!(x < kMaxExponent))
      return false;
    sigma_see = p_.beta * std::expm1(x);
    dsigma_dls = p_.alpha * p_.beta * std::exp(x);
  } else {
    SeriesElementProblem prob;
    prob.alpha = p_.alpha;
    prob.beta = p_.beta;
    prob.k = k;
    prob.lambda_s_prev = st.ls;
    prob.alpha1 = alpha1;
    prob.s = s;
    prob.k_c = k_c;
    prob.k_e = p_.k_e;
    prob.d = p_.d;
    prob.r = h * p_.v_max;
    prob.fixed_branch = p_.explicit_lag;
    prob.branch = st.dlm > 0.0 ? FvBranch::lengthening : FvBranch::shortening;  // Fortran: DRSM > 0
    prob.initial_guess = st.dls_guess;
    const SeriesElementSolution sol = solve_series_element(prob);
    iterations += sol.iterations;
    if (!sol.converged)
      return false;
    dls = sol.delta_lambda_s;
    sigma_see = sol.sigma_see;
    dsigma_dls = sol.dsigma_ddls;
    // Implicit function theorem on g(Δλs; λ̄f) = σ_SEE(^tλs + Δλs) - s(λ_j) f_v(α1 - kΔλs;
    // k_c(λ_j)) = 0, where λ_j, ^tλs and ^tλm (the previous substep's) depend on λ̄f:
    // dΔλs/dλ̄f = -(g_λ w + g_λs dλs/dλ̄f + g_λm dλm/dλ̄f) / g_Δλs.
    const double g_lambda =
        -ds * sol.fv.f - s * sol.fv.df_ddlm * (1.0 + k) - s * sol.fv.df_dkc * dk_c;
    const double g_ls = sol.dsigma_ddls + s * k * sol.fv.df_ddlm;
    const double g_lm = s * sol.fv.df_ddlm;
    ddls = -(g_lambda * w + g_ls * st.dls_dlf + g_lm * st.dlm_dlf) / sol.dg_ddls;
  }
  const double dlm = alpha1 - k * dls;  // D.8
  st.dls_guess = dls;                   // the next substep starts from this one's increment
  st.ls += dls;
  st.lm += dlm;
  st.dlm = dlm;
  st.dls_dlf += ddls;
  st.dlm_dlf += dalpha1 - k * ddls;
  return true;
}

// Thesis 3.22–3.39 with the readings listed in the header; stresses Pa, stretches dimensionless.
FibreResponse HillFibre::update(double lambda_f, double time, double dt,
                                std::span<const double> history, std::span<double> trial) const {
  FibreResponse out;
  const double ls0 = history[kLambdaS], lm0 = history[kLambdaM];
  const double dlm0 = history[kDeltaLambdaM], lf0 = history[kLambdaF];
  std::copy(history.begin(), history.end(), trial.begin());
  if (!std::isfinite(ls0) || !std::isfinite(lm0) || !std::isfinite(dlm0) || !std::isfinite(lf0) ||
      !std::isfinite(lambda_f) || !(lambda_f > 0.0) || !std::isfinite(time) || !std::isfinite(dt) ||
      dt < 0.0)
    return out;

  out.sigma_pe = parallel_stress(lambda_f, &out.dsigma_pe);
  const int m = substep_count(history, time, dt);
  SubstepState st{ls0, lm0, dlm0, 0.0, 0.0};
  // The first substep starts Newton from the last step's SEE rate.
  st.dls_guess = history[kSeeRate] * dt / m;
  double sigma_see = 0.0, dsigma_dls = 0.0, dlm_sum = 0.0;
  for (int j = 1; j <= m; ++j) {
    // λ̄f and t interpolated linearly over the step; the last substep ends exactly at (λ̄f, t).
    const double w = static_cast<double>(j) / m;
    const double lambda_j = j == m ? lambda_f : lf0 + w * (lambda_f - lf0);
    const double time_j = j == m ? time : time - dt + w * dt;
    const double lf_prev = j == 1 ? lf0 : lf0 + (w - 1.0 / m) * (lambda_f - lf0);
    if (!substep(lambda_j, w, lf_prev, time_j, dt / m, st, sigma_see, dsigma_dls, out.iterations))
      return out;
    dlm_sum += st.dlm;  // summed, not st.lm - ^tλm, to keep a tiny Δλm's sign and digits
  }
  out.sigma_see = sigma_see;
  // Thesis 5.54 (frozen CE over the whole step): U''_SE = αβ (1 + k)/k exp(α(λs - 1)).
  out.dsigma_see =
      p_.frozen_ce_tangent ? dsigma_dls * (1.0 + p_.k) / p_.k : dsigma_dls * st.dls_dlf;
  trial[kLambdaS] = st.ls;
  trial[kLambdaM] = st.lm;
  trial[kDeltaLambdaM] = dlm_sum;
  trial[kLambdaF] = lambda_f;
  if (dt > 0.0) {
    trial[kSeeRate] = (st.ls - ls0) / dt;
    trial[kFibreRate] = (lambda_f - lf0) / dt;
  }
  trial[kSeeStress] = out.sigma_see;
  trial[kSeeStiffness] = out.dsigma_see;
  out.substeps = m;
  out.ok = std::isfinite(out.sigma_see) && std::isfinite(out.dsigma_see) &&
           std::isfinite(trial[kLambdaM]);
  if (!out.ok)
    std::copy(history.begin(), history.end(), trial.begin());
  return out;
}

// The response update() stored with the trial history; stresses Pa.
FibreResponse HillFibre::response_of_trial(double lambda_f, std::span<const double> trial) const {
  FibreResponse out;
  out.sigma_pe = parallel_stress(lambda_f, &out.dsigma_pe);
  out.sigma_see = trial[kSeeStress];
  out.dsigma_see = trial[kSeeStiffness];
  out.ok = std::isfinite(out.sigma_see) && std::isfinite(out.dsigma_see);
  return out;
}

}  // namespace isomuscle::materials
