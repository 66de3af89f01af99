// Material-point states of the Hill muscle laws: no stress at F = I when passive; isometric
// contraction (thesis 3.5.3, 3.44) with F = I held, where matrix, PE and volumetric parts vanish
// and σ_SEE = σ_CE = σ0 f_t f_λ(1) f_v exactly; the inactive CE sliding freely so that a passive
// pre-stretch is not seen as CE velocity at activation (SPEC §2).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "material_test_support.hpp"
#include "materials/hill_curves.hpp"
#include "materials/hill_fibre.hpp"
#include "materials/hill_muscle.hpp"
#include "materials/material_factory.hpp"

namespace isomuscle::materials {
namespace {

TEST(MaterialStates, NoStressAtIdentityWhenPassive) {
  std::mt19937 rng(1);
  for (const std::string& model : material_models()) {
    const auto law = make_material(model);
    std::vector<double> history(static_cast<std::size_t>(law->history_size()));
    law->initial_history(history);
    PointInput in;
    in.fibre = testing::random_unit(rng);
    in.time = 0.0;  // f_t(0) = 0 for both muscle laws' default activation
    in.dt = 1e-3;
    in.history = history;
    const testing::Evaluation e = testing::evaluate(*law, in);
    ASSERT_EQ(e.status, PointStatus::ok) << model;
    EXPECT_LE(e.S.norm(), 1e-12 * law->shear_modulus()) << model << "\n" << e.S;
    for (std::size_t i = 0; i < history.size(); ++i)
      EXPECT_NEAR(e.trial[i], history[i], 1e-14) << model;
    // Positive definite tangent at rest.
    Eigen::SelfAdjointEigenSolver<Matrix6d> es(e.tangent);
    EXPECT_GT(es.eigenvalues().minCoeff(), 0.0) << model;
  }
}

// Chapter-3 force–velocity 3.29 on λ̇m = Δλm/Δt.
double fv_329(double lambda_dot_m, double lambda_dot_min, double kc, double ke, double d) {
  const double x = lambda_dot_m / lambda_dot_min;
  if (lambda_dot_m <= 0.0)
    return (1.0 - x) / (1.0 + kc * x);
  return d - (d - 1.0) * (1.0 + x) / (1.0 - kc * ke * x);
}

// Chapter-5 force–velocity 5.39 on Δλm/Δλm0.
double fv_539(double dlm, double dlm0, double kc, double ke, double d) {
  const double x = dlm / dlm0;
  if (dlm <= 0.0)
    return (1.0 + x) / (1.0 - kc * x);
  return d - (d - 1.0) * (1.0 - x) / (1.0 + kc * ke * x);
}

// Thesis 3.5.3: n1 = 0, n2 = 1, t0 = 0.1 s, t1 = 0.4 s, F = I held, fibres along z. One
// backward-Euler step per time step (substeps = 1), so that σ_SEE = s f_v(Δλm/Δt) holds over the
// step.
void isometric_contraction(const std::string& model, const std::map<std::string, double>& params) {
  const auto owner = make_material(model, params);
  const auto& law = dynamic_cast<const HillMuscle&>(*owner);
  const HillFibreParameters& p = law.parameters().fibre;
  const double fl1 = force_length(1.0, p.lambda_opt);
  const double dt = 1e-3;
  std::vector<double> committed(kHillHistorySize), trial(kHillHistorySize);
  law.initial_history(committed);
  std::vector<Eigen::Matrix3d> parts(4);
  double worst_relation = 0.0, worst_shape = 0.0;
  for (int step = 1; step <= 800; ++step) {
    PointInput in;
    in.fibre = Eigen::Vector3d::UnitZ();
    in.time = step * dt;
    in.dt = dt;
    in.history = committed;
    PointResult out;
    out.history = trial;
    ASSERT_EQ(law.evaluate(in, out), PointStatus::ok) << in.time;
    law.cauchy_parts(in, trial, parts);
    const double see = law.fibre().series_stress(trial);
    const double s = p.sigma0 * law.activation(in.time) * fl1;
    const double dlm = trial[kDeltaLambdaM];
    // Geometry D.7 at λ̄f = 1: λm + k λs = 1 + k.
    EXPECT_NEAR(trial[kLambdaM] + p.k * trial[kLambdaS], 1.0 + p.k, 1e-12);
    // Matrix, PE and volumetric parts vanish; the CE part is σ_SEE (n⊗n - I/3) (5.41).
    EXPECT_EQ(parts[1].norm(), 0.0);
    EXPECT_EQ(parts[2].norm(), 0.0);
    EXPECT_EQ(parts[3].norm(), 0.0);
    EXPECT_NEAR(parts[0](2, 2), 2.0 / 3.0 * see, 1e-9 * p.sigma0);
    EXPECT_NEAR(parts[0](0, 0), -1.0 / 3.0 * see, 1e-9 * p.sigma0);
    // σ33 = σ_CE33 + σ_VOL33 + σ_I33 + σ_PE33 (3.44) and the total equals F S F^T / J = S here.
    EXPECT_NEAR(parts[0](2, 2) + parts[1](2, 2) + parts[2](2, 2) + parts[3](2, 2), out.S(2, 2),
                1e-9 * p.sigma0);
    // σ_SEE = σ_CE = σ0 f_t f_λ(1) f_v (3.24–3.25), f_v from the thesis formula.
    double fv = 1.0;
    if (model == "lu2010") {
      fv = fv_329(dlm / dt, -p.v_max, p.k_c, p.k_e, p.d);
    } else {
      fv = fv_539(dlm, p.v_max * dt, p.sigma0 * fl1 / p.a_v, p.k_e, p.d);
    }
    if (s == 0.0) {
      EXPECT_EQ(see, 0.0);
      EXPECT_EQ(trial[kLambdaS], 1.0);
    } else {
      worst_relation = std::max(worst_relation, std::abs(see - s * fv) / p.sigma0);
      EXPECT_NEAR(see, s * fv, 1e-9 * p.sigma0) << in.time;
      // Activation rising: the CE shortens as the SEE stretches; falling: it lengthens.
      const double next = law.activation(in.time + dt);
      if (next > law.activation(in.time) && in.time < 0.4) {
        EXPECT_LT(dlm, 0.0) << in.time;
        EXPECT_LE(see, s) << in.time;
      }
      if (in.time > 0.4 + dt) {
        EXPECT_GT(dlm, 0.0) << in.time;
        EXPECT_GE(see, s) << in.time;
      }
    }
    worst_shape = std::max(worst_shape, std::abs(see - s) / p.sigma0);
    // Full activation reached: σ_SEE -> σ0 f_λ(1).
    if (step == 400) {
      EXPECT_NEAR(see / (p.sigma0 * fl1), 1.0, 1e-3);
    }
    committed = trial;
  }
  EXPECT_LT(law.fibre().series_stress(committed), 1e-3 * p.sigma0);  // deactivated at 0.8 s
  std::cout << "[measured] " << model
            << " isometric: max |σ_SEE - σ0 f_t f_λ f_v|/σ0 = " << worst_relation
            << ", max |σ_SEE - σ0 f_t f_λ|/σ0 = " << worst_shape << "\n";
}

TEST(MaterialStates, IsometricContractionLu2010) {
  isometric_contraction("lu2010", {{"t0", 0.1}, {"t1", 0.4}, {"substeps", 1.0}});
}

TEST(MaterialStates, IsometricContractionTang2009) {
  isometric_contraction("tang2009",
                        {{"t0", 0.1}, {"t1", 0.4}, {"ramp_time", 0.0}, {"substeps", 1.0}});
}

// Passive stretch to λ = 1.1 along the fibre before t0, then activation: the CE slid with the
// fibre while inactive, so the first active step sees no CE velocity from the pre-stretch
// (α1 = 0), unlike the Fortran, which would see Δλm = (1 + k) 0.1 in one step and lengthen.
TEST(MaterialStates, InactiveContractileElementSlidesFreely) {
  const auto owner = make_material("lu2010", {{"t0", 0.2}});
  const auto& law = dynamic_cast<const HillMuscle&>(*owner);
  const HillFibreParameters& p = law.parameters().fibre;
  std::vector<double> committed(kHillHistorySize), trial(kHillHistorySize);
  law.initial_history(committed);
  const double dt = 1e-3;
  for (int step = 1; step <= 300; ++step) {
    const double t = step * dt;
    const double lambda = 1.0 + 0.1 * std::min(1.0, t / 0.1);
    PointInput in;
    in.F = Eigen::Vector3d(1.0 / std::sqrt(lambda), 1.0 / std::sqrt(lambda), lambda).asDiagonal();
    in.time = t;
    in.dt = dt;
    in.history = committed;
    PointResult out;
    out.history = trial;
    ASSERT_EQ(law.evaluate(in, out), PointStatus::ok);
    if (t <= 0.2) {
      EXPECT_EQ(trial[kLambdaS], 1.0);
      EXPECT_NEAR(trial[kLambdaM], (1.0 + p.k) * lambda - p.k, 1e-12);
      EXPECT_EQ(law.fibre().series_stress(trial), 0.0);
    } else if (step == 201) {
      // α1 = 0: Δλm = -k Δλs, the CE shortens as the SEE takes up the new force.
      EXPECT_NEAR(trial[kDeltaLambdaM], -p.k * (trial[kLambdaS] - committed[kLambdaS]), 1e-14);
      EXPECT_LT(trial[kDeltaLambdaM], 0.0);
    }
    committed = trial;
  }
  EXPECT_GT(law.fibre().series_stress(committed), 0.5 * p.sigma0);
}

// Sub-stepping (hill_fibre.hpp): m substeps of a step are m single steps of dt/m with λ̄f
// interpolated linearly from the committed λ̄f and f_t at each substep's end. The adaptive m
// depends on the committed state only: 1 for a passive point and at isometric equilibrium (the
// bound rule: the state already at the SEE stress of t + dt), more at the activation front, and
// the adaptive result is that of substeps = m.
TEST(MaterialStates, SubstepsAreRepeatedSingleSteps) {
  for (const std::string model : {"lu2010", "tang2009"}) {
    const std::map<std::string, double> base = {
        {"t0", 0.1}, {"ramp_time", 0.0}, {"substep_rule", 1.0}};
    const auto adaptive = make_material(model, base);
    auto single_params = base, fixed_params = base;
    single_params["substeps"] = 1.0;
    const auto single = make_material(model, single_params);
    const auto& law = dynamic_cast<const HillMuscle&>(*adaptive);
    const HillFibreParameters& p = law.parameters().fibre;
    const double dt = 1e-3, time = 0.11;
    const double lf0 = 1.02, lf = 1.015;  // shortening fibre, J = 1, fibre along z
    const auto input = [&](double lambda, double t, double h, std::span<const double> history) {
      PointInput in;
      in.F = Eigen::Vector3d(1.0 / std::sqrt(lambda), 1.0 / std::sqrt(lambda), lambda).asDiagonal();
      in.fibre = Eigen::Vector3d::UnitZ();
      in.time = t;
      in.dt = h;
      in.history = history;
      return in;
    };
    // The CE at rest with σ_SEE = 0 (the fibre has just been activated).
    std::vector<double> committed = {1.0, (1.0 + p.k) * lf0 - p.k, 0.0, lf0, 0.0, 0.0, 0.0, 0.0};
    const int m = law.fibre().substep_count(committed, time, dt);
    EXPECT_GT(m, 4) << model;
    EXPECT_EQ(law.fibre().substep_count(committed, 0.05, dt), 1) << model << ": passive";
    EXPECT_EQ(law.fibre().substep_count(committed, time, 0.0), 1) << model << ": dt = 0";
    std::vector<double> equilibrium = committed;
    const double s = p.sigma0 * law.activation(time) * force_length(lf0, p.lambda_opt);
    equilibrium[kLambdaS] = 1.0 + std::log1p(s / p.beta) / p.alpha;
    EXPECT_EQ(law.fibre().substep_count(equilibrium, time, dt), 1) << model << ": equilibrium";

    fixed_params["substeps"] = m;
    const auto fixed = make_material(model, fixed_params);
    std::vector<double> trial_a(kHillHistorySize), trial_f(kHillHistorySize);
    PointResult out_a, out_f;
    out_a.history = trial_a;
    out_f.history = trial_f;
    ASSERT_EQ(law.evaluate(input(lf, time, dt, committed), out_a), PointStatus::ok);
    ASSERT_EQ(fixed->evaluate(input(lf, time, dt, committed), out_f), PointStatus::ok);
    EXPECT_EQ(trial_a, trial_f) << model;
    EXPECT_EQ(out_a.S, out_f.S) << model;

    std::vector<double> state = committed, next(kHillHistorySize);
    PointResult out;
    out.history = next;
    for (int j = 1; j <= m; ++j) {
      const double w = static_cast<double>(j) / m;
      const double lambda = j == m ? lf : lf0 + w * (lf - lf0);
      const double t = j == m ? time : time - dt + w * dt;
      ASSERT_EQ(single->evaluate(input(lambda, t, dt / m, state), out), PointStatus::ok);
      state = next;
    }
    for (int i : {kLambdaS, kLambdaM, kLambdaF})
      EXPECT_NEAR(trial_a[i], state[i], 1e-12) << model << " entry " << i;
    // The step's Δλm is the sum over the substeps.
    EXPECT_NEAR(trial_a[kDeltaLambdaM], state[kLambdaM] - committed[kLambdaM], 1e-12) << model;
    EXPECT_LT((out_a.S - out.S).norm(), 1e-9 * p.sigma0) << model;
    EXPECT_LT(trial_a[kDeltaLambdaM], 0.0) << model << ": the CE shortens";
  }
}

// The estimate rule (the default, hill_fibre.hpp) against the bound: at the activation front (the
// SEE at zero, the CE free to shorten at v_max) both ask for the bound; in a steady free
// contraction (the SEE stress at the force-velocity value of a fibre that shortens with the CE,
// the last step's rates stored) the estimate asks for a few substeps where the bound asks for
// many; a change of the activation level adds the SEE stretch that follows it.
TEST(MaterialStates, SubstepEstimateFollowsTheStateTheBoundDoesNot) {
  const auto estimate = make_material("tang2009", {{"t0", 0.0}});
  const auto bound = make_material("tang2009", {{"t0", 0.0}, {"substep_rule", 1.0}});
  const HillFibre& fe = dynamic_cast<const HillMuscle&>(*estimate).fibre();
  const HillFibre& fb = dynamic_cast<const HillMuscle&>(*bound).fibre();
  const HillFibreParameters& p = fe.parameters();
  const double dt = 0.01, time = 0.1, lf = 0.9;
  // Front: σ_SEE = 0 at full activation.
  const std::vector<double> front = {1.0, (1.0 + p.k) * lf - p.k, 0.0, lf, 0.0, 0.0, 0.0, 0.0};
  EXPECT_EQ(fe.substep_count(front, time, dt), fb.substep_count(front, time, dt));
  EXPECT_GT(fb.substep_count(front, time, dt), 20);
  // Steady shortening: the CE shortens at half its maximal rate and the fibre with it, so that the
  // SEE stays as it is ((1 + k) λ̄f' = λm', D.8), σ_SEE = s f_v(-1/2).
  const double fl = force_length(lf, p.lambda_opt);
  const double s = p.sigma0 * fl;
  const double k_c = p.sigma0 * fl / p.a_v;
  const double y = -0.5;  // Δλm / (Δt v_max)
  const double fv = (1.0 + y) / (1.0 - k_c * y);
  const double ls = 1.0 + std::log1p(s * fv / p.beta) / p.alpha;
  const double lm_rate = y * p.v_max;
  const std::vector<double> steady = {ls,  (1.0 + p.k) * lf - p.k * ls, lm_rate * dt, lf,
                                      0.0, lm_rate / (1.0 + p.k)};
  const int m_estimate = fe.substep_count(steady, time, dt);
  const int m_bound = fb.substep_count(steady, time, dt);
  std::printf("[ measured ] steady shortening at dt = %g s: %d substeps (estimate), %d (bound)\n",
              dt, m_estimate, m_bound);
  EXPECT_LE(m_estimate, 2);
  EXPECT_GE(m_bound, 32);
  // A change of the activation level (a slow linear ramp, 5 % -> 6 % over the step) with the SEE
  // at the isometric stress of the level at t: the SEE stretch ln(f_t(t + dt)/f_t(t)) / α that
  // follows it.
  const auto ramp = make_material("tang2009", {{"t0", 0.0}, {"ramp_time", 0.1}});
  const HillFibre& fr = dynamic_cast<const HillMuscle&>(*ramp).fibre();
  const double ft_before = ramp->activation(0.005), ft_now = ramp->activation(0.006);
  const double ls_iso = 1.0 + std::log1p(p.sigma0 * ft_before * fl / p.beta) / p.alpha;
  const std::vector<double> iso = {ls_iso, (1.0 + p.k) * lf - p.k * ls_iso, 0.0, lf, 0.0, 0.0, 0.0,
                                   0.0};
  const double rise = std::log(ft_now / ft_before) / p.alpha;
  EXPECT_EQ(fr.substep_count(iso, 0.006, 0.001),
            static_cast<int>(std::ceil(p.alpha * rise / p.substep_see_strain)));
}

TEST(MaterialStates, SubstepsParameterMustBeAWholeNumber) {
  EXPECT_THROW(make_material("lu2010", {{"substeps", 2.5}}), std::invalid_argument);
  EXPECT_THROW(make_material("tang2009", {{"substeps", -1.0}}), std::invalid_argument);
  EXPECT_NO_THROW(make_material("tang2009", {{"substeps", 8.0}}));
}

}  // namespace
}  // namespace isomuscle::materials
