#pragma once
// Fibre directions from a NURBS solid (thesis 5.27–5.30, SPEC §1 "Fibre field"): the undeformed
// fibre at parametric point xi is the normalised tangent of the isocurve through xi in a chosen
// parametric direction d, A = (dH/dxi_d) / |dH/dxi_d|, i.e. a normalised column of the geometry
// Jacobian. The deformed direction is a = F A / |F A| with fibre stretch lambda_f = |F A|.
#include <Eigen/Core>
#include <string_view>

#include "geometry/nurbs_volume.hpp"

namespace isomuscle::geometry {

// "u" | "v" | "w" -> 0 | 1 | 2; throws std::invalid_argument naming the valid choices.
int parse_parametric_direction(std::string_view name);
// 0 | 1 | 2 -> "u" | "v" | "w".
const char* parametric_direction_name(int direction);

// A = J_d / |J_d| (thesis 5.29) for the column d of a geometry Jacobian J = dH/dxi. Throws
// std::domain_error when that column vanishes (|J_d| <= 1e-10 times the largest column, or not
// finite): there the isocurve has no tangent, e.g. the direction around the centreline on the
// collapsed axis w = 1 of a shrink solid.
Eigen::Vector3d fibre_direction(const Eigen::Matrix3d& jacobian, int direction);

// The same at parametric point xi of a volume; the error message names xi.
Eigen::Vector3d fibre_direction(const NurbsVolume& volume, const Eigen::Vector3d& xi,
                                int direction);

// Fibre stretch lambda_f = |F A| (thesis 5.30) for a unit undeformed direction A.
double fibre_stretch(const Eigen::Matrix3d& deformation_gradient,
                     const Eigen::Vector3d& undeformed_direction);

// Deformed fibre direction a = F A / |F A| (thesis 5.30, Weiss et al. 1996). Throws
// std::domain_error when |F A| is zero or not finite (F singular along A: an inverted element).
Eigen::Vector3d deformed_fibre_direction(const Eigen::Matrix3d& deformation_gradient,
                                         const Eigen::Vector3d& undeformed_direction);

}  // namespace isomuscle::geometry
