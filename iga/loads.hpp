#pragma once
// External loads in the reference configuration (dead loads), assembled into the "all" DOF
// numbering (3 node + c):
//   surface traction on a parametric side:  f_a += int_side R_a t0(X, t) dA   (t0 in Pa per unit
//                                                                               reference area)
//   body force:                             f_a += int_V R_a b0(X, t) dV     (b0 in N/m^3)
// dA = |dX/ds x dX/dt| ds dt on the side; a collapsed side (the centreline w = 1 of a shrink solid)
// has dA = 0 and carries no load.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "iga/boundary_conditions.hpp"
#include "iga/dof_map.hpp"
#include "iga/space.hpp"

namespace isomuscle::iga {

using VectorFunction = std::function<Eigen::Vector3d(const Eigen::Vector3d& X, double t)>;

struct SurfaceLoad {
  std::string label;
  Side side = Side::u1;
  VectorFunction traction;  // nominal traction, Pa
};

struct BodyLoad {
  std::string label;
  VectorFunction force;  // N/m^3 of reference volume
};

struct Loads {
  std::vector<SurfaceLoad> surface;
  std::vector<BodyLoad> body;
  bool empty() const { return surface.empty() && body.empty(); }
};

// f = sum of the loads at time t, size dofs.num_dofs() (overwritten). Throws std::invalid_argument
// naming the load when a function is empty or returns a non-finite value.
void assemble_external_forces(const Space& space, const DofMap& dofs, const Loads& loads, double t,
                              Eigen::VectorXd& f);

// Reference area of a parametric side (m^2), by the same quadrature.
double side_area(const Space& space, Side side);

}  // namespace isomuscle::iga
