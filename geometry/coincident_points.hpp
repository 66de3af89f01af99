#pragma once
// Coincident control points of a NURBS solid. The shrinking construction (thesis 5.13–5.15) makes
// two kinds: the first and last rows of a closed clamped direction (the seam) and every control
// point of a row collapsed onto the centreline. They are one physical point each, so the IGA DOF
// map must merge them (SPEC §1, DESIGN "coincidence checked geometrically, always"). Found here by
// geometry alone, with a tolerance relative to the bounding box, by spatial hashing (expected
// O(n), not O(n^2)).
#include <Eigen/Core>
#include <vector>

#include "geometry/nurbs_volume.hpp"

namespace isomuscle::geometry {

struct CoincidentPoints {
  // For every point: the index of the lowest-numbered point of its group (itself when alone).
  std::vector<int> representative;
  // For every point: its group numbered 0..num_distinct-1 in order of first appearance.
  std::vector<int> group;
  int num_distinct = 0;
};

// Groups points closer than relative_tolerance * (diagonal of their bounding box), transitively.
// relative_tolerance must lie in [0, 1e-3] (std::invalid_argument otherwise); 0 groups only
// exactly equal points. Points must be finite.
CoincidentPoints find_coincident_points(const std::vector<Eigen::Vector3d>& points,
                                        double relative_tolerance = 1e-8);

// The same for the control points of a volume (index i + n_u (j + n_v k)).
CoincidentPoints find_coincident_points(const NurbsVolume& volume,
                                        double relative_tolerance = 1e-8);

}  // namespace isomuscle::geometry
