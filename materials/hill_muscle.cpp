#include "materials/hill_muscle.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "materials/decoupled_hyperelastic.hpp"
#include "materials/kinematics.hpp"

namespace isomuscle::materials {

namespace {

void check_sizes(const std::string& law, std::size_t committed, std::size_t trial) {
  if (committed != kHillHistorySize || trial != kHillHistorySize)
    throw std::invalid_argument("material '" + law + "': history spans must hold " +
                                std::to_string(kHillHistorySize) + " doubles (got committed " +
                                std::to_string(committed) + ", trial " + std::to_string(trial) +
                                ")");
}

// Unit undeformed fibre direction N (SPEC §1: A = ∂H/∂ξ / |∂H/∂ξ|).
Eigen::Vector3d unit_fibre(const std::string& law, const Eigen::Vector3d& fibre) {
  const double n = fibre.norm();
  if (!(n > 0.0) || !std::isfinite(n))
    throw std::invalid_argument("material '" + law +
                                "': the fibre direction must be a nonzero finite vector");
  return fibre / n;
}

}  // namespace

void HillMuscle::initial_history(std::span<double> history) const {
  check_sizes(p_.name, history.size(), history.size());
  fibre_.initial_history(history);
}

std::vector<std::string> HillMuscle::history_names() const {
  return {"lambda_s", "lambda_m",   "delta_lambda_m", "lambda_f",
          "see_rate", "fibre_rate", "see_stress",     "see_stiffness"};
}

std::vector<std::string> HillMuscle::cauchy_part_names() const {
  return {"see", "pe", "matrix", "vol"};
}

// (U, U', U'') of U_J = (J - 1)²/D (3.21, 5.44, 5.55); Pa.
Eigen::Vector3d HillMuscle::volumetric(double J) const {
  return {(J - 1.0) * (J - 1.0) / p_.D, 2.0 * (J - 1.0) / p_.D, 2.0 / p_.D};
}

PointStatus HillMuscle::evaluate(const PointInput& in, PointResult& out,
                                 bool compute_tangent) const {
  return evaluate_impl(in, out, compute_tangent, true);
}

PointStatus HillMuscle::evaluate_isochoric(const PointInput& in, PointResult& out,
                                           bool compute_tangent) const {
  return evaluate_impl(in, out, compute_tangent, false);
}

// S (5.40) and dS/dE (5.47 corrected, with the consistent U''_f of hill_fibre.hpp); Pa.
PointStatus HillMuscle::evaluate_impl(const PointInput& in, PointResult& out, bool compute_tangent,
                                      bool with_volume) const {
  check_sizes(p_.name, in.history.size(), out.history.size());
  Kinematics kin;
  if (!compute_kinematics(in.F, kin)) {
    std::copy(in.history.begin(), in.history.end(), out.history.begin());
    out.S.setZero();
    return PointStatus::inverted;
  }
  const Eigen::Vector3d N = unit_fibre(p_.name, in.fibre);
  const double I4_bar = kin.J_m23 * fibre_invariant(kin, N);
  const double lambda_f = std::sqrt(I4_bar);

  const FibreResponse fib = in.trial_is_current
                                ? fibre_.response_of_trial(lambda_f, out.history)
                                : fibre_.update(lambda_f, in.time, in.dt, in.history, out.history);
  if (!fib.ok) {
    out.S.setZero();
    return PointStatus::local_solve_failed;
  }

  // U'_I = bc exp[b(Ī1 - 3)] (5.42), U''_I = b U'_I (5.51).
  IsochoricDerivatives iso;
  iso.psi1 = p_.b * p_.c * std::exp(p_.b * (kin.I1_bar - 3.0));
  iso.psi11 = p_.b * iso.psi1;
  set_fibre_derivatives(lambda_f, fib.sigma_see + fib.sigma_pe, fib.dsigma_see + fib.dsigma_pe,
                        iso);
  VolumetricDerivatives vol;
  vol.dU = 2.0 * (kin.J - 1.0) / p_.D;
  vol.d2U = 2.0 / p_.D;
  decoupled_stress(kin, N, I4_bar, iso, with_volume ? &vol : nullptr, out.S,
                   compute_tangent ? &out.tangent : nullptr);
  if (!out.S.allFinite() || (compute_tangent && !out.tangent.allFinite())) {
    // Overflow (e.g. exp[b(Ī1 - 3)] at an absurd stretch): report instead of returning inf/NaN.
    std::copy(in.history.begin(), in.history.end(), out.history.begin());
    out.S.setZero();
    return PointStatus::local_solve_failed;
  }
  return PointStatus::ok;
}

// Thesis 5.41 split into the parts of 3.44; Pa.
void HillMuscle::cauchy_parts(const PointInput& in, std::span<const double> trial_history,
                              std::span<Eigen::Matrix3d> parts) const {
  if (parts.size() != 4)
    throw std::invalid_argument("material '" + p_.name +
                                "': cauchy_parts needs 4 matrices (see, pe, matrix, vol)");
  check_sizes(p_.name, trial_history.size(), trial_history.size());
  Kinematics kin;
  if (!compute_kinematics(in.F, kin))
    throw std::runtime_error("material '" + p_.name +
                             "': cauchy_parts called with J <= 0 or a non-finite F");
  const Eigen::Vector3d N = unit_fibre(p_.name, in.fibre);
  const double lambda_f = std::sqrt(kin.J_m23 * fibre_invariant(kin, N));
  const Eigen::Vector3d FN = kin.F * N;
  const Eigen::Vector3d n = FN / FN.norm();
  Eigen::Matrix3d dev_nn = n * n.transpose();
  dev_nn.diagonal().array() -= 1.0 / 3.0;

  parts[0] = (fibre_.series_stress(trial_history) * lambda_f / kin.J) * dev_nn;
  parts[1] = (fibre_.parallel_stress(lambda_f) * lambda_f / kin.J) * dev_nn;
  Eigen::Matrix3d B_bar;
  B_bar.noalias() = kin.F * kin.F.transpose();
  B_bar *= kin.J_m23;
  const double dUI = p_.b * p_.c * std::exp(p_.b * (kin.I1_bar - 3.0));
  parts[2] = (2.0 * dUI / kin.J) * B_bar;
  parts[2].diagonal().array() -= 2.0 / 3.0 * dUI * kin.I1_bar / kin.J;
  parts[3] = (2.0 * (kin.J - 1.0) / p_.D) * Eigen::Matrix3d::Identity();
}

}  // namespace isomuscle::materials
