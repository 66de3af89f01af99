#include "iga/loads.hpp"

#include <Eigen/Geometry>
#include <sstream>
#include <stdexcept>

#include "geometry/gauss_legendre.hpp"

namespace isomuscle::iga {

namespace {

// Calls visit(control point indices, values R_a, X, dA) at every Gauss point of a side.
template <typename Visit>
void for_each_side_point(const Space& space, Side side, Visit&& visit) {
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
        visit(basis, X, Xs.cross(Xt).norm() * w);
      }
    }
  }
}

void check_value(const Eigen::Vector3d& v, const std::string& label, const Eigen::Vector3d& X,
                 double t) {
  if (!v.allFinite()) {
    std::ostringstream msg;
    msg << "load '" << label << "' is not finite at X = (" << X[0] << ", " << X[1] << ", " << X[2]
        << "), t = " << t << " s";
    throw std::invalid_argument(msg.str());
  }
}

}  // namespace

// f_a = int_side R_a t0 dA + int_V R_a b0 dV (header).
void assemble_external_forces(const Space& space, const DofMap& dofs, const Loads& loads, double t,
                              Eigen::VectorXd& f) {
  f.setZero(dofs.num_dofs());
  for (const SurfaceLoad& load : loads.surface) {
    if (!load.traction) {
      throw std::invalid_argument("surface load '" + load.label + "' has no traction function");
    }
    for_each_side_point(
        space, load.side,
        [&](const geometry::VolumeBasis& basis, const Eigen::Vector3d& X, double dA) {
          if (dA == 0.0) {
            return;
          }
          const Eigen::Vector3d tr = load.traction(X, t);
          check_value(tr, load.label, X, t);
          for (std::size_t a = 0; a < basis.index.size(); ++a) {
            const int node = dofs.node(basis.index[a]);
            f.segment<3>(3 * node) += (basis.value[a] * dA) * tr;
          }
        });
  }
  for (const BodyLoad& load : loads.body) {
    if (!load.force) {
      throw std::invalid_argument("body load '" + load.label + "' has no force function");
    }
    for (int e = 0; e < space.num_elements(); ++e) {
      const auto cps = space.control_points(e);
      for (int q = 0; q < space.points_per_element(); ++q) {
        const Eigen::Vector3d& X = space.position(e, q);
        const Eigen::Vector3d b = load.force(X, t);
        check_value(b, load.label, X, t);
        const auto R = space.values(e, q);
        const double dv = space.dv(e, q);
        for (std::size_t a = 0; a < cps.size(); ++a) {
          f.segment<3>(3 * dofs.node(cps[a])) += (R[a] * dv) * b;
        }
      }
    }
  }
}

double side_area(const Space& space, Side side) {
  double area = 0.0;
  for_each_side_point(
      space, side,
      [&](const geometry::VolumeBasis&, const Eigen::Vector3d&, double dA) { area += dA; });
  return area;
}

}  // namespace isomuscle::iga
