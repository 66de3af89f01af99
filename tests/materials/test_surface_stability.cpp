// Surface stability of a deformed, incompressible half-space (materials/surface_stability.hpp)
// against the classical results for the neo-Hookean solid, the isochoric part as the mixed
// formulation uses it and the pressure that makes the surface traction-free:
// * at rest, s = rho c_R^2 = 0.91262 mu (the Rayleigh wave of an incompressible solid, whose speed
//   is 0.95531 of the shear wave's), whatever the surface's normal;
// * in plane-strain compression along the surface (stretch l along it, 1/l along the normal) the
//   surface wrinkles at Biot's l = 0.5437, first for waves along the compression;
// * in equibiaxial compression (l, l along the surface, 1/l^2 along the normal) at l = 0.6661.
// Each evaluation takes about 4 s in Release (a dense eigenproblem per tangent tried), so the
// suite is Slow.
#include "materials/surface_stability.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <vector>

#include "material_test_support.hpp"
#include "materials/material_factory.hpp"

namespace isomuscle::materials {
namespace {

// s / mu of the neo-Hookean solid at F with a traction-free surface of current normal n.
SurfaceStabilityResult neo_hookean_surface(const Eigen::Matrix3d& F, const Eigen::Vector3d& n,
                                           double& mu) {
  const auto law = make_material("neo_hookean");
  mu = law->shear_modulus();
  PointInput in;
  in.F = F;
  std::vector<double> history;
  PointResult out;
  out.history = history;
  EXPECT_EQ(law->evaluate_isochoric(in, out, true), PointStatus::ok);
  const Eigen::Matrix3d sigma_iso = F * out.S * F.transpose() / F.determinant();
  return surface_stability(F, out.S, out.tangent, -n.dot(sigma_iso * n), n, 8);
}

TEST(SlowSurfaceStability, NeoHookeanHalfSpaceMatchesRayleighAndBiot) {
  double mu = 0.0;
  // At rest, for two normals.
  const Eigen::Vector3d tilted = Eigen::Vector3d(1.0, 2.0, 2.0) / 3.0;
  for (const Eigen::Vector3d& n : {Eigen::Vector3d(Eigen::Vector3d::UnitY()), tilted}) {
    const double s = neo_hookean_surface(Eigen::Matrix3d::Identity(), n, mu).smallest / mu;
    std::printf("at rest, normal (%.2f, %.2f, %.2f): s = %.5f mu\n", n.x(), n.y(), n.z(), s);
    EXPECT_NEAR(s, 0.91262, 5e-4);
  }
  // Plane strain: stable above Biot's 0.5437, wrinkling below it, waves along the compression.
  const auto plane_strain = [&](double l) {
    return neo_hookean_surface(Eigen::Vector3d(l, 1.0 / l, 1.0).asDiagonal().toDenseMatrix(),
                               Eigen::Vector3d::UnitY(), mu);
  };
  const SurfaceStabilityResult above = plane_strain(0.548), below = plane_strain(0.540);
  std::printf("plane strain: s = %.5f mu at 0.548, %.5f mu at 0.540\n", above.smallest / mu,
              below.smallest / mu);
  EXPECT_GT(above.smallest, 0.0);
  EXPECT_LT(below.smallest, 0.0);
  EXPECT_GT(std::abs(below.direction.x()), 0.999);
  // Equibiaxial: Biot's 0.6661.
  const auto equibiaxial = [&](double l) {
    return neo_hookean_surface(Eigen::Vector3d(l, l, 1.0 / (l * l)).asDiagonal().toDenseMatrix(),
                               Eigen::Vector3d::UnitZ(), mu);
  };
  const double s_above = equibiaxial(0.670).smallest, s_below = equibiaxial(0.662).smallest;
  std::printf("equibiaxial: s = %.5f mu at 0.670, %.5f mu at 0.662\n", s_above / mu, s_below / mu);
  EXPECT_GT(s_above, 0.0);
  EXPECT_LT(s_below, 0.0);
  // A rotated frame (F -> R F, n -> R n) gives the same s.
  std::mt19937 rng(2);
  const Eigen::Matrix3d R = testing::random_rotation(rng);
  const double rotated =
      neo_hookean_surface(R * Eigen::Vector3d(0.548, 1.0 / 0.548, 1.0).asDiagonal(),
                          R * Eigen::Vector3d::UnitY(), mu)
          .smallest;
  EXPECT_NEAR(rotated, above.smallest, 1e-6 * mu);
  EXPECT_THROW(surface_stability(Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Zero(),
                                 Matrix6d::Identity(), 0.0, Eigen::Vector3d(1, 1, 0), 8),
               std::invalid_argument);
}

}  // namespace
}  // namespace isomuscle::materials
