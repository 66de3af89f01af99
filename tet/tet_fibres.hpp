#pragma once
// Fibre directions at the quadrature points of a tetrahedral mesh (one unit vector per point, the
// layout TetProblem takes):
// * constant: one direction everywhere;
// * from a NURBS solid (thesis chapter 5, the FEM–NURBS method; SPEC §1 "Fibre field"): each
//   quadrature point X is located in the solid by point inversion, xi = H^-1(X)
//   (geometry::PointInverter, on the unrefined shrink solid), and takes the normalised tangent of
//   the isocurve through xi in the parametric direction d, A = (dH/dxi_d) / |dH/dxi_d|
//   (thesis 5.29, geometry/fibre_field.hpp).
#include <Eigen/Core>
#include <vector>

#include "geometry/nurbs_volume.hpp"
#include "geometry/point_inversion.hpp"
#include "tet/tet_space.hpp"

namespace isomuscle::tet {

// The same unit direction at every point; throws std::invalid_argument for a zero or non-finite
// direction.
std::vector<Eigen::Vector3d> constant_fibres(const TetSpace& space,
                                             const Eigen::Vector3d& direction);

// The fibre at one physical point X (m): the isocurve tangent in direction d at the parameters
// found by inversion. A point outside the solid (straight-sided tetrahedra cut chords through the
// curved boundary) takes the closest point of the solid when it lies within max_outside_distance
// (m); farther away std::runtime_error names X and the distance. Throws std::domain_error where the
// isocurve has no tangent (fibre_field.hpp).
Eigen::Vector3d nurbs_fibre_at(const geometry::PointInverter& inverter, const Eigen::Vector3d& X,
                               int direction, double max_outside_distance);

// xi = H^-1(X) of one physical point, with nurbs_fibre_at's rule for points outside the solid.
Eigen::Vector3d parameters_at(const geometry::PointInverter& inverter, const Eigen::Vector3d& X,
                              double max_outside_distance);

// parameters_at at every quadrature point, element-major (for fibre fields that cut the body at
// isoparametric surfaces); max_outside_distance < 0 as for nurbs_fibres.
std::vector<Eigen::Vector3d> quadrature_parameters(const TetSpace& space,
                                                   const geometry::NurbsVolume& volume,
                                                   double max_outside_distance = -1.0,
                                                   const geometry::InversionOptions& options = {});

// nurbs_fibre_at at every quadrature point, element-major. max_outside_distance < 0 means 2 % of
// the solid's size (PointInverter::size()).
std::vector<Eigen::Vector3d> nurbs_fibres(const TetSpace& space,
                                          const geometry::NurbsVolume& volume, int direction,
                                          double max_outside_distance = -1.0,
                                          const geometry::InversionOptions& options = {});

}  // namespace isomuscle::tet
