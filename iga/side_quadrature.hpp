#pragma once
// Gauss quadrature over a parametric side of a NURBS solid: at every point of every element whose
// face lies on the side, the element, the basis there (control point indices, values R_a and
// derivatives), the point X and the reference area element dA = |dX/ds x dX/dt| w ds dt (s, t the
// side's own directions). The rule per direction is the space's (degree + 1 by default). A
// collapsed side (the centreline w = 1 of a shrink solid) gives dA = 0 everywhere.
#include <Eigen/Core>
#include <functional>

#include "geometry/nurbs_volume.hpp"
#include "iga/boundary_conditions.hpp"
#include "iga/space.hpp"

namespace isomuscle::iga {

using SidePointVisitor = std::function<void(int element, const geometry::VolumeBasis& basis,
                                            const Eigen::Vector3d& X, double dA)>;

void for_each_side_point(const Space& space, Side side, const SidePointVisitor& visit);

}  // namespace isomuscle::iga
