// Example shapes (SPEC §5): exact circles, surfaces on their analytic shapes, DAO dimensions.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "geometry/nurbs_curve.hpp"
#include "geometry/shapes.hpp"

namespace isomuscle::geometry {
namespace {

NurbsCurve as_curve(const PlanarCurve& c) {
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector2d& p : c.points)
    points.emplace_back(p.x(), p.y(), 0.0);
  return NurbsCurve(c.knots, points, c.weights);
}

class ShapesCircle : public ::testing::TestWithParam<CircleForm> {};

TEST_P(ShapesCircle, UnitCircleIsExactAndClosed) {
  const PlanarCurve circle = unit_circle(GetParam());
  EXPECT_EQ(circle.points.size(), GetParam() == CircleForm::kNinePoint ? 9u : 7u);
  EXPECT_EQ(circle.knots.degree(), 2);
  EXPECT_TRUE(circle.knots.is_clamped());
  EXPECT_EQ(circle.points.front(), circle.points.back());
  const NurbsCurve curve = as_curve(circle);
  double worst = 0.0;
  double previous_angle = -1.0;
  for (int k = 0; k <= 1000; ++k) {
    const Eigen::Vector3d x = curve.evaluate(k / 1000.0);
    worst = std::max(worst, std::abs(x.norm() - 1.0));
    // Counter-clockwise: the angle increases monotonically over [0, 2 pi).
    double angle = std::atan2(x.y(), x.x());
    if (angle < 0.0)
      angle += 2.0 * std::numbers::pi;
    if (k > 0 && k < 1000) {
      EXPECT_GT(angle, previous_angle) << "at t = " << k / 1000.0;
    }
    previous_angle = angle;
  }
  EXPECT_LT(worst, 1e-15);
}

INSTANTIATE_TEST_SUITE_P(BothForms, ShapesCircle,
                         ::testing::Values(CircleForm::kNinePoint, CircleForm::kSevenPoint));

TEST(Shapes, HalfCircleRunsOverTheUpperHalf) {
  const NurbsCurve arc = as_curve(unit_half_circle());
  EXPECT_LT((arc.evaluate(0.0) - Eigen::Vector3d(1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((arc.evaluate(0.5) - Eigen::Vector3d(0, 1, 0)).norm(), 1e-15);
  EXPECT_LT((arc.evaluate(1.0) - Eigen::Vector3d(-1, 0, 0)).norm(), 1e-15);
  for (int k = 0; k <= 100; ++k) {
    const Eigen::Vector3d x = arc.evaluate(k / 100.0);
    EXPECT_NEAR(x.norm(), 1.0, 1e-15);
    EXPECT_GE(x.y(), -1e-16);
  }
}

TEST(Shapes, ConeFrustumLiesOnItsCone) {
  const double rb = 0.02, rt = 0.004, h = 0.05;
  const NurbsSurface s = cone_frustum(rb, rt, h);
  EXPECT_TRUE(s.is_closed(0));
  EXPECT_FALSE(s.is_closed(1));
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const double u = unit(rng), v = unit(rng);
    const Eigen::Vector3d x = s.evaluate(u, v);
    EXPECT_NEAR(x.z(), h * v, 1e-16) << "the profile is linearly parametrised";
    EXPECT_NEAR(std::hypot(x.x(), x.y()), rb + (rt - rb) * x.z() / h, 1e-16);
  }
}

TEST(Shapes, BarrelFollowsItsParabola) {
  const double L = 0.05, re = 0.0045, rm = 0.00875;
  const NurbsSurface s = barrel(L, re, rm);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const double u = unit(rng), v = unit(rng);
    const Eigen::Vector3d x = s.evaluate(u, v);
    const double t = x.z() / L;
    EXPECT_NEAR(x.z(), L * v, 1e-16);
    EXPECT_NEAR(std::hypot(x.x(), x.y()), re + 4.0 * (rm - re) * t * (1.0 - t), 1e-16);
  }
  EXPECT_NEAR(std::hypot(s.evaluate(0.3, 0.5).x(), s.evaluate(0.3, 0.5).y()), rm, 1e-16);
  // The closed form against a fine midpoint sum of pi r(z)^2.
  double sum = 0.0;
  const int n = 200000;
  for (int k = 0; k < n; ++k) {
    const double t = (k + 0.5) / n;
    const double r = re + 4.0 * (rm - re) * t * (1.0 - t);
    sum += std::numbers::pi * r * r * L / n;
  }
  EXPECT_NEAR(barrel_volume(L, re, rm) / sum, 1.0, 1e-10);
}

TEST(Shapes, TorusAndHalfTorusLieOnTheirTorus) {
  const double R = 0.013, r = 0.004;
  const NurbsSurface whole = torus(R, r);
  const NurbsSurface half = half_torus(R, r);
  EXPECT_TRUE(whole.is_closed(0));
  EXPECT_TRUE(whole.is_closed(1));
  EXPECT_TRUE(half.is_closed(0));
  EXPECT_FALSE(half.is_closed(1));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const double u = unit(rng), v = unit(rng);
    for (const NurbsSurface* s : {&whole, &half}) {
      const Eigen::Vector3d x = s->evaluate(u, v);
      const double rho = std::hypot(x.x(), x.y());
      EXPECT_NEAR(std::hypot(rho - R, x.z()), r, 1e-16);
    }
    EXPECT_GE(half.evaluate(u, v).y(), -1e-16);
  }
  // v runs around the ring: the tube centre moves from +x through +y to -x for the half torus.
  EXPECT_GT(half.evaluate(0.0, 0.0).x(), 0.0);
  EXPECT_GT(half.evaluate(0.0, 0.5).y(), 0.0);
  EXPECT_LT(half.evaluate(0.0, 1.0).x(), 0.0);
  EXPECT_NEAR(torus_volume(R, r), 2.0 * std::numbers::pi * R * std::numbers::pi * r * r, 1e-20);
}

// DAO stand-in dimensions (README): length about 3.5 cm, base 3.0 cm wide and 2 mm thick, top
// 6 mm wide and 4 mm thick; the end sections are exact ellipses.
TEST(Shapes, DepressorAnguliOrisHasTheDesignedDimensions) {
  const NurbsSurface s = depressor_anguli_oris();
  EXPECT_TRUE(s.is_closed(0));
  const auto section_extent = [&](double v) {
    double width = 0.0, thickness = 1e9;
    // Opposite points u and u + 1/2 of the nine-point circle are symmetric about the centre.
    for (int k = 0; k < 400; ++k) {
      const double u = k / 800.0;
      const double d = (s.evaluate(u, v) - s.evaluate(u + 0.5, v)).norm();
      width = std::max(width, d);
      thickness = std::min(thickness, d);
    }
    return std::make_pair(width, thickness);
  };
  const auto [base_width, base_thickness] = section_extent(0.0);
  const auto [top_width, top_thickness] = section_extent(1.0);
  EXPECT_NEAR(base_width, 0.030, 1e-6);
  EXPECT_NEAR(base_thickness, 0.002, 1e-6);
  EXPECT_NEAR(top_width, 0.006, 1e-6);
  EXPECT_NEAR(top_thickness, 0.004, 1e-6);
  // Length of the centreline (midpoints of opposite surface points), by a fine polygon.
  double length = 0.0;
  Eigen::Vector3d previous = 0.5 * (s.evaluate(0.0, 0.0) + s.evaluate(0.5, 0.0));
  for (int k = 1; k <= 2000; ++k) {
    const double v = k / 2000.0;
    const Eigen::Vector3d c = 0.5 * (s.evaluate(0.0, v) + s.evaluate(0.5, v));
    length += (c - previous).norm();
    previous = c;
  }
  EXPECT_GT(length, 0.033);
  EXPECT_LT(length, 0.037);
}

TEST(Shapes, ExampleSuiteMatchesSpec) {
  const auto shapes = example_shapes();
  ASSERT_EQ(shapes.size(), 5u);
  const char* names[] = {"cone", "barrel", "torus", "half_torus", "dao"};
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    EXPECT_EQ(shapes[k].name, names[k]);
    EXPECT_EQ(shapes[k].centreline_direction, 1);
    EXPECT_TRUE(shapes[k].surface.is_closed(0)) << shapes[k].name;
    EXPECT_EQ(shapes[k].exact_volume.has_value(), k < 4) << shapes[k].name;
  }
  // Cone frustum from SPEC §5: bottom diameter 4.0 cm, top 0.8 cm, height 5.0 cm.
  EXPECT_NEAR(*shapes[0].exact_volume,
              std::numbers::pi * 0.05 * (0.02 * 0.02 + 0.02 * 0.004 + 0.004 * 0.004) / 3.0, 1e-20);
}

TEST(Shapes, BadDimensionsAreRejected) {
  EXPECT_THROW(cone_frustum(-0.01, 0.01, 0.05), std::invalid_argument);
  EXPECT_THROW(barrel(0.05, 0.0, 0.01), std::invalid_argument);
  EXPECT_THROW(torus(0.01, 0.02), std::invalid_argument);
  EXPECT_THROW(half_torus(0.01, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace isomuscle::geometry
