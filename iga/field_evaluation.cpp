#include "iga/field_evaluation.hpp"

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>
#include <string>

namespace isomuscle::iga {

// u(xi) = sum_a R_a u_a, dX/dxi = sum_a X_a (x) dR_a/dxi, du/dX = (sum_a u_a (x) dR_a/dxi) J^-1.
FieldPoint evaluate_field(const Space& space, const DofMap& dofs, const Eigen::VectorXd& u_full,
                          const Eigen::Vector3d& xi) {
  if (u_full.size() != dofs.num_dofs()) {
    throw std::invalid_argument("evaluate_field: displacement vector of size " +
                                std::to_string(u_full.size()) + ", expected " +
                                std::to_string(dofs.num_dofs()));
  }
  FieldPoint out;
  out.element = space.locate(xi);
  out.xi = xi;
  geometry::VolumeBasis basis;
  space.volume().evaluate_basis_in_span(space.element(out.element).span, xi, basis);
  Eigen::Matrix3d du_dxi = Eigen::Matrix3d::Zero();
  out.jacobian.setZero();
  for (std::size_t a = 0; a < basis.index.size(); ++a) {
    const Eigen::Vector3d& P = space.volume().points()[basis.index[a]];
    const Eigen::Vector3d ua = u_full.segment<3>(3 * dofs.node(basis.index[a]));
    out.X.noalias() += basis.value[a] * P;
    out.u.noalias() += basis.value[a] * ua;
    out.jacobian.noalias() += P * basis.derivative[a].transpose();
    du_dxi.noalias() += ua * basis.derivative[a].transpose();
  }
  const double det = out.jacobian.determinant();
  out.F.setIdentity();
  out.regular = det > 1e-14 * std::pow(out.jacobian.norm(), 3);
  if (out.regular) {
    out.F.noalias() += du_dxi * out.jacobian.inverse();
  }
  return out;
}

Tessellation tessellate(const Space& space, const DofMap& dofs, const Eigen::VectorXd& u_full,
                        int subdivisions) {
  if (subdivisions < 1 || subdivisions > 16) {
    throw std::invalid_argument("tessellate: subdivisions " + std::to_string(subdivisions) +
                                " outside the valid range 1..16");
  }
  Tessellation t;
  std::array<std::vector<double>, 3> coords;
  std::array<std::vector<int>, 3> cell_span;  // element position of each cell per direction
  for (int d = 0; d < 3; ++d) {
    const auto& counts = space.element_counts();
    for (int i = 0; i < counts[d]; ++i) {
      std::array<int, 3> pos = {0, 0, 0};
      pos[d] = i;
      const Element& el = space.element(pos[0] + counts[0] * (pos[1] + counts[1] * pos[2]));
      const double a = el.box[d][0];
      const double b = el.box[d][1];
      for (int s = 0; s < subdivisions; ++s) {
        coords[d].push_back(a + (b - a) * s / subdivisions);
        cell_span[d].push_back(i);
      }
      if (i == counts[d] - 1) {
        coords[d].push_back(b);
      }
    }
    t.grid[d] = static_cast<int>(coords[d].size());
  }
  const int n = t.grid[0] * t.grid[1] * t.grid[2];
  t.parametric.resize(n);
  t.reference.resize(n);
  t.displacement.resize(n);
  for (int k = 0; k < t.grid[2]; ++k) {
    for (int j = 0; j < t.grid[1]; ++j) {
      for (int i = 0; i < t.grid[0]; ++i) {
        const int idx = i + t.grid[0] * (j + t.grid[1] * k);
        const Eigen::Vector3d xi(coords[0][i], coords[1][j], coords[2][k]);
        const FieldPoint fp = evaluate_field(space, dofs, u_full, xi);
        t.parametric[idx] = xi;
        t.reference[idx] = fp.X;
        t.displacement[idx] = fp.u;
      }
    }
  }
  const auto& counts = space.element_counts();
  auto id = [&](int i, int j, int k) { return i + t.grid[0] * (j + t.grid[1] * k); };
  for (int k = 0; k + 1 < t.grid[2]; ++k) {
    for (int j = 0; j + 1 < t.grid[1]; ++j) {
      for (int i = 0; i + 1 < t.grid[0]; ++i) {
        t.hexahedra.push_back({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                               id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1),
                               id(i, j + 1, k + 1)});
        t.cell_element.push_back(cell_span[0][i] +
                                 counts[0] * (cell_span[1][j] + counts[1] * cell_span[2][k]));
      }
    }
  }
  return t;
}

}  // namespace isomuscle::iga
