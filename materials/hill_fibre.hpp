#pragma once
// The Hill three-element fibre of a material point (thesis 3.20–3.41, Appendix D; chapter 5:
// 5.34–5.39, 5.52–5.54): PE in parallel with CE + SEE in series. Given the isochoric fibre stretch
// λ̄f at t + Δt and the committed history it returns the fibre "stress" U'_f = σ_SEE + σ_PE (3.20)
// and its consistent derivative U''_f = dU'_f/dλ̄f, and writes the trial history.
//
// History layout (kHillHistorySize doubles per point):
//   [0] lambda_s       λs, SEE stretch L_SEE/L_SEE0 (Fortran hsv(5))
//   [1] lambda_m       λm, CE stretch L_CE/L_CE0 (hsv(6))
//   [2] delta_lambda_m Δλm of the last step, summed over its substeps (hsv(8); the lagged branch
//                      choice reads it)
//   [3] lambda_f       λ̄f at the end of the last step (the lagged f_λ reads it; the Fortran
//                      stores σ0 f_λ(λ̄f) in hsv(7) instead)
//   [4] see_rate       Δλs/Δt of the last step, 1/s (the substep estimate reads it)
//   [5] fibre_rate     Δλ̄f/Δt of the last step, 1/s (ditto)
//   [6] see_stress     σ_SEE at the end of the last step, Pa, as update() returned it
//   [7] see_stiffness  dσ_SEE/dλ̄f of the last step, Pa (consistent or frozen-CE, as update()
//                      returned it); with [6] the response at the trial state, so that a second
//                      evaluation at the same state (Newton's tangent pass at the state its line
//                      search just evaluated) reads it instead of solving the step again
//                      (response_of_trial)
//
// Readings of the thesis chosen here (SPEC §2):
// * f_λ is evaluated at the current stretch λ̄f^(t+Δt) (implicit: the stress is then a function
//   of the current state only, which a Newton solver and its tangent need), not at the previous
//   step's stretch as in the Fortran; explicit_lag = true restores the Fortran's lag of both f_λ
//   and the force–velocity branch.
// * The force–velocity branch is that of the solution's own Δλm (see series_element_update.hpp);
//   the Fortran picks it from the previous step's Δλm (explicit_lag = true).
// * Inactive (s = σ0 f_t f_λ = 0): σ_SEE = σ_CE = 0 and the CE slides freely, so the history stays
//   consistent: λs = 1, λm = (1 + k) λ̄f - k. This is also the s -> 0 limit of the local solve.
//   The Fortran instead freezes λm while inactive and calls the fibre active only for
//   t0 < t < t1 + 0.1 s; here a fibre is active exactly when f_t(t) f_λ(λ̄f) > 0.
// * Δt = 0 with s > 0: the instantaneous response with the CE length frozen (the Δt -> 0 limit).
// * Tangent: consistent (implicit function theorem on the local equation, including f_λ(λ̄f) and,
//   for tang2009, k_c(λ̄f)), or the thesis's frozen-CE form 5.54 with frozen_ce_tangent = true.
// * Local sub-stepping (the backward-Euler step is first order in Δt and the SEE stress front after
//   an activation change is not resolved by Δt = 1e-3 s): the step [t, t + Δt] is split into m
//   equal substeps with λ̄f interpolated linearly between the committed λ̄f (history[3]) and the
//   current one and f_t evaluated at each substep's end; the history is advanced substep by
//   substep. substeps > 0 fixes m; substeps = 0 (default) picks m before the solve from the
//   committed state, t + Δt and Δt only (never from the trial λ̄f, so m is frozen while the global
//   Newton iterates on the step and the tangent is exact): m = ceil(α E / substep_see_strain),
//   capped at max_substeps, where E estimates the SEE stretch increment over the step:
//     bound     E_b = min(|Δλs_s|, v_max Δt / k), an a-priori bound (Δλs_s: the increment that
//               makes σ_SEE = σ0 f_t(t + Δt) f_λ(^tλ̄f); v_max Δt / k: the SEE stretch when the
//               CE shortens at its maximal rate); substep_rule = bound uses it alone.
//     estimate  (default) E = min(E_b, max(E_ee, E_see, E_act)): E_ee the explicit-Euler
//               increment Δλs = ((1 + k) Δλ̄f − Δλm)/k (D.8) with Δλ̄f at the last step's rate
//               and Δλm = Δt v_max y, y = f_v^-1(^tσ_SEE / s) the CE velocity that the committed
//               SEE stress asks for (3.29 inverted); E_see = |last step's Δλs/Δt| Δt; E_act =
//               |ln(f_t(t + Δt)/f_t(t))| / α, the SEE stretch that follows a change of s (the
//               bound E_b where f_t switches from or to zero). The bound is reached only at the
//               fronts; in a free contraction the fibre shortens with the CE, the SEE hardly
//               changes, and the bound overestimates the increment tenfold (measured on the
//               barrel: 64 substeps per step at Δt = 10 ms where 8 are within 0.05 % of the
//               converged tip displacement).
//   A point inactive at both t and t + Δt takes one step, and explicit_lag (the Fortran's lagged
//   update) always takes one. The tangent is chained through the substeps by forward
//   sensitivity: each substep's implicit-function derivative with respect to its λ̄f (weight j/m)
//   and to the previous substep's λs and λm. The frozen-CE tangent 5.54 freezes the CE over the
//   whole step. Accuracy and cost, measured: the isometric and concentric curves at Δt = 1e-3 and
//   1e-4 s agree within 0.14 % (lu2010) and 0.23 % (tang2009) of the peak stress with the
//   estimate and substep_see_strain = 0.01 (the defaults; at 0.025: 0.32 %, 0.52 %); the bound
//   at 0.025 gave 0.10 % / 0.31 % (0.05: 0.41 %; one step: 1.4 % lu2010, 4.6 % tang2009). On the
//   barrel's free contraction (examples/barrel/contract.toml, Δt up to 10 ms) the estimate takes
//   a few substeps where the bound took the cap of 64: 3.8 s instead of 9.3 s (with the local
//   Newton started from the previous substep's increment), tip displacement −14.4151 mm against
//   −14.4176 mm (fixed substeps 1, 2, 4, 8, 16 converge at first order towards −14.420 mm).
#include <span>

#include "materials/hill_curves.hpp"

namespace isomuscle::materials {

enum HillHistoryIndex : int {
  kLambdaS = 0,
  kLambdaM = 1,
  kDeltaLambdaM = 2,
  kLambdaF = 3,
  kSeeRate = 4,
  kFibreRate = 5,
  kSeeStress = 6,
  kSeeStiffness = 7,
  kHillHistorySize = 8,
};

// How the adaptive substep count is chosen (header).
enum class SubstepRule { estimate, bound };

struct HillFibreParameters {
  double alpha = 10.0;       // α, SEE (3.23)
  double beta = 1.0e3;       // β, SEE (3.23), Pa
  double k = 0.3;            // L_SEE0/L_CE0 (D.2)
  double sigma0 = 7.0e5;     // maximal isometric stress σ0, Pa
  double A = 4.0;            // PE coefficient: σ_PE = σ0 A (λ̄f - 1)² (3.41; 5.37 has A = 4)
  double lambda_opt = 1.05;  // optimal fibre stretch (3.28)
  double k_c = 5.0;          // force–velocity shape (3.29), used when a_v == 0
  double a_v = 0.0;          // > 0: k_c = σ0 f_λ(λ̄f) / a_v (5.39, Tang et al. 2009), Pa
  double k_e = 5.0;          // force–velocity shape (3.29)
  double d = 1.5;            // eccentric offset (3.29)
  double v_max = 17.0;       // maximal shortening rate, 1/s: -λ̇min (3.29) or λ̇m0 (5.39)
  ActivationCurve activation;
  bool frozen_ce_tangent = false;
  bool explicit_lag = false;
  int substeps = 0;  // > 0: fixed number of substeps; 0: adaptive (header)
  SubstepRule substep_rule = SubstepRule::estimate;  // adaptive: how E is estimated (header)
  double substep_see_strain = 0.01;  // adaptive: bound of α·Δλs per substep, dimensionless
  int max_substeps = 64;             // adaptive: cap on m
};

struct FibreResponse {
  bool ok = false;          // false: the local solve failed (trial history = committed)
  double sigma_see = 0.0;   // σ_SEE = σ_CE, Pa
  double sigma_pe = 0.0;    // σ_PE, Pa
  double dsigma_see = 0.0;  // dσ_SEE/dλ̄f, Pa (consistent or frozen-CE)
  double dsigma_pe = 0.0;   // dσ_PE/dλ̄f, Pa
  int iterations = 0;       // local Newton iterations, all substeps (0 when no solve was needed)
  int substeps = 0;         // substeps taken (0 when the input was invalid)
};

class HillFibre {
 public:
  explicit HillFibre(const HillFibreParameters& p) : p_(p) {}

  const HillFibreParameters& parameters() const { return p_; }
  // Undeformed, unactivated point: λs = λm = λ̄f = 1, Δλm = 0.
  void initial_history(std::span<double> history) const;
  // Activation level f_t(t) (3.26–3.27 or the chapter-5 ramp).
  double activation(double time) const { return p_.activation(time); }
  // σ_PE = σ0 A (λ̄f - 1)² for λ̄f > 1, else 0 (3.40–3.41); Pa. Writes dσ_PE/dλ̄f to *slope.
  double parallel_stress(double lambda_f, double* slope = nullptr) const;
  // σ_SEE = β[exp(α(λs - 1)) - 1] (3.23) from a history; Pa.
  double series_stress(std::span<const double> history) const;

  // One step to time `time` (= t + Δt) with step dt and stretch lambda_f = λ̄f^(t+Δt). Reads the
  // committed history, writes the trial history (both kHillHistorySize long, may not alias).
  // The derivatives dsigma_* are always computed: they are stored in the trial history ([7]), and
  // their forward sensitivities cost a division per substep against a local solve.
  FibreResponse update(double lambda_f, double time, double dt, std::span<const double> history,
                       std::span<double> trial) const;
  // The response that update() returned when it wrote `trial` at the stretch lambda_f: σ_SEE and
  // dσ_SEE/dλ̄f from the trial history, σ_PE and its slope from lambda_f; the same numbers, with
  // no local solve.
  FibreResponse response_of_trial(double lambda_f, std::span<const double> trial) const;
  // The number of substeps m that update() takes from a committed history to time `time` with
  // step dt (see the header); it does not depend on the trial λ̄f.
  int substep_count(std::span<const double> history, double time, double dt) const;

 private:
  // State advanced through the substeps, with its derivatives with respect to the step's λ̄f.
  struct SubstepState {
    double ls = 1.0, lm = 1.0, dlm = 0.0;  // λs, λm, Δλm of the last substep
    double dls_dlf = 0.0, dlm_dlf = 0.0;   // dλs/dλ̄f, dλm/dλ̄f
    double dls_guess = 0.0;                // where the next local Newton starts (Δλs)
  };
  // One backward-Euler substep of length h to λ̄f = lambda_j (= lf0 + w (λ̄f - lf0)) at time_j;
  // advances st, writes σ_SEE and dσ_SEE/dλs at its end. False when the local solve failed.
  bool substep(double lambda_j, double w, double lf_prev, double time_j, double h, SubstepState& st,
               double& sigma_see, double& dsigma_dls, int& iterations) const;

  HillFibreParameters p_;
};

}  // namespace isomuscle::materials
