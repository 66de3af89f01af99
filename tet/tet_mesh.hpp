#pragma once
// A tetrahedral mesh (DESIGN "tet/"): nodes, 4- or 10-node tetrahedra, boundary triangles (3 or 6
// nodes) with tags, and the names of physical groups. Node order of a tetrahedron is gmsh's
// (positively oriented, det dX/dxi > 0):
//   corners 0, 1, 2, 3; edge nodes 4 (0-1), 5 (1-2), 6 (2-0), 7 (3-0), 8 (3-2), 9 (3-1).
// Triangles: corners 0, 1, 2; edge nodes 3 (0-1), 4 (1-2), 5 (2-0). Lengths in metres.
//
// Sources: gmsh meshing of a closed boundary given as an IGES file (tet_meshing.hpp), a user's
// .msh file (physical groups as regions), or a structured box split into tetrahedra (tests and
// convergence studies).
#include <Eigen/Core>
#include <Eigen/LU>
#include <array>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace isomuscle::tet {

struct TetMesh {
  int order = 1;                           // 1: 4-node, 2: 10-node tetrahedra
  std::vector<Eigen::Vector3d> nodes;      // m
  std::vector<int> elements;               // nodes_per_element() per tetrahedron
  std::vector<int> element_region;         // physical group (or entity) tag of each tetrahedron
  std::vector<int> boundary;               // nodes_per_face() per boundary triangle
  std::vector<int> boundary_tag;           // physical group (or entity) tag of each triangle
  std::map<int, std::string> group_names;  // physical group tag -> name (may be empty)

  int nodes_per_element() const { return order == 1 ? 4 : 10; }
  int nodes_per_face() const { return order == 1 ? 3 : 6; }
  int num_nodes() const { return static_cast<int>(nodes.size()); }
  int num_elements() const { return static_cast<int>(element_region.size()); }
  int num_boundary_faces() const { return static_cast<int>(boundary_tag.size()); }
  std::span<const int> element(int e) const {
    return {elements.data() + static_cast<std::size_t>(e) * nodes_per_element(),
            static_cast<std::size_t>(nodes_per_element())};
  }
  std::span<const int> face(int f) const {
    return {boundary.data() + static_cast<std::size_t>(f) * nodes_per_face(),
            static_cast<std::size_t>(nodes_per_face())};
  }

  // Throws std::invalid_argument naming the element/face and the problem: order not 1 or 2,
  // array sizes inconsistent, node index out of range, a corner tetrahedron with volume <= 0.
  void validate() const;
};

// Reference volume of the mesh, sum over elements of int det(dX/dxi) (exact for straight and for
// curved 10-node tetrahedra: det J of a quadratic map is of degree 6, integrated by a degree-6
// rule), m^3.
double mesh_volume(const TetMesh& mesh);

// Tag of the physical group called name; throws std::invalid_argument listing the names.
int group_tag(const TetMesh& mesh, const std::string& name);

// Sorted, unique nodes of the boundary triangles with tag.
std::vector<int> boundary_nodes(const TetMesh& mesh, int tag);

// Sorted nodes with |X[axis] - coordinate| <= tolerance (a plane selector), axis 0, 1, 2.
std::vector<int> nodes_on_plane(const TetMesh& mesh, int axis, double coordinate, double tolerance);

// The box [lo, hi] with n[d] cells per direction, each cube split into six tetrahedra around its
// main diagonal (Kuhn triangulation: conforming, all positively oriented). Order 2 adds the
// straight edge midpoints. Boundary triangles carry tags 1..6 for the faces x = lo, x = hi,
// y = lo, y = hi, z = lo, z = hi. Throws std::invalid_argument for n < 1, lo >= hi or bad order.
TetMesh structured_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                       const std::array<int, 3>& n, int order);

}  // namespace isomuscle::tet
