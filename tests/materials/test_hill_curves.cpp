// The scalar curves of the Hill contractile element against the thesis formulas written out
// independently: activation 3.26–3.27 and the chapter-5 ramp, force–length 3.28, force–velocity
// 3.29 (chapter 3, on λ̇m/λ̇min) and 5.39 (chapter 5, on Δλm/Δλm0), with their derivatives.
#include <gtest/gtest.h>

#include <cmath>

#include "materials/hill_curves.hpp"

namespace isomuscle::materials {
namespace {

TEST(ActivationCurve, ExponentialFormOfThesis326) {
  // Figure 3.9 / 3.20: t0 = 0.1 s, t1 = 0.4 s, n1 = 0, n2 = 1, S = 50 1/s.
  ActivationCurve f;
  f.t0 = 0.1;
  f.t1 = 0.4;
  f.rate = 50.0;
  EXPECT_EQ(f(0.0), 0.0);
  EXPECT_EQ(f(0.0999), 0.0);
  EXPECT_NEAR(f(0.2), 1.0 - std::exp(-5.0), 1e-15);
  const double at_t1 = 1.0 - std::exp(-15.0);
  EXPECT_NEAR(f(0.4 - 1e-12), at_t1, 1e-9);
  // After t1: n1 + h1 - h1 (1 - exp(-S (t - t1))) with h1 the value reached at t1.
  EXPECT_NEAR(f(0.45), at_t1 - at_t1 * (1.0 - std::exp(-2.5)), 1e-15);
  EXPECT_NEAR(f(0.4), at_t1, 1e-15);  // continuous at t1
  // Levels other than 0 and 1.
  f.n1 = 0.2;
  f.n2 = 0.7;
  EXPECT_EQ(f(0.05), 0.2);
  EXPECT_NEAR(f(0.2), 0.2 + 0.5 * (1.0 - std::exp(-5.0)), 1e-15);
  EXPECT_NEAR(f(10.0), 0.2, 1e-12);
}

TEST(ActivationCurve, RampFormOfChapter5) {
  // 5.6: from t = 0, full after 0.005 s, held.
  ActivationCurve f;
  f.ramp_time = 0.005;
  EXPECT_EQ(f(-1e-3), 0.0);
  EXPECT_NEAR(f(0.0025), 0.5, 1e-14);
  EXPECT_EQ(f(0.005), 1.0);
  EXPECT_EQ(f(0.2), 1.0);
  // With a deactivation time the level falls linearly back to n1 over ramp_time.
  f.t1 = 0.1;
  EXPECT_EQ(f(0.1), 1.0);
  EXPECT_NEAR(f(0.1025), 0.5, 1e-12);
  EXPECT_EQ(f(0.2), 0.0);
  // Deactivated during the rise: decays from the level reached.
  f.t1 = 0.002;
  EXPECT_NEAR(f(0.002), 0.4, 1e-14);
  EXPECT_NEAR(f(0.0045), 0.2, 1e-12);
}

TEST(ForceLength, PiecewiseQuadraticOfThesis328) {
  const double lopt = 1.05;
  EXPECT_EQ(force_length(0.39 * lopt, lopt), 0.0);
  EXPECT_NEAR(force_length(0.5 * lopt, lopt), 9.0 * 0.01, 1e-14);
  EXPECT_NEAR(force_length(lopt, lopt), 1.0, 1e-15);
  EXPECT_NEAR(force_length(1.0, lopt), 1.0 - 4.0 * std::pow(1.0 - 1.0 / lopt, 2), 1e-15);
  EXPECT_NEAR(force_length(1.5 * lopt, lopt), 9.0 * 0.01, 1e-14);
  EXPECT_EQ(force_length(1.61 * lopt, lopt), 0.0);
  // Continuous at the joints r = 0.4, 0.6, 1.4, 1.6.
  for (double r : {0.4, 0.6, 1.4, 1.6}) {
    EXPECT_NEAR(force_length((r - 1e-12) * lopt, lopt), force_length((r + 1e-12) * lopt, lopt),
                1e-10)
        << r;
  }
  // Slope against central differences away from the joints.
  for (double r : {0.45, 0.55, 0.8, 1.0, 1.2, 1.45, 1.55}) {
    double slope = 0.0;
    force_length(r * lopt, lopt, &slope);
    const double h = 1e-6;
    const double fd =
        (force_length(r * lopt + h, lopt) - force_length(r * lopt - h, lopt)) / (2 * h);
    EXPECT_NEAR(slope, fd, 1e-7) << r;
  }
}

// Chapter-3 form (3.29) with λ̇m = Δλm/Δt and λ̇min < 0.
double fv_thesis_329(double lambda_dot_m, double lambda_dot_min, double kc, double ke, double d) {
  const double x = lambda_dot_m / lambda_dot_min;
  if (lambda_dot_m <= 0.0)
    return (1.0 - x) / (1.0 + kc * x);
  return d - (d - 1.0) * (1.0 + x) / (1.0 - kc * ke * x);
}

// Chapter-5 form (5.39) with Δλm0 = λ̇m0 Δt.
double fv_thesis_539(double dlm, double dlm0, double kc, double ke, double d) {
  const double x = dlm / dlm0;
  if (dlm <= 0.0)
    return (1.0 + x) / (1.0 - kc * x);
  return d - (d - 1.0) * (1.0 - x) / (1.0 + kc * ke * x);
}

TEST(ForceVelocity, MatchesThesis329And539WithDerivatives) {
  const double dt = 1e-3, kc = 5.0, ke = 5.0, d = 1.5, vmax = 17.0, r = dt * vmax;
  for (double dlm : {-0.05, -0.017, -0.004, -1e-5, 0.0, 1e-5, 0.004, 0.02, 0.3}) {
    const FvBranch branch = dlm <= 0.0 ? FvBranch::shortening : FvBranch::lengthening;
    const ForceVelocity fv = force_velocity(branch, dlm, r, kc, ke, d);
    EXPECT_NEAR(fv.f, fv_thesis_329(dlm / dt, -vmax, kc, ke, d), 1e-13) << dlm;
    EXPECT_NEAR(fv.f, fv_thesis_539(dlm, r, kc, ke, d), 1e-13) << dlm;
    const double h = 1e-8;
    const double fd_dlm = (force_velocity(branch, dlm + h, r, kc, ke, d).f -
                           force_velocity(branch, dlm - h, r, kc, ke, d).f) /
                          (2 * h);
    EXPECT_NEAR(fv.df_ddlm, fd_dlm, 1e-6 * std::abs(fd_dlm) + 1e-8) << dlm;
    const double fd_kc = (force_velocity(branch, dlm, r, kc + 1e-6, ke, d).f -
                          force_velocity(branch, dlm, r, kc - 1e-6, ke, d).f) /
                         2e-6;
    EXPECT_NEAR(fv.df_dkc, fd_kc, 1e-7) << dlm;
  }
  // Isometric: 1 on both branches; shortening at the maximal rate: 0; fast lengthening tends to
  // d + (d - 1)/(k_c k_e).
  EXPECT_DOUBLE_EQ(force_velocity(FvBranch::shortening, 0.0, r, kc, ke, d).f, 1.0);
  EXPECT_DOUBLE_EQ(force_velocity(FvBranch::lengthening, 0.0, r, kc, ke, d).f, 1.0);
  EXPECT_NEAR(force_velocity(FvBranch::shortening, -r, r, kc, ke, d).f, 0.0, 1e-15);
  EXPECT_NEAR(force_velocity(FvBranch::lengthening, 1e6 * r, r, kc, ke, d).f,
              d + (d - 1.0) / (kc * ke), 1e-6);
  // Finite for a vanishing step (r -> 0): no division of two overflowed numbers.
  const ForceVelocity tiny = force_velocity(FvBranch::shortening, -1e-3, 1e-300, kc, ke, d);
  EXPECT_TRUE(std::isfinite(tiny.f) && std::isfinite(tiny.df_ddlm) && std::isfinite(tiny.df_dkc));
}

}  // namespace
}  // namespace isomuscle::materials
