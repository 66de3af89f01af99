// Angles between a NURBS solid's parametric tangents, sampled, and the volume they cover.
#include "geometry/parametric_skew.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "geometry/volume_measures.hpp"

namespace isomuscle::geometry {

namespace {

// Angle between the lines along a and b, degrees in [0, 90]: the sign of a tangent is only the
// direction its parameter runs.
double line_angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double c = std::min(1.0, std::abs(a.dot(b)) / (a.norm() * b.norm()));
  return std::acos(c) * 180.0 / std::numbers::pi;
}

}  // namespace

ParametricSkew parametric_skew(const NurbsVolume& volume, int samples_per_span) {
  static constexpr int kPairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  static constexpr const char* kPairNames[3] = {"u-v", "u-w", "v-w"};
  ParametricSkew skew;
  double total = 0.0;
  std::array<double, 3> below{};
  for_each_cell_sample(
      volume, samples_per_span, "parametric_skew",
      [&](const Eigen::Vector3d& xi, const Eigen::Matrix3d& jacobian, double cell) {
        for (int d = 0; d < 3; ++d) {
          if (!(jacobian.col(d).norm() > 0.0)) {
            throw std::runtime_error("parametric_skew: the tangent along parametric direction " +
                                     std::to_string(d) + " is zero at (u, v, w) = (" +
                                     std::to_string(xi.x()) + ", " + std::to_string(xi.y()) + ", " +
                                     std::to_string(xi.z()) + ")");
          }
        }
        double smallest = 90.0;
        for (int p = 0; p < 3; ++p) {
          const double angle =
              line_angle_deg(jacobian.col(kPairs[p][0]), jacobian.col(kPairs[p][1]));
          smallest = std::min(smallest, angle);
          if (angle < skew.min_angle_deg) {
            skew.min_angle_deg = angle;
            skew.argmin = xi;
            skew.between = kPairNames[p];
          }
        }
        const double weight = std::abs(jacobian.determinant()) * cell;
        total += weight;
        for (std::size_t k = 0; k < kSkewThresholdsDeg.size(); ++k) {
          if (smallest < kSkewThresholdsDeg[k])
            below[k] += weight;
        }
        ++skew.samples;
      });
  for (std::size_t k = 0; k < below.size(); ++k)
    skew.volume_share_below[k] = total > 0.0 ? below[k] / total : 0.0;
  return skew;
}

}  // namespace isomuscle::geometry
