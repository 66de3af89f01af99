#include "iga/side_quadrature.hpp"

#include <Eigen/Geometry>
#include <array>

#include "geometry/gauss_legendre.hpp"

namespace isomuscle::iga {

// The element's face on the side, its Gauss points in the tensor rule of the side's two directions.
void for_each_side_point(const Space& space, Side side, const SidePointVisitor& visit) {
  const geometry::NurbsVolume& vol = space.volume();
  const int d = side_direction(side);
  const int s = (d + 1) % 3;
  const int t = (d + 2) % 3;
  const auto& counts = space.element_counts();
  const int layer = side_end(side) == 0 ? 0 : counts[d] - 1;
  std::array<geometry::GaussLegendreRule, 3> rules;
  for (int k = 0; k < 3; ++k) {
    const int n =
        space.quadrature().points[k] > 0 ? space.quadrature().points[k] : vol.degree(k) + 1;
    rules[k] = geometry::gauss_legendre_rule(n);
  }
  const double xi_d = side_end(side) == 0 ? vol.domain(d)[0] : vol.domain(d)[1];
  geometry::VolumeBasis basis;
  for (int e = 0; e < space.num_elements(); ++e) {
    const Element& el = space.element(e);
    if (el.position[d] != layer) {
      continue;
    }
    for (std::size_t qs = 0; qs < rules[s].points.size(); ++qs) {
      for (std::size_t qt = 0; qt < rules[t].points.size(); ++qt) {
        Eigen::Vector3d xi;
        xi[d] = xi_d;
        const double as = el.box[s][0], bs = el.box[s][1];
        const double at = el.box[t][0], bt = el.box[t][1];
        xi[s] = 0.5 * (as + bs) + 0.5 * (bs - as) * rules[s].points[qs];
        xi[t] = 0.5 * (at + bt) + 0.5 * (bt - at) * rules[t].points[qt];
        const double w = 0.25 * (bs - as) * (bt - at) * rules[s].weights[qs] * rules[t].weights[qt];
        vol.evaluate_basis_in_span(el.span, xi, basis);
        Eigen::Vector3d X = Eigen::Vector3d::Zero();
        Eigen::Vector3d Xs = Eigen::Vector3d::Zero();
        Eigen::Vector3d Xt = Eigen::Vector3d::Zero();
        for (std::size_t a = 0; a < basis.index.size(); ++a) {
          const Eigen::Vector3d& P = vol.points()[basis.index[a]];
          X.noalias() += basis.value[a] * P;
          Xs.noalias() += basis.derivative[a][s] * P;
          Xt.noalias() += basis.derivative[a][t] * P;
        }
        visit(e, basis, X, Xs.cross(Xt).norm() * w);
      }
    }
  }
}

}  // namespace isomuscle::iga
