#pragma once
// How far a NURBS solid's parametric directions are from meeting at right angles: the skew of the
// map H(u,v,w), the isogeometric counterpart of a finite-element mesh's element-angle check. The
// elements are the map's knot spans, so every refinement keeps these angles; only the solid's
// construction sets them. A shrink solid (thesis 5.13-5.15) of a flat section is the case that
// needs it: on its surface a radial line towards the centreline meets the ring around at
// asin(2ab / (a^2 + b^2)) in the middle of each quadrant of an ellipse of semi-axes a, b (7.6
// degrees for the DAO's 15 x 1 mm jaw section), so over most of a flat section both directions
// run across its width and its thickness is resolved only by the small difference between them
// (`isomuscle geometry solid` reports the DAO's smallest angle, 8.1 degrees sampled, and 28 % of
// its volume below 15 degrees).
#include <Eigen/Core>
#include <array>
#include <string>

#include "geometry/nurbs_volume.hpp"

namespace isomuscle::geometry {

struct ParametricSkew {
  // Smallest angle (degrees, in [0, 90]) between two of the tangents dH/du, dH/dv, dH/dw over the
  // samples, where (u, v, w) and between which two ("u-w", ...).
  double min_angle_deg = 90.0;
  Eigen::Vector3d argmin = Eigen::Vector3d::Zero();
  std::string between;
  // Share of the solid's volume (samples weighted by det J times their parametric cell) whose
  // smallest angle is below kSkewThresholdsDeg[k].
  std::array<double, 3> volume_share_below{};
  int samples = 0;
};

inline constexpr std::array<double, 3> kSkewThresholdsDeg{15.0, 30.0, 45.0};

// On jacobian_range's cell-centred grid (samples_per_span^3 points per knot span, none on a span
// boundary, so none where a collapsed axis makes a tangent vanish). Throws std::invalid_argument
// unless 1 <= samples_per_span <= 100, and std::runtime_error when a sampled tangent is zero.
ParametricSkew parametric_skew(const NurbsVolume& volume, int samples_per_span);

}  // namespace isomuscle::geometry
