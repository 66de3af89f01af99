#pragma once
// Extrusion of a NURBS surface into a solid of constant thickness (a "linear sweep", Piegl &
// Tiller, The NURBS Book §8.4):
//   H(u, v, w) = B(u, v) + w d,   w in [0, 1],
// degree 1 in w, control points C_ij0 = B_ij and C_ij1 = B_ij + d with the surface's weights in
// both layers (a rational surface stays exactly represented: the homogeneous points are
// (w_ij B_ij, w_ij) and (w_ij (B_ij + d), w_ij)). For flat sheets and plates that are not tubes
// around a centreline — Cook's membrane, a planar muscle sheet — where the shrinking construction
// (shrink.hpp) does not apply.
//
// Volume layout: direction 0 is the surface's u (reversed where needed so that det J > 0),
// direction 1 its v, direction 2 is w: w = 0 is the surface, w = 1 its copy moved by d.
#include <Eigen/Core>

#include "geometry/nurbs_surface.hpp"
#include "geometry/nurbs_volume.hpp"

namespace isomuscle::geometry {

struct Extrusion {
  NurbsVolume volume;
  bool u_reversed = false;  // the surface's u was reversed to make det J > 0
};

// Throws std::invalid_argument when d is not finite or zero, or when the solid is degenerate (d in
// the tangent plane of the surface somewhere, so that det J changes sign or vanishes: the signed
// volume of the solid is then not |V| of its absolute Jacobian).
Extrusion extrude(const NurbsSurface& surface, const Eigen::Vector3d& d);

}  // namespace isomuscle::geometry
