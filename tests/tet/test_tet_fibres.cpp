// Fibres at tetrahedral quadrature points from the NURBS shrink solid of the barrel (thesis
// chapter 5, FEM–NURBS): point inversion followed by the isocurve tangent.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "geometry/fibre_field.hpp"
#include "geometry/iges.hpp"
#include "geometry/shrink.hpp"
#include "tet/tet_fibres.hpp"
#include "tet/tet_meshing.hpp"

namespace isomuscle::tet {
namespace {

geometry::NurbsVolume barrel_solid() {
  const auto surfaces = geometry::read_iges_surfaces(std::filesystem::path(ISOMUSCLE_SOURCE_DIR) /
                                                     "examples/geometry/barrel.igs");
  return geometry::shrink_to_centreline(surfaces.at(0).surface, 0);
}

// At X = H(xi) the fibre found by inversion is the normalised isocurve tangent dH/dv at xi.
TEST(TetFibres, InversionReproducesIsocurveTangent) {
  const geometry::NurbsVolume solid = barrel_solid();
  const geometry::PointInverter inverter(solid);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> d(0.0, 1.0);
  double worst = 0.0;
  for (int i = 0; i < 50; ++i) {
    // Away from the collapsed axis w = 1, where u is not determined by X.
    const Eigen::Vector3d xi(d(rng), d(rng), 0.9 * d(rng));
    const Eigen::Vector3d X = solid.evaluate(xi);
    const Eigen::Vector3d expected = geometry::fibre_direction(solid, xi, 1);
    const Eigen::Vector3d got = nurbs_fibre_at(inverter, X, 1, 0.0);
    worst = std::max(worst, (got - expected).norm());
  }
  std::printf("max |A(H^-1(X)) - A(xi)| over 50 points: %.2e\n", worst);
  EXPECT_LT(worst, 1e-10);
}

// On a gmsh mesh of barrel.igs: unit fibres, and (the barrel being a solid of revolution about z)
// each fibre lies in the meridional plane through its point, A . e_theta = 0; the points of a
// curved 10-node mesh lie inside the solid.
TEST(TetFibres, BarrelMeshFibresLieInMeridionalPlanes) {
  const geometry::NurbsVolume solid = barrel_solid();
  MeshingOptions opt;
  opt.element_size = 4e-3;
  opt.order = 2;
  const TetMesh mesh =
      mesh_iges(std::filesystem::path(ISOMUSCLE_SOURCE_DIR) / "examples/geometry/barrel.igs", opt);
  const TetSpace space(mesh);
  const std::vector<Eigen::Vector3d> fibres = nurbs_fibres(space, solid, 1);
  ASSERT_EQ(static_cast<int>(fibres.size()), space.num_points());
  double worst = 0.0;
  int checked = 0;
  for (int e = 0; e < space.num_elements(); ++e) {
    for (int q = 0; q < space.points_per_element(); ++q) {
      const Eigen::Vector3d& X = space.position(e, q);
      const Eigen::Vector3d& A =
          fibres[static_cast<std::size_t>(e) * space.points_per_element() + q];
      EXPECT_NEAR(A.norm(), 1.0, 1e-12);
      const double r = std::hypot(X[0], X[1]);
      if (r > 1e-4) {
        const Eigen::Vector3d e_theta(-X[1] / r, X[0] / r, 0.0);
        worst = std::max(worst, std::abs(A.dot(e_theta)));
        ++checked;
      }
    }
  }
  std::printf("%d points, max |A . e_theta| = %.2e\n", checked, worst);
  EXPECT_GT(checked, 100);
  EXPECT_LT(worst, 1e-10);
  EXPECT_THROW(
      nurbs_fibre_at(geometry::PointInverter(solid), Eigen::Vector3d(1.0, 0.0, 0.0), 1, 1e-3),
      std::runtime_error);
}

}  // namespace
}  // namespace isomuscle::tet
