#include "tet/curved_tet_repair.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <limits>
#include <vector>

#include "tet/tet_elements.hpp"

namespace isomuscle::tet {

namespace {

// Corners of each edge node 4..9, in gmsh's order (tet_mesh.hpp).
constexpr int kEdgeCorners[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};

double straight_determinant(const TetMesh& mesh, std::span<const int> el) {
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c)
    J.col(c) = mesh.nodes[el[c + 1]] - mesh.nodes[el[0]];
  return J.determinant();
}

}  // namespace

double smallest_scaled_jacobian(const TetMesh& mesh, int e, const TetRule& rule) {
  if (mesh.order != 2)
    return 1.0;
  const std::span<const int> el = mesh.element(e);
  const double straight = straight_determinant(mesh, el);
  std::array<Eigen::Vector3d, 10> dN;
  double smallest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& xi : rule.points) {
    tet_shape_gradients(2, xi, dN.data());
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
    for (int a = 0; a < 10; ++a)
      J += mesh.nodes[el[a]] * dN[a].transpose();
    smallest = std::min(smallest, J.determinant() / straight);
  }
  return smallest;
}

int straighten_folded_elements(TetMesh& mesh, const TetRule& rule, double threshold) {
  if (mesh.order != 2)
    return 0;
  std::vector<bool> straightened(mesh.num_elements(), false);
  int count = 0;
  // A straightened element stays straight (its neighbours can only move its edge nodes to the
  // same midpoints), so each pass either straightens a new element or ends the loop.
  for (bool changed = true; changed;) {
    changed = false;
    for (int e = 0; e < mesh.num_elements(); ++e) {
      if (straightened[e] || smallest_scaled_jacobian(mesh, e, rule) >= threshold)
        continue;
      const std::span<const int> el = mesh.element(e);
      for (int k = 0; k < 6; ++k) {
        mesh.nodes[el[4 + k]] =
            0.5 * (mesh.nodes[el[kEdgeCorners[k][0]]] + mesh.nodes[el[kEdgeCorners[k][1]]]);
      }
      straightened[e] = true;
      ++count;
      changed = true;
    }
  }
  return count;
}

}  // namespace isomuscle::tet
