#pragma once
// Where on a body's free surface a local check is made (surface_stability_check.hpp,
// element_layer_check.hpp), as either discretisation locates it.
#include <Eigen/Core>

namespace isomuscle::io {

// A place on a traction-free part of the boundary (not a closed seam, the collapsed axis of a
// shrink solid or a face with prescribed displacements): a boundary point, its outward unit normal
// in the reference configuration, and the quadrature point below it (element, local point) where
// the state is taken.
struct SurfaceLocation {
  int element = -1, point = -1;
  Eigen::Vector3d surface_position = Eigen::Vector3d::Zero();  // m
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  // NURBS solids: the parametric direction the side is normal to (0, 1, 2) and its end (0 or 1);
  // -1 for tetrahedra.
  int side_direction = -1, side_end = 0;
};

}  // namespace isomuscle::io
