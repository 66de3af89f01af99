#pragma once
// [[tetrahedra.refine]] as gmsh's local element size (tet/tet_meshing.hpp, MeshingOptions::
// local_size): near each refined face the target edge length is
//   h(x) = size + (element_size - size) * min(d(x) / distance, 1),
// d(x) the distance from x to the face, and the smallest h of all refinements is taken. The face
// is the solid's (the same parametric face a [[boundary]] of that name selects). d is measured to
// points sampled on the face a quarter of the refined size apart, less the sampling's error
// bound (about 0.6 size): h is size on the face and nowhere above what is asked; the refined zone
// reaches up to 0.6 size further than `distance`.
#include <vector>

#include "io/scene.hpp"
#include "io/scene_solid.hpp"
#include "tet/tet_meshing.hpp"

namespace isomuscle::io {

// Sets options.local_size and options.finest_size from the refinements (nothing when empty);
// options.element_size must be set. Throws std::invalid_argument naming the face when it is a
// single point of the solid.
void set_face_refinement(tet::MeshingOptions& options, const SceneSolid& solid,
                         const std::vector<TetRefinement>& refinements);

}  // namespace isomuscle::io
