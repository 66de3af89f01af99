// Linear sweep of a surface (Piegl & Tiller §8.4); see extrusion.hpp.
#include "geometry/extrusion.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "geometry/volume_measures.hpp"

namespace isomuscle::geometry {

namespace {

// H = B + w d with degree 1 in w (extrusion.hpp).
NurbsVolume sweep(const NurbsSurface& s, const Eigen::Vector3d& d) {
  std::vector<Eigen::Vector3d> points(s.points());
  std::vector<double> weights(s.weights());
  for (const Eigen::Vector3d& p : s.points())
    points.push_back(p + d);
  weights.insert(weights.end(), s.weights().begin(), s.weights().end());
  return NurbsVolume({s.knots_u(), s.knots_v(), KnotVector::clamped(1, {})}, std::move(points),
                     std::move(weights));
}

}  // namespace

// Orientation as in shrink_to_centreline: a negative signed volume reverses u. A solid whose
// Jacobian changes sign is rejected: its signed volume differs from the volume of |det J|.
Extrusion extrude(const NurbsSurface& surface, const Eigen::Vector3d& d) {
  if (!d.allFinite() || !(d.norm() > 0.0)) {
    std::ostringstream msg;
    msg << "extrusion vector (" << d.x() << ", " << d.y() << ", " << d.z()
        << ") m must be finite and non-zero";
    throw std::invalid_argument(msg.str());
  }
  Extrusion out;
  out.volume = sweep(surface, d);
  const int points = std::max({out.volume.degree(0), out.volume.degree(1)}) + 2;
  const double signed_volume = solid_volume(out.volume, points);
  if (signed_volume < 0.0) {
    out.volume = sweep(surface.reversed_u(), d);
    out.u_reversed = true;
  }
  const JacobianRange range = jacobian_range(out.volume, 4);
  if (!std::isfinite(signed_volume) || range.non_positive > 0) {
    std::ostringstream msg;
    msg << "extruded solid is degenerate: det J <= 0 at " << range.non_positive << " of "
        << range.samples << " sample points (smallest " << range.min << " at (u, v, w) = ("
        << range.argmin.x() << ", " << range.argmin.y() << ", " << range.argmin.z()
        << ")): the extrusion vector lies in the tangent plane of the surface there";
    throw std::invalid_argument(msg.str());
  }
  return out;
}

}  // namespace isomuscle::geometry
