#pragma once
// The three scalar curves of the Hill contractile element (thesis 3.25): activation f_t(t)
// (3.26–3.27, and the chapter-5 ramp), force–length f_λ(λ̄f) (3.28) and force–velocity f_v
// (3.29 / 5.39 written on stretch increments). All dimensionless.
#include <limits>

namespace isomuscle::materials {

// Activation level f_t(t) in [0, 1] (thesis 3.26–3.27, 5.6).
// ramp_time == 0: exponential rise n1 + (n2 - n1)(1 - exp(-S (t - t0))) for t0 <= t < t1, after t1
//   decay from the value reached at t1 with the same rate S (3.26 third line).
// ramp_time > 0: linear rise from n1 at t0 to n2 at t0 + ramp_time, held, and after t1 a linear
//   decay from the value reached at t1 back to n1 over ramp_time. With t0 = 0, ramp_time = 0.005 s
//   and t1 = inf this is the chapter-5 activation ("full after 0.005 s, then held", Figure 5.16;
//   the thesis does not give the shape of the rise, a straight line is the simplest reading).
struct ActivationCurve {
  double n1 = 0.0;                                      // level before t0 and after deactivation
  double n2 = 1.0;                                      // level during activation
  double t0 = 0.0;                                      // activation time, s
  double t1 = std::numeric_limits<double>::infinity();  // deactivation time, s
  double rate = 50.0;                                   // S, 1/s (exponential form only)
  double ramp_time = 0.0;                               // s; 0 selects the exponential form

  double operator()(double t) const;
};

// Force–length curve (thesis 3.28), r = λ/λopt: 0 for r < 0.4, 9(r-0.4)² on [0.4, 0.6),
// 1 - 4(1-r)² on [0.6, 1.4), 9(r-1.6)² on [1.4, 1.6), 0 for r >= 1.6 (SPEC §2; the Fortran's
// 1e-4 floor is not used). Returns f_λ and writes df_λ/dλ to *slope when slope != nullptr.
double force_length(double lambda, double lambda_opt, double* slope = nullptr);

enum class FvBranch { shortening, lengthening };

// Force–velocity value and its partial derivatives.
struct ForceVelocity {
  double f = 1.0;        // f_v
  double df_ddlm = 0.0;  // df_v / dΔλm
  double df_dkc = 0.0;   // df_v / dk_c
};

// Force–velocity function (thesis 3.29 with x = λ̇m/λ̇min = -Δλm/r, identical to 5.39 with
// x = Δλm/Δλm0 = Δλm/r), written on the CE stretch increment Δλm over the step and
// r = Δt·v_max > 0 (v_max = -λ̇min of chapter 3, λ̇m0 of chapter 5, 1/s). Multiplying numerator and
// denominator by r keeps it finite for any Δt > 0:
//   shortening  f_v = (r + Δλm) / (r - k_c Δλm)                        (Δλm <= 0)
//   lengthening f_v = d - (d - 1)(r - Δλm) / (r + k_c k_e Δλm)         (Δλm > 0)
// The branch is passed explicitly so that a lagged branch choice (Fortran) can be evaluated on the
// other side of Δλm = 0; each formula is continuous, equals 1 at Δλm = 0 and increases with Δλm.
ForceVelocity force_velocity(FvBranch branch, double delta_lambda_m, double r, double k_c,
                             double k_e, double d);

}  // namespace isomuscle::materials
