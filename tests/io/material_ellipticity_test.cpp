// assess_material_ellipticity and its log line on made-up scans: points where the law lost strong
// ellipticity are counted and the smallest named; points that could not be evaluated are counted
// apart; "near the mode" takes the points within the mode's radius of its peak, or the nearest
// point when the radius holds none; without a mode there is no such part; a scan with no point
// evaluated is an error.
#include "io/material_ellipticity.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace isomuscle::io {
namespace {

EllipticityAt at(double e, double x) {
  EllipticityAt p;
  p.smallest = e;
  p.position = Eigen::Vector3d(x, 0.0, 0.0);
  return p;
}

UnstableMode mode_at(double x, double radius) {
  UnstableMode m;
  m.ok = true;
  m.peak_position = Eigen::Vector3d(x, 0.0, 0.0);
  m.radius = radius;
  return m;
}

TEST(MaterialEllipticity, CountsLossNamesTheSmallestAndLooksNearTheMode) {
  MaterialEllipticityScan scan;
  scan.shear_modulus = 1000.0;
  scan.normals = 96;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  scan.points = {at(1500.0, 0.0), at(-200.0, 1.0), at(0.0, 2.0),   at(nan, 3.0),
                 at(900.0, 4.0),  at(1100.0, 5.0), at(1300.0, 6.0)};

  const UnstableMode mode = mode_at(5.2, 1.5);
  const MaterialEllipticity e = assess_material_ellipticity(scan, &mode);
  EXPECT_EQ(e.points, 7u);
  EXPECT_EQ(e.not_evaluated, 1u);
  EXPECT_EQ(e.not_elliptic, 2u);  // e <= 0: -200 and 0
  EXPECT_EQ(e.smallest.smallest, -200.0);
  EXPECT_EQ(e.smallest.position.x(), 1.0);
  ASSERT_TRUE(e.near_mode);
  EXPECT_EQ(e.radius, 1.5);
  EXPECT_EQ(e.near_mode_points, 3u);  // x = 4, 5, 6
  EXPECT_EQ(e.smallest_near_mode.smallest, 900.0);
  const std::string text = describe(e);
  EXPECT_NE(text.find("lost strong ellipticity at 2 of 6 quadrature points"), std::string::npos)
      << text;
  EXPECT_NE(text.find("-0.2 mu at (1, 0, 0) m"), std::string::npos) << text;
  EXPECT_NE(text.find("0.9 mu within 1.5 m of the mode's peak"), std::string::npos) << text;
  EXPECT_NE(text.find("1 points could not be evaluated"), std::string::npos) << text;

  // A radius that holds no point: the nearest one stands for the mode's site.
  const UnstableMode narrow = mode_at(3.4, 0.1);
  const MaterialEllipticity n = assess_material_ellipticity(scan, &narrow);
  EXPECT_DOUBLE_EQ(n.radius, 0.6);  // to x = 4 (x = 3 was not evaluated)
  EXPECT_EQ(n.near_mode_points, 1u);
  EXPECT_EQ(n.smallest_near_mode.smallest, 900.0);

  // All elliptic, no mode.
  scan.points = {at(1500.0, 0.0), at(800.0, 1.0)};
  const MaterialEllipticity ok = assess_material_ellipticity(scan, nullptr);
  EXPECT_EQ(ok.not_elliptic, 0u);
  EXPECT_FALSE(ok.near_mode);
  EXPECT_NE(describe(ok).find("strongly elliptic at all 2 quadrature points (smallest isochoric "
                              "wave stiffness 0.8 mu at (1, 0, 0) m): the instability is "
                              "structural"),
            std::string::npos)
      << describe(ok);
  UnstableMode failed;
  EXPECT_FALSE(assess_material_ellipticity(scan, &failed).near_mode);

  scan.points = {at(nan, 0.0)};
  EXPECT_THROW(assess_material_ellipticity(scan, &mode), std::invalid_argument);
}

}  // namespace
}  // namespace isomuscle::io
