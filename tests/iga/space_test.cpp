// iga::Space and Gauss–Legendre: exactness, tabulated data, volumes, and the det J error.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geometry/gauss_legendre.hpp"
#include "geometry/refinement.hpp"
#include "iga/space.hpp"
#include "iga_test_support.hpp"

namespace isomuscle::iga {
namespace {

TEST(GaussLegendre, IntegratesPolynomialsOfDegree2nMinus1Exactly) {
  for (int n = 1; n <= 12; ++n) {
    const geometry::GaussLegendreRule r = geometry::gauss_legendre_rule(n);
    for (int k = 0; k <= 2 * n - 1; ++k) {
      double sum = 0.0;
      for (int i = 0; i < n; ++i) {
        sum += r.weights[i] * std::pow(r.points[i], k);
      }
      const double exact = k % 2 == 1 ? 0.0 : 2.0 / (k + 1);
      EXPECT_NEAR(sum, exact, 1e-14) << "n = " << n << ", x^" << k;
    }
    // x^(2n) is not integrated exactly: the error is the Gauss remainder
    // 2^(2n+1) (n!)^4 / ((2n+1) ((2n)!)^2) (Abramowitz & Stegun 25.4.29 with f^(2n) = (2n)!).
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      sum += r.weights[i] * std::pow(r.points[i], 2 * n);
    }
    const double remainder = std::exp((2 * n + 1) * std::log(2.0) + 4 * std::lgamma(n + 1.0) -
                                      std::log(2.0 * n + 1.0) - 2 * std::lgamma(2 * n + 1.0));
    EXPECT_NEAR(2.0 / (2 * n + 1) - sum, remainder, 1e-9 * remainder + 1e-15) << n;
  }
  EXPECT_THROW(geometry::gauss_legendre_rule(0), std::invalid_argument);
  EXPECT_THROW(geometry::gauss_legendre_rule(geometry::kMaxGaussLegendrePoints + 1),
               std::invalid_argument);
}

TEST(Space, TabulatesPartitionOfUnityAndReproducesPosition) {
  const geometry::NurbsVolume v = testing::distorted_rational_block(3, 2, 0.1, 7);
  const Space space(v);
  EXPECT_EQ(space.num_elements(), 8);
  EXPECT_EQ(space.functions_per_element(), 64);
  EXPECT_EQ(space.points_per_element(), 64);
  for (int e = 0; e < space.num_elements(); ++e) {
    const auto cps = space.control_points(e);
    for (int q = 0; q < space.points_per_element(); ++q) {
      const auto R = space.values(e, q);
      const auto G = space.gradients(e, q);
      double sum = 0.0;
      Eigen::Vector3d gsum = Eigen::Vector3d::Zero();
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      Eigen::Matrix3d dxdX = Eigen::Matrix3d::Zero();  // sum X_a (x) dR_a/dX = I
      for (std::size_t a = 0; a < cps.size(); ++a) {
        sum += R[a];
        gsum += G[a];
        x += R[a] * v.points()[cps[a]];
        dxdX += v.points()[cps[a]] * G[a].transpose();
      }
      EXPECT_NEAR(sum, 1.0, 1e-14);
      EXPECT_LT(gsum.norm(), 1e-11);
      EXPECT_LT((x - space.position(e, q)).norm(), 1e-14);
      EXPECT_LT((x - v.evaluate(space.parametric(e, q))).norm(), 1e-13);
      EXPECT_LT((dxdX - Eigen::Matrix3d::Identity()).norm(), 1e-12);
      EXPECT_GT(space.dv(e, q), 0.0);
    }
  }
}

TEST(Space, VolumeOfShrinkCylinderConvergesToPiR2H) {
  // The integrand det J of the rational map is not polynomial: the quadrature error falls fast
  // with the number of points.
  const geometry::NurbsVolume v = testing::shrink_cylinder(0.5, 2.0, 2, {1, 1, 1});
  const double exact = std::numbers::pi * 0.25 * 2.0;
  const Space coarse(v);
  QuadratureOptions fine;
  fine.points = {8, 8, 8};
  const Space accurate(v, fine);
  EXPECT_NEAR(coarse.reference_volume(), exact, 1e-3 * exact);
  EXPECT_NEAR(accurate.reference_volume(), exact, 1e-12 * exact);
}

TEST(Space, LeftHandedSolidIsRejectedNamingElementAndPoint) {
  const geometry::NurbsVolume v = testing::box(Eigen::Vector3d(1, 1, 1), {1, 1, 1}, {2, 1, 1});
  std::vector<Eigen::Vector3d> pts = v.points();
  for (auto& p : pts) {
    p.x() = -p.x();  // mirror: det J < 0 everywhere
  }
  const geometry::NurbsVolume mirrored(v.all_knots(), pts, v.weights());
  try {
    const Space s(mirrored);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("element 0"), std::string::npos) << what;
    EXPECT_NE(what.find("quadrature point 0"), std::string::npos) << what;
    EXPECT_NE(what.find("left-handed"), std::string::npos) << what;
  }
}

TEST(Space, LocatesParametricPoints) {
  const geometry::NurbsVolume v = testing::box(Eigen::Vector3d(1, 2, 3), {2, 2, 2}, {3, 2, 4});
  const Space s(v);
  EXPECT_EQ(s.locate(Eigen::Vector3d(0.0, 0.0, 0.0)), 0);
  EXPECT_EQ(s.locate(Eigen::Vector3d(1.0, 1.0, 1.0)), s.num_elements() - 1);
  const int e = s.locate(Eigen::Vector3d(0.5, 0.25, 0.6));
  EXPECT_EQ(s.element(e).position, (std::array<int, 3>{1, 0, 2}));
  EXPECT_THROW(s.locate(Eigen::Vector3d(1.5, 0.0, 0.0)), std::invalid_argument);
  QuadratureOptions bad;
  bad.points = {2, -1, 2};
  EXPECT_THROW(Space(v, bad), std::invalid_argument);
}

}  // namespace
}  // namespace isomuscle::iga
