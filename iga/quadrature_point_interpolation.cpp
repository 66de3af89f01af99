#include "iga/quadrature_point_interpolation.hpp"

#include <sstream>
#include <stdexcept>

#include "iga/pressure_space.hpp"

namespace isomuscle::iga {

namespace {

// Lagrange basis l_i(t) through the abscissae `nodes` (ascending, distinct), i = 0..n-1.
std::vector<double> lagrange_values(const std::vector<double>& nodes, double t) {
  const std::size_t n = nodes.size();
  std::vector<double> l(n, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      if (j != i)
        l[i] *= (t - nodes[j]) / (nodes[i] - nodes[j]);
    }
  }
  return l;
}

}  // namespace

std::vector<double> quadrature_point_weights(const Space& space, int e, const Eigen::Vector3d& xi) {
  if (e < 0 || e >= space.num_elements()) {
    throw std::invalid_argument("quadrature_point_weights: element " + std::to_string(e) +
                                " out of range");
  }
  // Element reference coordinates t in [-1, 1]^3 (the Gauss rule's coordinates, space.cpp).
  const Eigen::Vector3d t = element_reference_coordinates(space.element(e), xi);
  constexpr double kSlack = 1e-9;  // rounding of xi at the element's faces
  if ((t.array().abs() > 1.0 + kSlack).any()) {
    std::ostringstream msg;
    msg << "quadrature_point_weights: xi = (" << xi[0] << ", " << xi[1] << ", " << xi[2]
        << ") is outside element " << e;
    throw std::invalid_argument(msg.str());
  }
  const std::array<int, 3>& n = space.points_per_direction();
  std::array<std::vector<double>, 3> l;
  for (int d = 0; d < 3; ++d) {
    l[d] = lagrange_values(space.rule(d).points, t[d]);
  }
  std::vector<double> w(static_cast<std::size_t>(space.points_per_element()));
  for (int qw = 0; qw < n[2]; ++qw) {
    for (int qv = 0; qv < n[1]; ++qv) {
      for (int qu = 0; qu < n[0]; ++qu) {
        w[static_cast<std::size_t>(qu + n[0] * (qv + n[1] * qw))] = l[0][qu] * l[1][qv] * l[2][qw];
      }
    }
  }
  return w;
}

}  // namespace isomuscle::iga
