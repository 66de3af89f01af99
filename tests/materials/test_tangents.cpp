// Tangents of every law against central differences of its stress (full and isochoric), over
// random F (stretches 0.7–1.4, shear, rotation) and random fibres; the Hill laws in passive,
// active-shortening and active-lengthening states with dt = 1e-3 s, away from the kinks of the
// piecewise curves (f_λ at r = 0.6, 1.4; f_v at Δλm = 0), and at the activation front, where the
// update takes several substeps (hill_fibre.hpp) and the tangent is chained through them.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>
#include <string>

#include "material_test_support.hpp"
#include "materials/hill_curves.hpp"
#include "materials/hill_fibre.hpp"
#include "materials/hill_muscle.hpp"
#include "materials/material_factory.hpp"

namespace isomuscle::materials {
namespace {

using testing::evaluate;
using testing::fd_tangent;
using testing::Part;
using testing::relative_error;

constexpr double kTolerance = 1e-6;
constexpr double kDt = 1e-3;

double fibre_stretch(const Eigen::Matrix3d& F, const Eigen::Vector3d& N) {
  return std::pow(F.determinant(), -1.0 / 3.0) * (F * N).norm();
}

struct Worst {
  double full = 0.0, iso = 0.0;
};

std::ostream& operator<<(std::ostream& os, const Worst& w) {
  return os << "max relative tangent error: full " << w.full << ", isochoric " << w.iso;
}

// Checks the tangent of `law` at `in` (full and isochoric); records the relative errors.
void check_tangent(const MaterialLaw& law, const PointInput& in, const std::string& what,
                   Worst& worst) {
  for (Part part : {Part::full, Part::isochoric}) {
    const testing::Evaluation e = evaluate(law, in, part);
    EXPECT_EQ(e.status, PointStatus::ok) << what;
    Matrix6d fd;
    EXPECT_TRUE(fd_tangent(law, in, part, fd)) << what;
    const double err = relative_error(e.tangent, fd);
    EXPECT_LT(err, kTolerance) << what << (part == Part::full ? " (full)" : " (isochoric)")
                               << "\nanalytic\n"
                               << e.tangent << "\nfd\n"
                               << fd;
    // Hyperelastic and incremental-potential laws: symmetric tangent.
    EXPECT_LT((e.tangent - e.tangent.transpose()).cwiseAbs().maxCoeff(),
              1e-12 * e.tangent.cwiseAbs().maxCoeff())
        << what;
    double& w = part == Part::full ? worst.full : worst.iso;
    w = std::max(w, err);
  }
}

TEST(MaterialTangent, HyperelasticLawsMatchCentralDifferences) {
  std::mt19937 rng(11);
  for (const std::string model : {"neo_hookean", "linear_elastic"}) {
    const auto law = make_material(model);
    Worst worst;
    for (int trial = 0; trial < 25; ++trial) {
      PointInput in;
      in.F = testing::random_F(rng);
      check_tangent(*law, in, model, worst);
    }
    std::cout << "[measured] " << model << " " << worst << "\n";
  }
}

enum class State { passive, shortening, lengthening, front };

const char* state_name(State s) {
  switch (s) {
    case State::passive:
      return "passive";
    case State::shortening:
      return "shortening";
    case State::lengthening:
      return "lengthening";
    case State::front:
      return "front";
  }
  return "";
}

// A committed history that puts the point in the wanted state at stretch lambda_f: passive with
// a CE that slid freely; active from an isometric equilibrium (σ_SEE = s) with the fibre length
// changed by -+ 0.5 1/s · dt since the last step, so the CE lengthens or shortens; at the front,
// the SEE carries a fifth of s (activation just switched on): the CE shortens fast, in substeps.
std::vector<double> history_for(const HillMuscle& law, State state, double lambda_f, double time) {
  const HillFibreParameters& p = law.parameters().fibre;
  std::vector<double> h(kHillHistorySize);
  const double delta = (state == State::lengthening ? 1.0 : -1.0) * 0.5 * kDt;
  double ls = 1.0;
  if (state != State::passive) {
    const double s = p.sigma0 * law.activation(time) * force_length(lambda_f, p.lambda_opt);
    ls = 1.0 + std::log1p((state == State::front ? 0.2 : 1.0) * s / p.beta) / p.alpha;
  }
  h[kLambdaS] = ls;
  h[kLambdaM] = (1.0 + p.k) * (lambda_f - delta) - p.k * ls;
  h[kDeltaLambdaM] = state == State::passive ? 0.0 : delta;
  h[kLambdaF] = lambda_f - delta;
  return h;
}

void check_hill_law(const std::string& model, const std::map<std::string, double>& extra) {
  std::map<std::string, double> params = extra;
  params["t0"] = 0.1;  // passive before 0.1 s, active (exponential rise) after
  const auto owner = make_material(model, params);
  const auto& law = dynamic_cast<const HillMuscle&>(*owner);
  const double lopt = law.parameters().fibre.lambda_opt;
  std::mt19937 rng(7);
  for (State state : {State::passive, State::shortening, State::lengthening, State::front}) {
    Worst worst;
    int done = 0;
    while (done < 20) {
      PointInput in;
      in.F = testing::random_F(rng);
      in.fibre = testing::random_unit(rng);
      const double lf = fibre_stretch(in.F, in.fibre);
      const double r = lf / lopt;
      // Away from the kinks of f_λ, and where the CE carries force.
      bool near_kink = false;
      for (double kink : {0.4, 0.6, 1.4, 1.6})
        near_kink |= std::abs(r - kink) < 1e-3;
      if (near_kink || (state != State::passive && (r < 0.5 || r > 1.5)))
        continue;
      in.dt = kDt;
      in.time = state == State::passive ? 0.05 : 0.2;
      const std::vector<double> history = history_for(law, state, lf, in.time);
      in.history = history;
      const int substeps = law.fibre().substep_count(history, in.time, in.dt);
      if (state == State::front && !law.parameters().fibre.explicit_lag) {
        EXPECT_GT(substeps, 1);
      } else if (law.parameters().fibre.substeps == 0) {
        EXPECT_EQ(substeps, 1);
      }
      const testing::Evaluation e = evaluate(law, in);
      ASSERT_EQ(e.status, PointStatus::ok);
      const double dlm = e.trial[kDeltaLambdaM];
      if (state == State::passive) {
        EXPECT_EQ(e.trial[kLambdaS], 1.0);
      } else {
        // In the wanted branch, and away from the f_v kink at Δλm = 0.
        EXPECT_GT(state == State::lengthening ? dlm : -dlm, 1e-5) << state_name(state);
        EXPECT_GT(law.fibre().series_stress(e.trial), 0.0);
      }
      check_tangent(law, in, model + " " + state_name(state), worst);
      ++done;
    }
    std::string label;
    for (const auto& [name, value] : extra)
      label += " " + name + "=" + std::to_string(value);
    std::cout << "[measured] " << model << label << " " << state_name(state) << " " << worst
              << "\n";
  }
}

TEST(MaterialTangent, Lu2010ConsistentTangentMatchesCentralDifferences) {
  check_hill_law("lu2010", {});
}

TEST(MaterialTangent, Tang2009ConsistentTangentMatchesCentralDifferences) {
  check_hill_law("tang2009", {});
}

// A nearly vanishing matrix (c = 1e-3 Pa) so that the fibre terms dominate the tangent and are
// checked on their own scale.
TEST(MaterialTangent, FibreTermsAloneMatchCentralDifferences) {
  check_hill_law("lu2010", {{"c", 1e-3}});
  check_hill_law("tang2009", {{"c", 1e-3}});
}

// A fixed number of substeps in every state (the adaptive default takes one away from the front).
TEST(MaterialTangent, FixedSubstepsTangentMatchesCentralDifferences) {
  check_hill_law("lu2010", {{"substeps", 3.0}, {"c", 1e-3}});
  check_hill_law("tang2009", {{"substeps", 3.0}, {"c", 1e-3}});
}

TEST(MaterialTangent, ExplicitLagTangentMatchesCentralDifferences) {
  check_hill_law("lu2010", {{"explicit_lag", 1.0}});
  check_hill_law("tang2009", {{"explicit_lag", 1.0}});
}

// The thesis's frozen-CE tangent (5.54) is not the derivative of the stress for dt > 0; it
// approaches the consistent one as dt -> 0 (the relative gap shrinks about linearly with dt).
TEST(MaterialTangent, FrozenCeTangentDiffersAndConvergesAsDtVanishes) {
  const auto consistent = make_material("lu2010", {{"t0", 0.1}});
  const auto frozen = make_material("lu2010", {{"t0", 0.1}, {"frozen_ce_tangent", 1.0}});
  const auto& law = dynamic_cast<const HillMuscle&>(*consistent);
  PointInput in;
  in.F = Eigen::Vector3d(0.95, 0.95, 1.108).asDiagonal();
  in.fibre = Eigen::Vector3d::UnitZ();
  in.time = 0.2;
  const double lf = fibre_stretch(in.F, in.fibre);
  double previous_gap = 0.0;
  for (double dt : {1e-2, 1e-3, 1e-4, 1e-5}) {
    in.dt = dt;
    const std::vector<double> history = history_for(law, State::shortening, lf, in.time);
    in.history = history;
    const double gap = relative_error(evaluate(*frozen, in, Part::isochoric).tangent,
                                      evaluate(*consistent, in, Part::isochoric).tangent);
    std::cout << "[measured] frozen-CE vs consistent tangent, dt = " << dt << ": " << gap << "\n";
    if (dt == 1e-3) {
      EXPECT_GT(gap, 1e-2);
    }
    if (previous_gap > 0.0) {
      EXPECT_LT(gap, 0.2 * previous_gap);
    }
    previous_gap = gap;
  }
  EXPECT_LT(previous_gap, 1e-3);
}

}  // namespace
}  // namespace isomuscle::materials
