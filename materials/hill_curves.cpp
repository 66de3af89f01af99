#include "materials/hill_curves.hpp"

#include <algorithm>
#include <cmath>

namespace isomuscle::materials {

// Thesis 3.26–3.27 (ramp_time == 0) or the chapter-5 linear ramp (5.6, Figure 5.16); dimensionless.
double ActivationCurve::operator()(double t) const {
  if (t < t0)
    return n1;
  if (ramp_time > 0.0) {
    const auto rise = [&](double tau) {
      return n1 + (n2 - n1) * std::min(1.0, (tau - t0) / ramp_time);
    };
    if (t < t1)
      return rise(t);
    const double reached = rise(t1);
    return n1 + (reached - n1) * std::max(0.0, 1.0 - (t - t1) / ramp_time);
  }
  // h(ti, tb) = 1 - exp(-S (ti - tb)) (3.27).
  if (t < t1)
    return n1 + (n2 - n1) * -std::expm1(-rate * (t - t0));
  const double reached = (n2 - n1) * -std::expm1(-rate * (t1 - t0));
  // 3.26, third line: n1 + reached - reached h(t, t1) = n1 + reached exp(-S (t - t1)).
  return n1 + reached * std::exp(-rate * (t - t1));
}

// Thesis 3.28 (Blemker et al. 2005) with r = λ/λopt; dimensionless, slope in 1/(unit stretch).
double force_length(double lambda, double lambda_opt, double* slope) {
  const double r = lambda / lambda_opt;
  double f = 0.0, dfdr = 0.0;
  if (r >= 0.4 && r < 0.6) {
    f = 9.0 * (r - 0.4) * (r - 0.4);
    dfdr = 18.0 * (r - 0.4);
  } else if (r >= 0.6 && r < 1.4) {
    f = 1.0 - 4.0 * (1.0 - r) * (1.0 - r);
    dfdr = 8.0 * (1.0 - r);
  } else if (r >= 1.4 && r < 1.6) {
    f = 9.0 * (r - 1.6) * (r - 1.6);
    dfdr = 18.0 * (r - 1.6);
  }
  if (slope != nullptr)
    *slope = dfdr / lambda_opt;
  return f;
}

// Thesis 3.29 / 5.39 on stretch increments (see header); dimensionless.
ForceVelocity force_velocity(FvBranch branch, double dlm, double r, double k_c, double k_e,
                             double d) {
  ForceVelocity out;
  if (branch == FvBranch::shortening) {
    const double den = r - k_c * dlm;
    out.f = (r + dlm) / den;
    out.df_ddlm = r * (1.0 + k_c) / (den * den);
    out.df_dkc = (r + dlm) * dlm / (den * den);
  } else {
    const double kk = k_c * k_e;
    const double den = r + kk * dlm;
    out.f = d - (d - 1.0) * (r - dlm) / den;
    out.df_ddlm = (d - 1.0) * r * (1.0 + kk) / (den * den);
    out.df_dkc = (d - 1.0) * (r - dlm) * k_e * dlm / (den * den);
  }
  return out;
}

}  // namespace isomuscle::materials
