#include "materials/material_law.hpp"

#include <Eigen/LU>
#include <stdexcept>

#include "materials/kinematics.hpp"

namespace isomuscle::materials {

const char* to_string(PointStatus s) {
  switch (s) {
    case PointStatus::ok:
      return "ok";
    case PointStatus::inverted:
      return "inverted (J <= 0 or non-finite deformation gradient)";
    case PointStatus::local_solve_failed:
      return "local material solve failed (or the stress overflowed)";
  }
  return "unknown status";
}

PointStatus MaterialLaw::evaluate_isochoric(const PointInput& /*in*/, PointResult& /*out*/,
                                            bool /*compute_tangent*/) const {
  throw std::logic_error("material '" + name() +
                         "' has no isochoric/volumetric split (evaluate_isochoric)");
}

Eigen::Vector3d MaterialLaw::volumetric(double /*J*/) const {
  throw std::logic_error("material '" + name() +
                         "' has no isochoric/volumetric split (volumetric)");
}

// One part, the total Cauchy stress sigma = F S F^T / J (thesis 5.41); Pa. Allocates the scratch
// history: this is a reporting path, not an assembly one.
void MaterialLaw::cauchy_parts(const PointInput& in, std::span<const double> /*trial_history*/,
                               std::span<Eigen::Matrix3d> parts) const {
  if (parts.size() != 1)
    throw std::invalid_argument("material '" + name() + "': cauchy_parts needs 1 matrix (total)");
  std::vector<double> scratch(static_cast<std::size_t>(history_size()));
  PointResult result;
  result.history = scratch;
  const PointStatus status = evaluate(in, result, false);
  if (status != PointStatus::ok)
    throw std::runtime_error("material '" + name() + "': cauchy_parts: " + to_string(status));
  parts[0] = push_forward_stress(in.F, in.F.determinant(), result.S);
}

// Voigt order 11, 22, 33, 12, 23, 13 (material_law.hpp).
Vector6d to_voigt_stress(const Eigen::Matrix3d& S) {
  return voigt(S);
}

Eigen::Matrix3d from_voigt_stress(const Vector6d& s) {
  Eigen::Matrix3d S;
  S << s(0), s(3), s(5), s(3), s(1), s(4), s(5), s(4), s(2);
  return S;
}

}  // namespace isomuscle::materials
