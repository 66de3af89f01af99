// Shrinking construction (thesis 5.13–5.15); see shrink.hpp.
#include "geometry/shrink.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "geometry/volume_measures.hpp"

namespace isomuscle::geometry {

namespace {

const char* direction_name(int dir) {
  return dir == 0 ? "u" : "v";
}

void check_surface_direction(int dir, const char* what) {
  if (dir != 0 && dir != 1) {
    throw std::invalid_argument(std::string(what) + ": surface direction " + std::to_string(dir) +
                                " is not 0 (u) or 1 (v)");
  }
}

double bounding_box_diagonal(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d lo = points.front();
  Eigen::Vector3d hi = points.front();
  for (const Eigen::Vector3d& x : points) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  return (hi - lo).norm();
}

// The surface with its closed direction first (u), so rows i run around the centreline.
NurbsSurface closed_direction_first(const NurbsSurface& surface, int closed_direction) {
  return closed_direction == 0 ? surface : surface.transposed();
}

// Thesis 5.13 with degree 1 in w: C_ij0 = (B_ij, w_ij), C_ij1 = (D_j, weight of D_j).
NurbsVolume build_volume(const NurbsSurface& s, const Centreline& centreline) {
  const int nu = s.count_u();
  const int nv = s.count_v();
  std::vector<Eigen::Vector3d> points;
  std::vector<double> weights;
  points.reserve(static_cast<std::size_t>(2 * nu * nv));
  weights.reserve(static_cast<std::size_t>(2 * nu * nv));
  points.insert(points.end(), s.points().begin(), s.points().end());
  weights.insert(weights.end(), s.weights().begin(), s.weights().end());
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      points.push_back(centreline.points[j]);
      weights.push_back(centreline.weights[j]);
    }
  }
  return NurbsVolume({s.knots_u(), s.knots_v(), KnotVector::clamped(1, {})}, std::move(points),
                     std::move(weights));
}

}  // namespace

int parse_surface_direction(std::string_view name) {
  if (name == "u")
    return 0;
  if (name == "v")
    return 1;
  throw std::invalid_argument("surface direction '" + std::string(name) + "' is not one of u, v");
}

SeamGap seam_gap(const NurbsSurface& surface, int dir) {
  check_surface_direction(dir, "seam_gap");
  const NurbsSurface s = closed_direction_first(surface, dir);
  const int last = s.count_u() - 1;
  SeamGap gap;
  double mean_ratio = 0.0;
  for (int j = 0; j < s.count_v(); ++j) {
    gap.distance = std::max(gap.distance, (s.point(0, j) - s.point(last, j)).norm());
    mean_ratio += s.weight(last, j) / s.weight(0, j);
  }
  mean_ratio /= s.count_v();
  for (int j = 0; j < s.count_v(); ++j) {
    gap.weight_ratio_spread =
        std::max(gap.weight_ratio_spread,
                 std::abs(s.weight(last, j) / s.weight(0, j) - mean_ratio) / mean_ratio);
  }
  const double diagonal = bounding_box_diagonal(s.points());
  gap.relative = diagonal > 0.0 ? gap.distance / diagonal : 0.0;
  return gap;
}

void require_closed(const NurbsSurface& surface, int dir, double tolerance) {
  const SeamGap gap = seam_gap(surface, dir);
  if (gap.relative <= tolerance && gap.weight_ratio_spread <= tolerance)
    return;
  std::ostringstream msg;
  msg << "surface is not closed in " << direction_name(dir) << " (first and last control rows ";
  if (gap.relative > tolerance) {
    msg << "differ by " << gap.distance << " m, " << gap.relative
        << " of the bounding-box diagonal; tolerance " << tolerance << ")";
  } else {
    msg << "coincide but their weights are not proportional, spread " << gap.weight_ratio_spread
        << ")";
  }
  msg << "; the shrink solid needs the direction around the centreline to be closed: name the "
         "other direction with --centreline, or close the surface in the CAD tool";
  throw std::invalid_argument(msg.str());
}

// Thesis 5.14 with distinct points: D^h_j = (1/m_j) sum over the m_j distinct points i of row j
// of (w_ij P_ij, w_ij). The seam duplicate (last row) is dropped; any other pair of control points
// of the row that coincide in position and weight within tolerance is counted once as well.
Centreline centreline_control_points(const NurbsSurface& surface, int closed_direction,
                                     double tolerance) {
  check_surface_direction(closed_direction, "centreline_control_points");
  require_closed(surface, closed_direction, tolerance);
  const NurbsSurface s = closed_direction_first(surface, closed_direction);
  const double tol = tolerance * bounding_box_diagonal(s.points());
  Centreline line;
  for (int j = 0; j < s.count_v(); ++j) {
    Eigen::Vector3d weighted_sum = Eigen::Vector3d::Zero();
    double weight_sum = 0.0;
    int distinct = 0;
    for (int i = 0; i + 1 < s.count_u(); ++i) {
      bool seen = false;
      for (int k = 0; k < i && !seen; ++k) {
        seen = (s.point(i, j) - s.point(k, j)).norm() <= tol &&
               std::abs(s.weight(i, j) - s.weight(k, j)) <= tolerance * s.weight(k, j);
      }
      if (seen)
        continue;
      weighted_sum += s.weight(i, j) * s.point(i, j);
      weight_sum += s.weight(i, j);
      ++distinct;
    }
    line.points.push_back(weighted_sum / weight_sum);
    line.weights.push_back(weight_sum / distinct);
    line.distinct_counts.push_back(distinct);
  }
  return line;
}

// Builds H (5.13) and fixes its orientation: the signed volume (Gauss quadrature of det J) must be
// positive; otherwise the direction around the centreline is reversed, which flips the sign of
// det J everywhere and leaves the point set, the centreline and the v and w directions unchanged.
NurbsVolume shrink_to_centreline(const NurbsSurface& surface, int closed_direction,
                                 double tolerance) {
  check_surface_direction(closed_direction, "shrink_to_centreline");
  // All control points at one place: the seam check passes trivially (no gap) and the volume
  // comes out 0; say what is wrong with the surface itself rather than with the solid.
  if (!(bounding_box_diagonal(surface.points()) > 0.0)) {
    throw std::invalid_argument("surface is degenerate: all " +
                                std::to_string(surface.points().size()) +
                                " control points coincide (zero bounding box)");
  }
  const Centreline centreline = centreline_control_points(surface, closed_direction, tolerance);
  const NurbsSurface s = closed_direction_first(surface, closed_direction);
  NurbsVolume volume = build_volume(s, centreline);
  const int points = std::max({volume.degree(0), volume.degree(1), volume.degree(2)}) + 2;
  const double signed_volume = solid_volume(volume, points);
  if (!(std::isfinite(signed_volume) && signed_volume != 0.0)) {
    std::ostringstream msg;
    msg << "shrink solid is degenerate: signed volume " << signed_volume
        << " m^3 (the surface encloses no volume around its centreline)";
    throw std::invalid_argument(msg.str());
  }
  if (signed_volume < 0.0)
    volume = build_volume(s.reversed_u(), centreline);
  return volume;
}

}  // namespace isomuscle::geometry
