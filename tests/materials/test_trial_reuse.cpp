// A second evaluation at the state that the trial history already holds
// (PointInput::trial_is_current, what Newton's tangent pass after its line search asks for): the
// Hill laws read σ_SEE and dσ_SEE/dλ̄f from the trial history instead of solving the step again,
// and must give the very numbers of a fresh evaluation, for every reading of the fibre update
// (consistent and frozen-CE tangent, explicit lag, fixed substeps, Δt = 0, inactive), and leave
// the trial history as it is.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "material_test_support.hpp"
#include "materials/hill_curves.hpp"
#include "materials/hill_fibre.hpp"
#include "materials/hill_muscle.hpp"
#include "materials/material_factory.hpp"

namespace isomuscle::materials {
namespace {

struct Variant {
  std::string model;
  std::map<std::string, double> params;
  double time = 0.3;  // both laws' default activation is full here
  double dt = 1e-3;
};

std::vector<Variant> variants() {
  std::vector<Variant> out;
  for (const std::string model : {"lu2010", "tang2009"}) {
    out.push_back({model, {}});
    out.push_back({model, {{"frozen_ce_tangent", 1.0}}});
    out.push_back({model, {{"explicit_lag", 1.0}}});
    out.push_back({model, {{"substeps", 7.0}}});
    out.push_back({model, {}, 0.3, 0.0});
    out.push_back({model, {}, 0.0, 1e-3});   // inactive over the whole step
    out.push_back({model, {}, 2e-3, 2e-3});  // the activation ramp: many substeps
  }
  return out;
}

// A committed history some way from equilibrium with the stretch lf: the SEE at the isometric
// stress of the stretch 2 % lower, the CE shortening, the last step's rates nonzero.
std::vector<double> committed_history(const HillFibreParameters& p, double lf, double time) {
  std::vector<double> h(kHillHistorySize, 0.0);
  const double s = p.sigma0 * std::max(p.activation(time), 0.2) * force_length(lf, p.lambda_opt);
  h[kLambdaS] = 1.0 + std::log1p(s / p.beta) / p.alpha;
  h[kLambdaF] = 0.98 * lf;
  h[kLambdaM] = (1.0 + p.k) * h[kLambdaF] - p.k * h[kLambdaS];
  h[kDeltaLambdaM] = -2e-3;
  h[kSeeRate] = 0.5;
  h[kFibreRate] = -1.5;
  return h;
}

TEST(TrialReuse, SecondEvaluationAtTheTrialStateGivesTheSameNumbersWithoutASolve) {
  std::mt19937 rng(36);
  int reused = 0, active = 0;
  for (const Variant& v : variants()) {
    const auto owner = make_material(v.model, v.params);
    const auto& law = dynamic_cast<const HillMuscle&>(*owner);
    for (int i = 0; i < 40; ++i) {
      PointInput in;
      in.F = testing::random_F(rng, 0.8, 1.25);
      in.fibre = testing::random_unit(rng);
      in.time = v.time;
      in.dt = v.dt;
      const double lf = std::pow(in.F.determinant(), -1.0 / 3.0) * (in.F * in.fibre).norm();
      const std::vector<double> committed = committed_history(law.parameters().fibre, lf, v.time);
      in.history = committed;
      for (const testing::Part part : {testing::Part::full, testing::Part::isochoric}) {
        // The residual pass writes the trial history (no tangent asked for) ...
        std::vector<double> trial(kHillHistorySize, -1.0);
        PointResult residual_pass;
        residual_pass.history = trial;
        const PointStatus first = part == testing::Part::full
                                      ? law.evaluate(in, residual_pass, false)
                                      : law.evaluate_isochoric(in, residual_pass, false);
        ASSERT_EQ(first, PointStatus::ok) << v.model << " case " << i;
        const std::vector<double> written = trial;
        // ... the tangent pass reads it, and does not solve the step again: given a committed
        // history that the update rejects (NaN), it still succeeds ...
        const std::vector<double> unusable(kHillHistorySize, std::nan(""));
        PointInput again = in;
        again.history = unusable;
        again.trial_is_current = true;
        PointResult tangent_pass;
        tangent_pass.history = trial;
        const PointStatus second = part == testing::Part::full
                                       ? law.evaluate(again, tangent_pass, true)
                                       : law.evaluate_isochoric(again, tangent_pass, true);
        ASSERT_EQ(second, PointStatus::ok);
        // ... and gives what a fresh evaluation with the tangent gives, to the last bit.
        const testing::Evaluation fresh = testing::evaluate(law, in, part, true);
        ASSERT_EQ(fresh.status, PointStatus::ok);
        EXPECT_EQ(tangent_pass.S, fresh.S) << v.model << " case " << i;
        EXPECT_EQ(tangent_pass.tangent, fresh.tangent) << v.model << " case " << i;
        EXPECT_EQ(residual_pass.S, fresh.S);
        EXPECT_EQ(trial, written) << "the reading pass changed the trial history";
        EXPECT_EQ(trial, fresh.trial) << "the residual pass wrote another history";
        ++reused;
        active += trial[kSeeStress] != 0.0 ? 1 : 0;
      }
    }
  }
  // Most cases have an active fibre (all but the inactive variant's), so the stored stress and
  // slope matter in them.
  EXPECT_GT(active, reused / 2);
}

// The stored slope is the update's own dσ_SEE/dλ̄f: a central difference of the stored σ_SEE in
// λ̄f confirms it, so a reading pass assembles the consistent tangent.
TEST(TrialReuse, StoredSlopeIsTheDerivativeOfTheStoredStress) {
  for (const std::string model : {"lu2010", "tang2009"}) {
    const auto owner = make_material(model);
    const HillFibre& fibre = dynamic_cast<const HillMuscle&>(*owner).fibre();
    for (const double lf : {0.9, 1.0, 1.08}) {
      const std::vector<double> committed = committed_history(fibre.parameters(), lf, 0.3);
      std::vector<double> trial(kHillHistorySize), plus(kHillHistorySize), minus(kHillHistorySize);
      const double h = 1e-7;
      ASSERT_TRUE(fibre.update(lf, 0.3, 1e-3, committed, trial).ok);
      ASSERT_TRUE(fibre.update(lf + h, 0.3, 1e-3, committed, plus).ok);
      ASSERT_TRUE(fibre.update(lf - h, 0.3, 1e-3, committed, minus).ok);
      const double fd = (plus[kSeeStress] - minus[kSeeStress]) / (2.0 * h);
      EXPECT_NEAR(trial[kSeeStiffness], fd, 1e-6 * std::abs(fd)) << model << " lf " << lf;
      EXPECT_NEAR(trial[kSeeStress], fibre.series_stress(trial),
                  1e-12 * std::abs(trial[kSeeStress]))
          << model << " lf " << lf;
      const FibreResponse read = fibre.response_of_trial(lf, trial);
      EXPECT_TRUE(read.ok);
      EXPECT_EQ(read.sigma_see, trial[kSeeStress]);
      EXPECT_EQ(read.dsigma_see, trial[kSeeStiffness]);
    }
  }
}

}  // namespace
}  // namespace isomuscle::materials
