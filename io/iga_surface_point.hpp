#pragma once
// The traction-free boundary of an isogeometric solid and the place on it nearest a given point
// (RunModel::committed_surface_point, the surface_stability probe).
//
// A parametric side (u0 ... w1) is traction-free boundary unless it is
// * a closed seam: its nodes are the opposite side's (iga/dof_map.hpp merges them);
// * collapsed: the centreline w = 1 of a shrink solid, each of whose rows around the axis is one
//   node (a curve, not a surface);
// * supported: every node of it has a prescribed component (fixed, moved, symmetry plane), or it
//   rests on springs (one of `sprung`, the elastic supports' sides).
// Dead tractions are not told apart from a free surface: a loaded side counts as free.
#include <optional>
#include <vector>

#include "iga/boundary_conditions.hpp"
#include "iga/problem.hpp"
#include "io/run_model.hpp"

namespace isomuscle::io {

std::vector<iga::Side> traction_free_sides(const iga::Space& space, const iga::DofMap& dofs,
                                           const iga::ConstrainedDofs& constraints,
                                           const std::vector<iga::Side>& sprung = {});

// Over the quadrature points of the elements on a traction-free side, each projected onto the
// side along the side's parametric direction: the projection nearest `near`, then the point
// nearest its projection. The normal is that of the side at the projection, dX/dxi_a x dX/dxi_b
// oriented along +-dX/dxi_d (d the side's direction, outward at its end); projections where it
// vanishes (a collapsed edge) are skipped. nullopt when there is no such point.
std::optional<SurfaceLocation> locate_surface_point(const iga::Problem& problem,
                                                    const Eigen::Vector3d& near);

}  // namespace isomuscle::io
