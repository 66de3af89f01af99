// Frame invariance (F -> QF leaves S and the history unchanged and rotates every Cauchy part),
// the Cauchy parts summing to F S F^T / J, the volumetric split used by the mixed formulation
// (S = S_iso + J U'(J) C^-1 and likewise for the tangent, U' and U'' against differences of U),
// and compute_tangent = false skipping the tangent.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "material_test_support.hpp"
#include "materials/hill_curves.hpp"
#include "materials/hill_fibre.hpp"
#include "materials/hill_muscle.hpp"
#include "materials/material_factory.hpp"

namespace isomuscle::materials {
namespace {

struct Case {
  std::unique_ptr<MaterialLaw> law;
  PointInput in;
  std::vector<double> history;
};

// Every law, the muscle laws in an active state (isometric equilibrium, fibre being stretched).
std::vector<Case> cases(std::mt19937& rng) {
  std::vector<Case> out;
  for (const std::string& model : material_models()) {
    for (int i = 0; i < 5; ++i) {
      Case c;
      c.law = make_material(model);
      c.in.F = testing::random_F(rng, 0.85, 1.15);
      c.in.fibre = testing::random_unit(rng);
      c.in.time = 0.3;
      c.in.dt = 1e-3;
      c.history.assign(static_cast<std::size_t>(c.law->history_size()), 0.0);
      if (const auto* hill = dynamic_cast<const HillMuscle*>(c.law.get())) {
        const HillFibreParameters& p = hill->parameters().fibre;
        const double lf = std::pow(c.in.F.determinant(), -1.0 / 3.0) * (c.in.F * c.in.fibre).norm();
        const double s = p.sigma0 * hill->activation(c.in.time) * force_length(lf, p.lambda_opt);
        c.history[kLambdaS] = 1.0 + std::log1p(s / p.beta) / p.alpha;
        c.history[kLambdaM] = (1.0 + p.k) * (lf - 1e-3) - p.k * c.history[kLambdaS];
        c.history[kDeltaLambdaM] = 1e-3;
        c.history[kLambdaF] = lf - 1e-3;
      }
      out.push_back(std::move(c));
    }
  }
  return out;
}

std::vector<Eigen::Matrix3d> parts_of(const MaterialLaw& law, const PointInput& in,
                                      const std::vector<double>& trial) {
  std::vector<Eigen::Matrix3d> parts(law.cauchy_part_names().size());
  law.cauchy_parts(in, trial, parts);
  return parts;
}

TEST(MaterialObjectivity, RotationLeavesSAndRotatesCauchyParts) {
  std::mt19937 rng(21);
  for (Case& c : cases(rng)) {
    c.in.history = c.history;
    const testing::Evaluation a = testing::evaluate(*c.law, c.in);
    ASSERT_EQ(a.status, PointStatus::ok) << c.law->name();
    PointInput rotated = c.in;
    const Eigen::Matrix3d Q = testing::random_rotation(rng);
    rotated.F = Q * c.in.F;
    const testing::Evaluation b = testing::evaluate(*c.law, rotated);
    ASSERT_EQ(b.status, PointStatus::ok);
    EXPECT_LT((b.S - a.S).norm(), 1e-12 * a.S.norm()) << c.law->name();
    EXPECT_LT((b.tangent - a.tangent).norm(), 1e-12 * a.tangent.norm()) << c.law->name();
    // Stretches agree to round-off; the last step's rates (Hill laws' see_rate, fibre_rate:
    // increments / dt) carry that round-off divided by dt, and the stored stress and its slope
    // (see_stress, see_stiffness, Pa) agree to round-off relative to their size.
    const std::vector<std::string> names = c.law->history_names();
    for (std::size_t i = 0; i < a.trial.size(); ++i) {
      const bool rate = names[i].size() > 5 && names[i].ends_with("_rate");
      const bool stress = names[i].starts_with("see_s");
      EXPECT_NEAR(b.trial[i], a.trial[i],
                  rate     ? 1e-13 / c.in.dt
                  : stress ? 1e-12 * std::abs(a.trial[i])
                           : 1e-13)
          << c.law->name() << " " << names[i];
    }
    const std::vector<Eigen::Matrix3d> pa = parts_of(*c.law, c.in, a.trial);
    const std::vector<Eigen::Matrix3d> pb = parts_of(*c.law, rotated, b.trial);
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < pa.size(); ++i) {
      const Eigen::Matrix3d expected = Q * pa[i] * Q.transpose();
      EXPECT_LE((pb[i] - expected).norm(), 1e-12 * (pa[i].norm() + a.S.norm()))
          << c.law->name() << " part " << c.law->cauchy_part_names()[i];
      sum += pa[i];
    }
    const double J = c.in.F.determinant();
    const Eigen::Matrix3d sigma = c.in.F * a.S * c.in.F.transpose() / J;
    EXPECT_LT((sum - sigma).norm(), 1e-11 * sigma.norm()) << c.law->name();
  }
}

// S_vol(C) = J U'(J) C^-1 from the law's volumetric(J), for finite differences.
Eigen::Matrix3d volumetric_stress(const MaterialLaw& law, const Eigen::Matrix3d& F) {
  const Eigen::Matrix3d C = F.transpose() * F;
  const double J = F.determinant();
  return J * law.volumetric(J)(1) * C.inverse();
}

TEST(MaterialSplit, FullEqualsIsochoricPlusVolumetric) {
  std::mt19937 rng(5);
  for (Case& c : cases(rng)) {
    const MaterialLaw& law = *c.law;
    ASSERT_TRUE(law.has_volumetric_split()) << law.name();
    c.in.history = c.history;
    const testing::Evaluation full = testing::evaluate(law, c.in, testing::Part::full);
    const testing::Evaluation iso = testing::evaluate(law, c.in, testing::Part::isochoric);
    ASSERT_EQ(full.status, PointStatus::ok);
    ASSERT_EQ(iso.status, PointStatus::ok);
    EXPECT_EQ(full.trial, iso.trial) << law.name();
    const Eigen::Matrix3d S_vol = volumetric_stress(law, c.in.F);
    EXPECT_LE((full.S - iso.S - S_vol).norm(), 1e-12 * full.S.norm()) << law.name();
    // Tangent difference = dS_vol/dE by central differences (C +- 2h dE, F = sqrt(C)).
    const Eigen::Matrix3d C = c.in.F.transpose() * c.in.F;
    Matrix6d fd;
    constexpr int I[6] = {0, 1, 2, 0, 1, 0};
    constexpr int J[6] = {0, 1, 2, 1, 2, 2};
    const double h = 1e-6;
    for (int j = 0; j < 6; ++j) {
      Eigen::Matrix3d dC = Eigen::Matrix3d::Zero();
      dC(I[j], J[j]) += h;
      dC(J[j], I[j]) += h;
      const Eigen::Matrix3d Sp = volumetric_stress(law, testing::sqrt_spd(C + dC));
      const Eigen::Matrix3d Sm = volumetric_stress(law, testing::sqrt_spd(C - dC));
      fd.col(j) = (to_voigt_stress(Sp) - to_voigt_stress(Sm)) / (2.0 * h);
    }
    EXPECT_LT(testing::relative_error(full.tangent - iso.tangent, fd), 1e-6) << law.name();
    // volumetric(J): U' and U'' against central differences of U and U'.
    for (double Jv : {0.9, 1.0, 1.07}) {
      const double hj = 1e-6;
      const Eigen::Vector3d u = law.volumetric(Jv);
      const Eigen::Vector3d up = law.volumetric(Jv + hj), um = law.volumetric(Jv - hj);
      EXPECT_NEAR(u(1), (up(0) - um(0)) / (2 * hj), 1e-6 * std::abs(u(2)) * hj + 1e-9 * u(2));
      EXPECT_NEAR(u(2), (up(1) - um(1)) / (2 * hj), 1e-8 * u(2));
    }
    EXPECT_EQ(law.volumetric(1.0)(0), 0.0);
    EXPECT_EQ(law.volumetric(1.0)(1), 0.0);
    EXPECT_NEAR(law.volumetric(1.0)(2), law.bulk_modulus(), 1e-12 * law.bulk_modulus());
  }
}

TEST(MaterialTangentSwitch, ResidualOnlyEvaluationSkipsTheTangent) {
  std::mt19937 rng(8);
  for (Case& c : cases(rng)) {
    c.in.history = c.history;
    const testing::Evaluation with = testing::evaluate(*c.law, c.in, testing::Part::full, true);
    std::vector<double> trial(c.history.size());
    PointResult r;
    r.history = trial;
    r.tangent.setConstant(7.0);
    ASSERT_EQ(c.law->evaluate(c.in, r, false), PointStatus::ok);
    EXPECT_TRUE((r.tangent.array() == 7.0).all()) << c.law->name();
    EXPECT_EQ(r.S, with.S) << c.law->name();
    EXPECT_EQ(trial, with.trial) << c.law->name();
  }
}

TEST(LinearElastic, TangentAtRestIsHookesMatrix) {
  const double E = 15.0e3, nu = 0.49;  // skin (thesis ch. 4)
  const auto law = make_material("linear_elastic", {{"E", E}, {"nu", nu}});
  const testing::Evaluation e = testing::evaluate(*law, PointInput{});
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  Matrix6d hooke = Matrix6d::Zero();
  hooke.topLeftCorner<3, 3>().setConstant(lambda);
  hooke.diagonal() << lambda + 2 * mu, lambda + 2 * mu, lambda + 2 * mu, mu, mu, mu;
  EXPECT_LT(testing::relative_error(e.tangent, hooke), 1e-13) << e.tangent;
  EXPECT_NEAR(law->shear_modulus(), mu, 1e-12 * mu);
  EXPECT_NEAR(law->bulk_modulus(), E / (3 * (1 - 2 * nu)), 1e-9);
}

TEST(NeoHookean, IsochoricFormOfThesis41) {
  // Uniaxial isochoric stretch: sigma_33 - sigma_11 = 2 C10 (λ² - 1/λ), pressure-free part.
  const double C10 = 420.0, K = 36.0e3, l = 1.3;
  const auto law = make_material("neo_hookean", {{"C10", C10}, {"K", K}});
  PointInput in;
  in.F = Eigen::Vector3d(1 / std::sqrt(l), 1 / std::sqrt(l), l).asDiagonal();
  std::vector<Eigen::Matrix3d> parts(2);
  law->cauchy_parts(in, {}, parts);
  const Eigen::Matrix3d sigma = parts[0] + parts[1];
  EXPECT_NEAR(sigma(2, 2) - sigma(0, 0), 2 * C10 * (l * l - 1 / l), 1e-10 * C10);
  EXPECT_NEAR(parts[1].norm(), 0.0, 1e-12);  // J = 1
  EXPECT_NEAR(law->shear_modulus(), 2 * C10, 1e-12);
  EXPECT_NEAR(law->bulk_modulus(), K, 1e-12);
}

}  // namespace
}  // namespace isomuscle::materials
