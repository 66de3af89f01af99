#include "tet/tet_fibres.hpp"

#include <sstream>
#include <stdexcept>

#include "geometry/fibre_field.hpp"

namespace isomuscle::tet {

std::vector<Eigen::Vector3d> constant_fibres(const TetSpace& space,
                                             const Eigen::Vector3d& direction) {
  const double n = direction.norm();
  if (!direction.allFinite() || !(n > 0.0)) {
    throw std::invalid_argument("constant fibre direction must be a finite non-zero vector");
  }
  return std::vector<Eigen::Vector3d>(space.num_points(), direction / n);
}

Eigen::Vector3d parameters_at(const geometry::PointInverter& inverter, const Eigen::Vector3d& X,
                              double max_outside_distance) {
  const geometry::InversionResult r = inverter.invert(X);
  if (!r.inside && r.distance > max_outside_distance) {
    std::ostringstream msg;
    msg << "fibre at X = (" << X[0] << ", " << X[1] << ", " << X[2]
        << ") m: the point lies outside the NURBS solid by " << r.distance
        << " m, more than the allowed " << max_outside_distance
        << " m (does the mesh belong to this solid, in the same units?)";
    throw std::runtime_error(msg.str());
  }
  return r.xi;
}

// A = dH/dxi_d / |dH/dxi_d| at xi = H^-1(X) (thesis 5.29).
Eigen::Vector3d nurbs_fibre_at(const geometry::PointInverter& inverter, const Eigen::Vector3d& X,
                               int direction, double max_outside_distance) {
  return geometry::fibre_direction(inverter.volume(),
                                   parameters_at(inverter, X, max_outside_distance), direction);
}

std::vector<Eigen::Vector3d> quadrature_parameters(const TetSpace& space,
                                                   const geometry::NurbsVolume& volume,
                                                   double max_outside_distance,
                                                   const geometry::InversionOptions& options) {
  const geometry::PointInverter inverter(volume, options);
  const double allowed = max_outside_distance < 0.0 ? 0.02 * inverter.size() : max_outside_distance;
  std::vector<Eigen::Vector3d> out;
  out.reserve(space.num_points());
  for (int e = 0; e < space.num_elements(); ++e) {
    for (int q = 0; q < space.points_per_element(); ++q) {
      out.push_back(parameters_at(inverter, space.position(e, q), allowed));
    }
  }
  return out;
}

std::vector<Eigen::Vector3d> nurbs_fibres(const TetSpace& space,
                                          const geometry::NurbsVolume& volume, int direction,
                                          double max_outside_distance,
                                          const geometry::InversionOptions& options) {
  if (direction < 0 || direction > 2) {
    throw std::invalid_argument("fibre direction " + std::to_string(direction) +
                                " (valid: 0 = u, 1 = v, 2 = w)");
  }
  std::vector<Eigen::Vector3d> out =
      quadrature_parameters(space, volume, max_outside_distance, options);
  for (Eigen::Vector3d& xi : out)
    xi = geometry::fibre_direction(volume, xi, direction);
  return out;
}

}  // namespace isomuscle::tet
