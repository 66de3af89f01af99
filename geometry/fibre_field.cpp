// Fibre directions as normalised isocurve tangents (thesis 5.27–5.30).
#include "geometry/fibre_field.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace isomuscle::geometry {

namespace {

void check_direction(int direction) {
  if (direction < 0 || direction > 2) {
    throw std::invalid_argument("fibre direction " + std::to_string(direction) +
                                " is not a parametric direction: use 0 (u), 1 (v) or 2 (w)");
  }
}

}  // namespace

int parse_parametric_direction(std::string_view name) {
  if (name == "u")
    return 0;
  if (name == "v")
    return 1;
  if (name == "w")
    return 2;
  throw std::invalid_argument("parametric direction '" + std::string(name) +
                              "' is not one of u, v, w");
}

const char* parametric_direction_name(int direction) {
  check_direction(direction);
  static const char* const names[] = {"u", "v", "w"};
  return names[direction];
}

// Thesis 5.28–5.29: A = (dH/dxi_d) / |dH/dxi_d|; dimensionless. The relative threshold 1e-10
// separates a genuinely vanishing tangent (exactly zero up to rounding on a collapsed row) from a
// short one near it: the tangent shrinks linearly with the distance from the axis.
Eigen::Vector3d fibre_direction(const Eigen::Matrix3d& jacobian, int direction) {
  check_direction(direction);
  const Eigen::Vector3d tangent = jacobian.col(direction);
  const double length = tangent.norm();
  const double largest = jacobian.colwise().norm().maxCoeff();
  if (!(std::isfinite(length) && std::isfinite(largest)) || !(length > 1e-10 * largest)) {
    std::ostringstream msg;
    msg << "fibre direction along " << parametric_direction_name(direction)
        << " is undefined: the isocurve tangent dH/d" << parametric_direction_name(direction)
        << " vanishes (|dH/d" << parametric_direction_name(direction) << "| = " << length
        << ", largest Jacobian column " << largest
        << "); this happens on a collapsed row, e.g. on the centreline (w = 1) of a shrink solid "
           "for the direction around it";
    throw std::domain_error(msg.str());
  }
  return tangent / length;
}

Eigen::Vector3d fibre_direction(const NurbsVolume& volume, const Eigen::Vector3d& xi,
                                int direction) {
  const Eigen::Matrix3d jacobian = volume.jacobian(xi);
  try {
    return fibre_direction(jacobian, direction);
  } catch (const std::domain_error& e) {
    std::ostringstream msg;
    msg << "at (u, v, w) = (" << xi.x() << ", " << xi.y() << ", " << xi.z() << "): " << e.what();
    throw std::domain_error(msg.str());
  }
}

// Thesis 5.30: lambda_f = |F A|, dimensionless.
double fibre_stretch(const Eigen::Matrix3d& deformation_gradient,
                     const Eigen::Vector3d& undeformed_direction) {
  const Eigen::Vector3d stretched = deformation_gradient * undeformed_direction;
  return stretched.norm();
}

// Thesis 5.30: a = F A / lambda_f.
Eigen::Vector3d deformed_fibre_direction(const Eigen::Matrix3d& deformation_gradient,
                                         const Eigen::Vector3d& undeformed_direction) {
  const Eigen::Vector3d stretched = deformation_gradient * undeformed_direction;
  const double lambda = stretched.norm();
  if (!(std::isfinite(lambda) && lambda > 0.0)) {
    std::ostringstream msg;
    msg << "deformed fibre direction undefined: |F A| = " << lambda
        << " (the deformation gradient is singular or not finite along the fibre; an inverted "
           "element?)";
    throw std::domain_error(msg.str());
  }
  return stretched / lambda;
}

}  // namespace isomuscle::geometry
