// The material_ellipticity probe's columns (io/ellipticity_probe.hpp) on made-up scans: the
// smallest e over the evaluated points, how many are <= 0, and where the smallest is; points the
// law could not evaluate are left out, and a scan with none evaluated gives NaN in every column.
// The values of a real run are checked against the run's own stability assessment in
// test_run_cli.cpp (CompressedColumnReportsItsUnstableEquilibria).
#include "io/ellipticity_probe.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace isomuscle::io {
namespace {

EllipticityAt at(double e, const Eigen::Vector3d& x) {
  EllipticityAt p;
  p.smallest = e;
  p.position = x;
  return p;
}

TEST(EllipticityProbe, TheSmallestItsPlaceAndTheCountOfLostPoints) {
  EXPECT_EQ(ellipticity_probe_columns("e"),
            (std::vector<std::string>{"e", "e.not_elliptic", "e.x", "e.y", "e.z"}));
  MaterialEllipticityScan scan;
  scan.shear_modulus = 1000.0;
  scan.normals = 96;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  scan.points = {at(1500.0, {0.0, 0.0, 0.0}), at(-200.0, {0.1, 0.2, 0.3}), at(0.0, {1.0, 1.0, 1.0}),
                 at(nan, {2.0, 2.0, 2.0}), at(900.0, {3.0, 0.0, 0.0})};
  std::array<double, 5> out{};
  ellipticity_probe_values(scan, out);
  EXPECT_EQ(out[0], -200.0);
  EXPECT_EQ(out[1], 2.0);  // -200 and 0: e <= 0
  EXPECT_EQ(out[2], 0.1);
  EXPECT_EQ(out[3], 0.2);
  EXPECT_EQ(out[4], 0.3);

  // Strongly elliptic everywhere: the count is 0 and the smallest is positive.
  scan.points = {at(1500.0, {0.0, 0.0, 0.0}), at(nan, {2.0, 2.0, 2.0}), at(900.0, {3.0, 4.0, 5.0})};
  ellipticity_probe_values(scan, out);
  EXPECT_EQ(out[0], 900.0);
  EXPECT_EQ(out[1], 0.0);
  EXPECT_EQ(out[2], 3.0);
  EXPECT_EQ(out[4], 5.0);

  // Nothing evaluated (J <= 0 everywhere, say): NaN, not a made-up value.
  scan.points = {at(nan, {0.0, 0.0, 0.0})};
  ellipticity_probe_values(scan, out);
  for (const double v : out)
    EXPECT_TRUE(std::isnan(v));

  std::array<double, 4> short_row{};
  EXPECT_THROW(ellipticity_probe_values(scan, short_row), std::invalid_argument);
}

}  // namespace
}  // namespace isomuscle::io
