#include "materials/neo_hookean.hpp"

#include <cmath>
#include <stdexcept>

#include "materials/decoupled_hyperelastic.hpp"
#include "materials/kinematics.hpp"
#include "materials/parameter_values.hpp"

namespace isomuscle::materials {

NeoHookean::NeoHookean(std::string name, double mu, double kappa)
    : name_(std::move(name)), mu_(mu), kappa_(kappa) {}

// (U, U', U'') of U = kappa/2 (J - 1)² (thesis 4.1 with kappa = K); Pa.
Eigen::Vector3d NeoHookean::volumetric(double J) const {
  return {0.5 * kappa_ * (J - 1.0) * (J - 1.0), kappa_ * (J - 1.0), kappa_};
}

PointStatus NeoHookean::evaluate(const PointInput& in, PointResult& out,
                                 bool compute_tangent) const {
  return evaluate_impl(in, out, compute_tangent, true);
}

PointStatus NeoHookean::evaluate_isochoric(const PointInput& in, PointResult& out,
                                           bool compute_tangent) const {
  return evaluate_impl(in, out, compute_tangent, false);
}

// S = mu (J^(-2/3) I - Ī1/3 C^-1) + kappa J (J - 1) C^-1 and its tangent (decoupled_stress); Pa.
PointStatus NeoHookean::evaluate_impl(const PointInput& in, PointResult& out, bool compute_tangent,
                                      bool with_volume) const {
  Kinematics kin;
  if (!compute_kinematics(in.F, kin)) {
    out.S.setZero();
    return PointStatus::inverted;
  }
  IsochoricDerivatives iso;
  iso.psi1 = 0.5 * mu_;
  VolumetricDerivatives vol;
  vol.dU = kappa_ * (kin.J - 1.0);
  vol.d2U = kappa_;
  decoupled_stress(kin, Eigen::Vector3d::Zero(), 0.0, iso, with_volume ? &vol : nullptr, out.S,
                   compute_tangent ? &out.tangent : nullptr);
  return PointStatus::ok;
}

std::vector<std::string> NeoHookean::cauchy_part_names() const {
  return {"iso", "vol"};
}

// sigma_iso = (mu/J)(B̄ - Ī1/3 I), sigma_vol = kappa (J - 1) I (push-forward of the parts); Pa.
void NeoHookean::cauchy_parts(const PointInput& in, std::span<const double> /*trial_history*/,
                              std::span<Eigen::Matrix3d> parts) const {
  if (parts.size() != 2)
    throw std::invalid_argument("material '" + name_ +
                                "': cauchy_parts needs 2 matrices (iso, vol)");
  Kinematics kin;
  if (!compute_kinematics(in.F, kin))
    throw std::runtime_error("material '" + name_ + "': cauchy_parts called with J <= 0");
  parts[0].noalias() = kin.F * kin.F.transpose();
  parts[0] *= mu_ * kin.J_m23 / kin.J;
  parts[0].diagonal().array() -= mu_ * kin.I1_bar / (3.0 * kin.J);
  parts[1] = kappa_ * (kin.J - 1.0) * Eigen::Matrix3d::Identity();
}

const std::vector<ParameterSpec>& neo_hookean_parameters() {
  static const std::vector<ParameterSpec> specs = {
      make_spec("C10", 420.0, 0.0, kInfinity, true, false, "Pa",
                "C10 of U = C10(Ī1-3) + K/2 (J-1)^2 (thesis 4.1, subcutaneous tissue 0.42 kPa)"),
      make_spec("K", 36.0e3, 0.0, kInfinity, true, false, "Pa",
                "bulk modulus K of thesis 4.1 (subcutaneous tissue 36 kPa)"),
  };
  return specs;
}

std::unique_ptr<MaterialLaw> make_neo_hookean(const ParameterValues& v) {
  return std::make_unique<NeoHookean>("neo_hookean", 2.0 * v.get("C10"), v.get("K"));
}

}  // namespace isomuscle::materials
