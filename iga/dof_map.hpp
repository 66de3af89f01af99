#pragma once
// Degrees of freedom of the IGA space: one displacement DOF set (3 components) per DISTINCT
// physical control point. The control points of a closed seam (the first and last row of a closed
// clamped surface) and every row collapsed onto the centreline by the shrinking construction
// (thesis 5.13–5.15) are the same physical point; without merging their DOFs the discrete field
// can tear along the seam and the axis (SPEC §1 "Consequences for analysis"). Coincidence is
// checked geometrically, always (DESIGN line 6): points within tol * (bounding-box diagonal) are
// one node, and a given grouping is verified against the same test.
//
// DOF numbering ("all" numbering, before Dirichlet conditions): dof(node, c) = 3 node + c.
#include <Eigen/Core>
#include <span>
#include <vector>

#include "geometry/nurbs_volume.hpp"

namespace isomuscle::iga {

class DofMap {
 public:
  DofMap() = default;
  // Merges geometrically coincident control points of `volume`. relative_tolerance is a fraction
  // of the bounding-box diagonal of the control net; throws std::invalid_argument when it is not
  // in [0, 1e-3].
  explicit DofMap(const geometry::NurbsVolume& volume, double relative_tolerance = 1e-8);
  // One node per control point: no merging (for demonstrations that the field then tears).
  static DofMap unmerged(const geometry::NurbsVolume& volume);
  // A given grouping (node of every control point, nodes numbered 0..n-1 without gaps); throws
  // std::invalid_argument naming the control points when two points of a node are farther apart
  // than relative_tolerance times the bounding-box diagonal, or the numbering has gaps.
  DofMap(const geometry::NurbsVolume& volume, std::vector<int> node_of_control_point,
         double relative_tolerance = 1e-8);

  int num_nodes() const { return static_cast<int>(node_start_.size()) - 1; }
  int num_dofs() const { return 3 * num_nodes(); }
  int num_control_points() const { return static_cast<int>(node_of_.size()); }
  int node(int control_point) const { return node_of_[control_point]; }
  static int dof(int node, int component) { return 3 * node + component; }
  // Control points merged into `node`, ascending.
  std::span<const int> control_points(int node) const {
    return {members_.data() + node_start_[node],
            static_cast<std::size_t>(node_start_[node + 1] - node_start_[node])};
  }
  // Reference position of the node (its first control point).
  const Eigen::Vector3d& position(int node) const { return positions_[node]; }
  // Number of nodes holding more than one control point.
  int num_merged_nodes() const;

 private:
  void build(const geometry::NurbsVolume& volume, std::vector<int> node_of_control_point,
             double relative_tolerance);

  std::vector<int> node_of_;
  std::vector<int> node_start_{0};
  std::vector<int> members_;
  std::vector<Eigen::Vector3d> positions_;
};

}  // namespace isomuscle::iga
