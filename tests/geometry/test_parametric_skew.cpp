// The angles between a solid's parametric tangents (geometry/parametric_skew.hpp): exact on a
// sheared parallelepiped, right angles on a box, and the DAO shrink solid's flat jaw section.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "geometry/parametric_skew.hpp"
#include "geometry/shapes.hpp"
#include "geometry/shrink.hpp"

namespace isomuscle::geometry {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// The trilinear solid spanned by edges a, b, c from the origin (one knot span each way).
NurbsVolume parallelepiped(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c) {
  const KnotVector linear({0.0, 0.0, 1.0, 1.0}, 1);
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        points.push_back(i * a + j * b + k * c);
  return NurbsVolume({linear, linear, linear}, points, std::vector<double>(8, 1.0));
}

TEST(ParametricSkew, BoxMeetsAtRightAngles) {
  const ParametricSkew s = parametric_skew(parallelepiped({2, 0, 0}, {0, 1, 0}, {0, 0, 3}), 3);
  EXPECT_NEAR(s.min_angle_deg, 90.0, 1e-12);
  EXPECT_EQ(s.samples, 27);
  for (const double share : s.volume_share_below)
    EXPECT_EQ(share, 0.0);
}

// Edges u and v 20 degrees apart, w normal to both: every sample has 20 degrees between u and v,
// whichever way the parameters run.
TEST(ParametricSkew, ShearedParallelepipedHasItsEdgeAngle) {
  const double alpha = 20.0 * kDegree;
  const ParametricSkew s = parametric_skew(
      parallelepiped({1, 0, 0}, {-std::cos(alpha), -std::sin(alpha), 0}, {0, 0, 1}), 2);
  EXPECT_NEAR(s.min_angle_deg, 20.0, 1e-10);
  EXPECT_EQ(s.between, "u-v");
  EXPECT_EQ(s.volume_share_below[0], 0.0);           // not below 15 degrees
  EXPECT_NEAR(s.volume_share_below[1], 1.0, 1e-15);  // all below 30
  EXPECT_NEAR(s.volume_share_below[2], 1.0, 1e-15);
}

// The DAO's sections are ellipses of semi-axes a_j x b_j, 15 x 1 mm at the jaw (v = 0). On the
// surface (w = 0) the radial direction w runs from the ellipse to its centre, so it meets the
// ring around, the ellipse's tangent, at asin(2ab / (a^2 + b^2)) = 7.63 degrees in the middle of
// each quadrant (u = 1/8: the rational quarter ellipse's middle lies at 45 degrees of the unit
// circle). Inside, the rational shrink construction (homogeneous averages, thesis 5.14) bends
// the rings, and the sampled minimum lies near the jaw, between u and w; the rounder sections
// further up are far less skewed. Measured: 8.06 degrees, 28 % of the volume below 15 degrees.
TEST(ParametricSkew, DaoJawSectionIsSkewedBetweenAroundAndRadial) {
  const NurbsVolume solid = shrink_to_centreline(depressor_anguli_oris(), 0);
  const Eigen::Matrix3d j = solid.jacobian(Eigen::Vector3d(0.125, 0.0, 0.0));
  const double on_surface =
      std::acos(std::abs(j.col(0).dot(j.col(2))) / (j.col(0).norm() * j.col(2).norm()));
  EXPECT_NEAR(on_surface, std::asin(2.0 * 15.0 * 1.0 / (15.0 * 15.0 + 1.0)), 1e-9);

  const ParametricSkew s = parametric_skew(solid, 6);
  EXPECT_LT(s.min_angle_deg, 10.0);
  EXPECT_EQ(s.between, "u-w");
  EXPECT_LT(s.argmin.y(), 0.1);  // near the jaw
  EXPECT_GT(s.volume_share_below[0], 0.1);
  EXPECT_LT(s.volume_share_below[0], s.volume_share_below[1]);
  EXPECT_LE(s.volume_share_below[1], s.volume_share_below[2]);
}

// The barrel's sections are circles: no angle below 45 degrees anywhere.
TEST(ParametricSkew, BarrelIsNotSkewed) {
  const ParametricSkew s =
      parametric_skew(shrink_to_centreline(barrel(0.05, 0.0045, 0.00875), 0), 6);
  EXPECT_GT(s.min_angle_deg, 60.0);
  for (const double share : s.volume_share_below)
    EXPECT_EQ(share, 0.0);
}

TEST(ParametricSkew, RejectsSampleCountsOutOfRange) {
  const NurbsVolume box = parallelepiped({1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  EXPECT_THROW(parametric_skew(box, 0), std::invalid_argument);
  EXPECT_THROW(parametric_skew(box, 101), std::invalid_argument);
}

}  // namespace
}  // namespace isomuscle::geometry
