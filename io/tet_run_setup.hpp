#pragma once
// From a scene to a tetrahedral model ready to step (discretisation = "tet"; DESIGN "tet/"): the
// same solid as the IGA run (scene_solid.hpp), whose IGES boundary gmsh meshes into 4- or 10-node
// tetrahedra (or a user's .msh of the same shape), fibres at the quadrature points from the solid
// (the thesis's FEM-NURBS method of chapter 5: point inversion and the isocurve tangent, or the
// other fibre modes), the same material law, and the scene's boundary conditions on mesh nodes:
//
//   face u0 ... w1   the boundary nodes whose parameters in the solid (point inversion) lie on
//                    that face of the parameter cube, to 1e-6 of the domain (scene naming,
//                    SceneFrame): the ends v0, v1 of a shrink solid are the caps of the tube;
//   plane            the nodes within tolerance of the plane; at = [x, y, z]: the nodes within
//                    tolerance of the point;
//   symmetry         u . n = 0 on the selected nodes, for a plane whose normal is a coordinate
//                    axis (the constraint is then one component).
//
//   [[load]]         the traction on the boundary triangles whose nodes all lie on the face
//                    (tet/tet_surface_loads.hpp).
//
// Not offered on tetrahedra (a clear error at set-up): [geometry] extract (gmsh meshes the whole
// IGES shape), construction = "extrude" (an open sheet bounds no volume for gmsh).
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "geometry/point_inversion.hpp"
#include "io/scene.hpp"
#include "io/scene_solid.hpp"
#include "materials/material_law.hpp"
#include "tet/tet_mesh.hpp"
#include "tet/tet_problem.hpp"
#include "tet/tet_space.hpp"

namespace isomuscle::io {

// Everything a tetrahedral run keeps alive (the problem refers to the space and the law).
struct TetModel {
  SceneSolid solid;  // the unrefined solid: fibres, faces, parametric points
  std::unique_ptr<geometry::PointInverter> inverter;  // of solid.volume
  std::unique_ptr<tet::TetMesh> mesh;
  std::unique_ptr<tet::TetSpace> space;
  std::unique_ptr<materials::MaterialLaw> law;
  iga::FibreSpec fibre_spec;
  std::vector<int> boundary_nodes;           // sorted, nodes of the boundary triangles
  std::vector<Eigen::Vector3d> boundary_xi;  // their parameters in solid.volume (same order)
  std::unique_ptr<tet::TetProblem> problem;
  std::vector<std::string> notes;
  std::string failure_hint;  // appended to the reason of a failed run (empty: none)
};

// Builds the model (scene validated beforehand). Throws std::runtime_error /
// std::invalid_argument naming the setting at fault.
TetModel build_tet_model(const Scene& scene, int threads);

// The mesh nodes a selector picks (see the header); std::invalid_argument naming `what` when the
// selection is empty.
std::vector<int> selected_tet_nodes(const TetModel& model, const FaceSelector& where,
                                    const std::string& what);

}  // namespace isomuscle::io
