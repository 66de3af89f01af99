#pragma once
// Dead surface loads on a tetrahedral mesh: a nominal traction t0(X, t) per unit REFERENCE area on
// a set of boundary triangles (3-node, or 6-node curved ones of a 10-node mesh),
//   f_a += int_T N_a t0(X, t) dA,   dA = |dX/dxi x dX/deta| dxi deta,
// by a conical Gauss rule on the triangle (3 x 3 points, exact to degree 4: enough for the curved
// 6-node area element with a smooth traction). Triangle node order as tet_mesh.hpp.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "tet/tet_mesh.hpp"

namespace isomuscle::tet {

struct TetSurfaceLoad {
  std::string label;       // for messages
  std::vector<int> faces;  // indices into the mesh's boundary triangles
  std::function<Eigen::Vector3d(const Eigen::Vector3d& X, double t)> traction;  // Pa
};

// Adds the loads at time t to f (3 per node, N). Throws std::invalid_argument naming the load
// when a face index is out of range, the traction function is empty or returns a non-finite value.
void add_surface_loads(const TetMesh& mesh, const std::vector<TetSurfaceLoad>& loads, double t,
                       Eigen::VectorXd& f);

// Reference area of the faces (m^2), by the same rule.
double faces_area(const TetMesh& mesh, const std::vector<int>& faces);

// The boundary triangles all of whose nodes are in `nodes` (sorted).
std::vector<int> faces_on_nodes(const TetMesh& mesh, const std::vector<int>& nodes);

}  // namespace isomuscle::tet
