#pragma once
// Point inversion on a NURBS solid: find xi = (u, v, w) in the parametric box with H(xi) = x
// (thesis 5.13; needed to sample the NURBS fibre field at points of a tetrahedral mesh, thesis
// 5.27–5.30). Start from the nearest of a grid of sample points (a few per knot span), then a
// bound-constrained Newton iteration on r(xi) = H(xi) - x: the full Newton step when the Jacobian
// is regular and the step reduces |r|, otherwise a Levenberg–Marquardt step on the free
// components (robust next to a collapsed face where det J -> 0), each trial projected onto the
// domain (or carried across a closed seam, detected geometrically) and accepted only if |r|
// decreases. Several starts are tried, and a restart off a collapsed face where a start got
// stuck, until one converges (|r| <= 1000 tolerance size) or the starts are used up.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "geometry/nurbs_volume.hpp"

namespace isomuscle::geometry {

struct InversionOptions {
  int samples_per_span = 2;            // start grid: points per knot span and direction, >= 1
  int max_samples_per_direction = 24;  // cap per direction (then evenly spaced), >= 1
  int max_iterations = 50;             // per start, >= 1
  int max_starts = 4;                  // nearest samples tried in turn, >= 1
  double tolerance = 1e-14;            // stop when |H(xi) - x| <= tolerance * size, > 0
  double inside_tolerance = 1e-9;      // inside iff |H(xi) - x| <= inside_tolerance * size, > 0
  // Throws std::invalid_argument naming the offending field and its valid range.
  void validate() const;
};

struct InversionResult {
  bool inside = false;    // distance <= inside_tolerance * size
  Eigen::Vector3d xi;     // best parameters found (closest point when outside)
  double distance = 0.0;  // |H(xi) - x|, length units of the control points
  int iterations = 0;     // Newton iterations over all starts
};

class PointInverter {
 public:
  // Copies the volume and precomputes the start grid.
  explicit PointInverter(const NurbsVolume& volume, InversionOptions options = {});

  // Throws std::invalid_argument when x is not finite.
  InversionResult invert(const Eigen::Vector3d& x) const;

  // Bounding-box diagonal of the control points: the length scale of the tolerances.
  double size() const { return size_; }
  const NurbsVolume& volume() const { return volume_; }
  // Whether direction d was detected as a closed seam (faces xi_d = begin and xi_d = end coincide);
  // the iteration then continues across the seam instead of stopping at it.
  bool closed(int d) const { return closed_[static_cast<std::size_t>(d)]; }

 private:
  InversionResult solve_from(const Eigen::Vector3d& x, Eigen::Vector3d xi) const;
  bool collapsed_face_restart(const Eigen::Vector3d& x, const Eigen::Vector3d& xi,
                              Eigen::Vector3d& start) const;

  NurbsVolume volume_;
  InversionOptions options_;
  Eigen::Vector3d lo_, hi_;  // parametric box
  Eigen::Vector3d box_lo_, box_hi_;
  double size_ = 0.0;
  std::vector<Eigen::Vector3d> sample_xi_;
  std::vector<Eigen::Vector3d> sample_x_;
  std::array<std::vector<double>, 3> scan_;
  std::array<bool, 3> closed_ = {false, false,
                                 false};  // parameters scanned along a collapsed direction
};

// One-off convenience (builds the start grid each call; use PointInverter for many points).
InversionResult invert_point(const NurbsVolume& volume, const Eigen::Vector3d& x,
                             const InversionOptions& options = {});

}  // namespace isomuscle::geometry
