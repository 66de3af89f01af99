#pragma once
// Evaluating the discrete displacement field u(xi) = sum_a R_a(xi) u_node(a) of a full DOF vector
// ("all" numbering 3 node + c) at parametric points, and tessellating the solid for output: a
// parametric grid with `subdivisions` cells per knot span and direction, shared between
// neighbouring spans, one hexahedron per cell (VTK_HEXAHEDRON vertex order), reference positions
// and displacements per grid point. The HDF5/XDMF writer (io/) consumes Tessellation.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "iga/dof_map.hpp"
#include "iga/space.hpp"

namespace isomuscle::iga {

// Position X(xi), displacement u(xi) and gradients dX/dxi, du/dX at a parametric point.
struct FieldPoint {
  int element = -1;
  Eigen::Vector3d xi = Eigen::Vector3d::Zero();
  Eigen::Vector3d X = Eigen::Vector3d::Zero();             // reference position, m
  Eigen::Vector3d u = Eigen::Vector3d::Zero();             // displacement, m
  Eigen::Matrix3d jacobian = Eigen::Matrix3d::Identity();  // dX/dxi
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();         // I + du/dX (only when regular)
  bool regular = true;  // false where det(dX/dxi) <= 0: on the collapsed axis F is undefined
};

// Throws std::invalid_argument when xi is outside the domain or u_full has the wrong size.
FieldPoint evaluate_field(const Space& space, const DofMap& dofs, const Eigen::VectorXd& u_full,
                          const Eigen::Vector3d& xi);

struct Tessellation {
  std::array<int, 3> grid = {0, 0, 0};        // points per direction
  std::vector<Eigen::Vector3d> parametric;    // per point, i fastest
  std::vector<Eigen::Vector3d> reference;     // X, m
  std::vector<Eigen::Vector3d> displacement;  // u, m (deformed position X + u)
  std::vector<std::array<int, 8>> hexahedra;  // point indices, VTK order
  std::vector<int> cell_element;              // the knot-span element of each cell
};

// subdivisions in 1..16 (std::invalid_argument otherwise).
Tessellation tessellate(const Space& space, const DofMap& dofs, const Eigen::VectorXd& u_full,
                        int subdivisions);

}  // namespace isomuscle::iga
