#pragma once
// The traction-free boundary of a tetrahedral mesh and the place on it nearest a given point
// (RunModel::committed_surface_point, the surface_stability probe). A boundary triangle is
// traction-free unless every node of it has a prescribed component (a fixed, moved or symmetry
// face). Dead tractions are not told apart from a free surface: a loaded triangle counts as free.
#include <optional>

#include "io/run_model.hpp"
#include "tet/tet_problem.hpp"

namespace isomuscle::io {

// The traction-free boundary triangle whose centroid (of its corners) is nearest `near`, its
// element's quadrature point nearest that centroid, and the outward normal of the triangle's
// corners (away from the element's fourth corner). nullopt when no triangle is free.
std::optional<SurfaceLocation> locate_surface_point(const tet::TetProblem& problem,
                                                    const Eigen::Vector3d& near);

}  // namespace isomuscle::io
