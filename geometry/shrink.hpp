#pragma once
// Shrinking construction of a NURBS solid from a closed boundary surface (thesis 5.13–5.15, after
// Ma, Lin & Chua 2001; SPEC §1). The surface B(u,v) is closed in one parametric direction (around
// the centreline); the other direction runs along the centreline. The solid
//   H(u,v,w) = sum_ijk N_i(u) N_j(v) N_k(w) C^h_ijk   (homogeneous, projected as in 5.15)
// has degree 1 in w, C^h_ij0 = B^h_ij (w = 0 is the surface) and C^h_ij1 = D_j (w = 1 collapses
// onto the centreline), where D_j is the mean of the DISTINCT homogeneous control points of row j
// (5.14 with the seam point counted once: averaging it twice would move the centreline off the
// centre, SPEC pitfall).
//
// Volume layout: direction 0 goes around the centreline (the surface's closed direction, reversed
// where needed so that det J > 0), direction 1 runs along the centreline (same sense as in the
// surface), direction 2 is w.
#include <Eigen/Core>
#include <string_view>
#include <vector>

#include "geometry/nurbs_surface.hpp"
#include "geometry/nurbs_volume.hpp"

namespace isomuscle::geometry {

inline constexpr int kAroundCentreline = 0;
inline constexpr int kAlongCentreline = 1;
inline constexpr int kTowardsCentreline = 2;

// Seam tolerance, relative to the bounding-box diagonal of the control net: IGES files carry
// coordinates with as few as 9 significant digits.
inline constexpr double kDefaultClosureTolerance = 1e-7;

// "u" | "v" -> 0 | 1; throws std::invalid_argument naming the valid choices.
int parse_surface_direction(std::string_view name);

// Largest distance (metres) between corresponding control points of the first and last rows in
// direction dir (0 = u: rows i = 0 and n_u - 1), and the same relative to the bounding-box
// diagonal.
struct SeamGap {
  double distance = 0.0;
  double relative = 0.0;
  double weight_ratio_spread = 0.0;  // max |w_last / w_first - mean ratio| / mean ratio
};
SeamGap seam_gap(const NurbsSurface& surface, int dir);

// Throws std::invalid_argument "surface is not closed in u (first and last control rows differ by
// ... m, ... of the bounding-box diagonal) ..." unless the seam gap and the spread of the weight
// ratios are within tolerance.
void require_closed(const NurbsSurface& surface, int dir,
                    double tolerance = kDefaultClosureTolerance);

// The centreline control points D_j of thesis 5.14: for each row j of the direction along the
// centreline, the mean of the distinct homogeneous control points (w P, w) of the closed
// direction. Cartesian point sum w P / sum w and weight mean w over the distinct points.
struct Centreline {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> weights;
  std::vector<int> distinct_counts;  // how many distinct control points row j averages
};
Centreline centreline_control_points(const NurbsSurface& surface, int closed_direction,
                                     double tolerance = kDefaultClosureTolerance);

// The shrink solid (see above). closed_direction is the surface's parametric direction that
// closes around the centreline (0 = u, 1 = v); the other one runs along the centreline. Throws
// std::invalid_argument when closed_direction is not 0 or 1, the surface is not closed in it, or
// the solid is degenerate (zero volume).
NurbsVolume shrink_to_centreline(const NurbsSurface& surface, int closed_direction,
                                 double tolerance = kDefaultClosureTolerance);

}  // namespace isomuscle::geometry
