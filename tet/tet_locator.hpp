#pragma once
// Point location in a tetrahedral mesh: which element holds a reference point X, and where in it
// (reference coordinates xi of the element map X(xi) = sum_a N_a(xi) X_a). Used to evaluate a
// stored tetrahedral solution at material points (comparisons with IGA runs) and by probes.
//
// Candidates come from a uniform grid of element bounding boxes (each cell lists the elements
// whose box meets it); in each candidate xi is found from the barycentric coordinates of the
// corners and, for curved 10-node elements, refined by Newton on the quadratic map. X is inside
// when every barycentric coordinate is >= -tolerance. Points just outside every element (a
// straight-sided mesh cuts chords through a curved boundary) are assigned to the element they
// are least outside of, when that is within `outside_tolerance` (a fraction of the element size).
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "tet/tet_mesh.hpp"

namespace isomuscle::tet {

struct TetLocation {
  int element = -1;
  Eigen::Vector3d xi = Eigen::Vector3d::Zero();  // reference coordinates in the element
  double outside = 0.0;  // how far outside (most negative barycentric coordinate, >= 0)
};

class TetLocator {
 public:
  // mesh must outlive the locator. outside_tolerance: barycentric amount a point may lie outside
  // its nearest element (0.05 = 5 % of the element's size).
  explicit TetLocator(const TetMesh& mesh, double outside_tolerance = 0.05);

  // The element holding X, or nullopt when X lies outside the mesh (beyond the tolerance).
  std::optional<TetLocation> locate(const Eigen::Vector3d& X) const;

  // sum_a N_a(xi) v_a over the nodes of the located element, for a nodal field (3 per node).
  Eigen::Vector3d interpolate(const TetLocation& at, const Eigen::VectorXd& nodal) const;

 private:
  // xi of X in element e (barycentric, then Newton for order 2) and its "outside" amount.
  TetLocation solve_in(int e, const Eigen::Vector3d& X) const;

  const TetMesh& mesh_;
  double outside_tolerance_;
  Eigen::Vector3d lo_, cell_size_;
  Eigen::Vector3i cells_;
  std::vector<std::vector<int>> grid_;
};

}  // namespace isomuscle::tet
