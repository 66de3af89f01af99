#include "iga/loads.hpp"

#include <Eigen/Geometry>
#include <sstream>
#include <stdexcept>

#include "iga/side_quadrature.hpp"

namespace isomuscle::iga {

namespace {

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
        [&](int, const geometry::VolumeBasis& basis, const Eigen::Vector3d& X, double dA) {
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
      [&](int, const geometry::VolumeBasis&, const Eigen::Vector3d&, double dA) { area += dA; });
  return area;
}

}  // namespace isomuscle::iga
