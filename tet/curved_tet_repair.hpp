#pragma once
// Curved 10-node tetrahedra that fold over where the analysis integrates, made straight-sided.
// gmsh places the edge nodes of boundary edges on the curved surface (setOrder(2)); where the
// surface turns faster than the mesh resolves it, the curved element folds over. The synthetic
// depressor anguli oris (examples/geometry/README.md) is 2 mm thick and 30 mm wide at its root,
// so the radius of curvature at the edges of its elliptical section is b^2 / a = 0.07 mm: with
// 1.5 mm elements 7 of the 2558 tetrahedra gmsh 4.8 returns are folded at a quadrature point
// (45 have det < 0 somewhere), and the set-up stopped at the first such point. gmsh's high-order
// optimisers do not mend them (HighOrderElastic leaves 36 of the 45; "HighOrder" is not built
// into Debian's gmsh).
// Straightening an element's edges gives the straight-sided element of the same corners, valid
// whenever the corner tetrahedron is, at the price of the boundary's curvature inside that
// element only.
//
// The test is the scaled Jacobian det(dX/dxi)(xi) / det(dX/dxi)_straight at the points of the
// rule the analysis integrates with (the default 4-point rule, default_tet_rule(2), unless a scene
// asks for another; the 14-point rule's points lie nearer the edges and corners and find folds
// the 4 points miss): below 0.01 an element is folded or so nearly singular there that its
// stiffness is 100 times off. Only those points:
// curved elements of the round examples at about five elements across have det < 0 at some
// corner or edge midpoint but not at the rule's points (cone 4 of 774 elements), and straightening
// them cost 1.3e-3 of the cone's volume with no gain to the analysis. Straightening an edge
// changes the neighbours that share it, so the test is repeated until no element is below it.
#include "tet/tet_elements.hpp"
#include "tet/tet_mesh.hpp"

namespace isomuscle::tet {

// The smallest scaled Jacobian of element e at the points of rule (1 for a straight-sided element
// and for every element of a 4-node mesh).
double smallest_scaled_jacobian(const TetMesh& mesh, int e,
                                const TetRule& rule = default_tet_rule(2));

// Moves the edge nodes of every 10-node element whose smallest scaled Jacobian at the points of
// rule is below threshold to the midpoints of their edges; returns the number of elements
// straightened (0 for a 4-node mesh or a mesh without such elements). The corner tetrahedra must
// be valid (TetMesh::validate).
int straighten_folded_elements(TetMesh& mesh, const TetRule& rule = default_tet_rule(2),
                               double threshold = 0.01);

}  // namespace isomuscle::tet
