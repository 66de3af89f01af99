// Extruded solids H = B(u, v) + w d (geometry/extrusion.hpp): the surface kept exactly at w = 0
// and moved by d at w = 1, volume = area x thickness, orientation fixed by reversing u, degenerate
// sweeps rejected.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geometry/extrusion.hpp"
#include "geometry/shapes.hpp"
#include "geometry/volume_measures.hpp"

namespace isomuscle::geometry {
namespace {

// Cook's panel: a trapezoid of area 48 (44 + 16) / 2 = 1440.
constexpr double kCookArea = 1440.0;

TEST(Extrusion, CookPanelIsAPlateOfAreaTimesThickness) {
  const NurbsSurface panel = cook_membrane_surface();
  const Extrusion plate = extrude(panel, {0.0, 0.0, 2.5});
  EXPECT_FALSE(plate.u_reversed);
  EXPECT_NEAR(solid_volume(plate.volume, 3), 2.5 * kCookArea, 1e-10 * kCookArea);
  EXPECT_NEAR(solid_volume_from_boundary(plate.volume, 3), 2.5 * kCookArea, 1e-10 * kCookArea);
  for (double u : {0.0, 0.3, 1.0}) {
    for (double v : {0.0, 0.7, 1.0}) {
      const Eigen::Vector3d x = panel.evaluate(u, v);
      EXPECT_LT((plate.volume.evaluate({u, v, 0.0}) - x).norm(), 1e-13);
      EXPECT_LT((plate.volume.evaluate({u, v, 1.0}) - x - Eigen::Vector3d(0, 0, 2.5)).norm(),
                1e-13);
      // The w isocurve is the straight sweep: dH/dw = d.
      EXPECT_LT((plate.volume.jacobian({u, v, 0.5}).col(2) - Eigen::Vector3d(0, 0, 2.5)).norm(),
                1e-13);
    }
  }
}

// Sweeping against the surface normal gives det J < 0: u is reversed, the points are the same.
TEST(Extrusion, SweepAgainstTheNormalReversesU) {
  const NurbsSurface panel = cook_membrane_surface();
  const Extrusion plate = extrude(panel, {0.0, 0.0, -1.0});
  EXPECT_TRUE(plate.u_reversed);
  EXPECT_NEAR(solid_volume(plate.volume, 3), kCookArea, 1e-10 * kCookArea);
  const JacobianRange range = jacobian_range(plate.volume, 3);
  EXPECT_EQ(range.non_positive, 0);
  EXPECT_LT((plate.volume.evaluate({0.2, 0.6, 0.0}) - panel.evaluate(0.8, 0.6)).norm(), 1e-13);
}

// A rational sheet stays exact: the quarter disc of radius 1 in the xy plane (a rational quadratic
// arc, weights 1, sqrt(1/2), 1) extruded by 0.1 has the volume pi/4 * 0.1 to quadrature accuracy.
TEST(Extrusion, RationalSheetKeepsItsExactArea) {
  const double s = std::sqrt(0.5);
  // u: the quarter arc from (1, 0) to (0, 1) (rational quadratic), v: from the origin to the arc.
  const KnotVector arc = KnotVector::clamped(2, {});
  const KnotVector radial = KnotVector::clamped(1, {});
  std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0},
                                         {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  std::vector<double> weights = {1.0, s, 1.0, 1.0, s, 1.0};
  const NurbsSurface quarter(arc, radial, points, weights);
  const Extrusion slab = extrude(quarter, {0.0, 0.0, 0.1});
  const VolumeEstimate v = converged_solid_volume(slab.volume);
  EXPECT_NEAR(v.volume, std::numbers::pi / 4.0 * 0.1, 1e-12);
}

TEST(Extrusion, DegenerateSweepsAreRejected) {
  const NurbsSurface panel = cook_membrane_surface();
  EXPECT_THROW(extrude(panel, {0.0, 0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(extrude(panel, {0.0, 0.0, std::nan("")}), std::invalid_argument);
  try {
    extrude(panel, {1.0, 0.0, 0.0});  // in the plane of the panel: no volume
    FAIL() << "an in-plane sweep must be rejected";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("degenerate"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace isomuscle::geometry
