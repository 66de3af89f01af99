// The surface check of an unstable equilibrium (io/surface_stability_check.hpp) and the surface
// points it is placed at (RunModel::committed_surface_point, io/iga_surface_point.hpp,
// io/tet_surface_point.hpp).
// * The check on made-up local states of the neo-Hookean solid: plane-strain compression along a
//   free surface is stable above Biot's stretch 0.5437 and wrinkles below it
//   (materials/surface_stability.hpp), in a rotated frame too; the surface's current normal is
//   Nanson's cof F N, not F N, which a shear along the surface tilts; the half-space's pressure
//   makes the normal traction zero.
// * On the barrel clamped at its v0 end, both discretisations: the traction-free boundary is the
//   lateral surface and the free end (not the clamped end, the seam or the collapsed axis); the
//   surface point nearest a point outside the middle of the barrel lies on the lateral surface
//   with a radial normal, the one nearest a point beyond the free end on that end; one near the
//   clamped end is never on it. At the reference state the check gives the Rayleigh wave,
//   0.91262 mu.
#include "io/surface_stability_check.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "io/element_layer_check.hpp"
#include "io/iga_run_model.hpp"
#include "io/iga_run_setup.hpp"
#include "io/iga_surface_point.hpp"
#include "io/scene_loader.hpp"
#include "io/tet_run_model.hpp"
#include "io_test_util.hpp"
#include "materials/material_factory.hpp"

namespace isomuscle::io {
namespace {

// The neo-Hookean solid at F with a surface of reference normal N, as a run model gives it.
SurfacePointAt neo_hookean_point(const Eigen::Matrix3d& F, const Eigen::Vector3d& N) {
  const auto law = materials::make_material("neo_hookean");
  SurfacePointAt point;
  point.normal = N;
  point.shear_modulus = law->shear_modulus();
  point.response = continuum::stepped_response(*law, F, Eigen::Vector3d::UnitX(), {}, 0.0, 0.0,
                                               /*pressure=*/123.0);
  return point;
}

TEST(SlowSurfaceStabilityCheck, BiotsThresholdInARotatedFrameAndNansonsNormal) {
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  const auto plane_strain = [&](double l) {
    return assess_surface_stability(
        neo_hookean_point(R * Eigen::Vector3d(l, 1.0 / l, 1.0).asDiagonal().toDenseMatrix(),
                          Eigen::Vector3d::UnitY()));
  };
  const SurfaceStabilityCheck above = plane_strain(0.548), below = plane_strain(0.540);
  const double mu = above.point.shear_modulus;
  std::printf("rotated plane strain: s = %.5f mu at 0.548, %.5f mu at 0.540 (%.3g s)\n",
              above.smallest / mu, below.smallest / mu, above.seconds);
  EXPECT_GT(above.smallest, 0.0);
  EXPECT_LT(below.smallest, 0.0);
  // The slowest wave runs along the compression, R e_x.
  EXPECT_GT(std::abs(below.direction.dot(R * Eigen::Vector3d::UnitX())), 0.999);
  for (const SurfaceStabilityCheck* c : {&above, &below}) {
    EXPECT_LT((c->current_normal - R * Eigen::Vector3d::UnitY()).norm(), 1e-12);
    // Uniaxial in the surface's plane: no shear traction, and the pressure of the free surface.
    const continuum::SteppedResponse& r = c->point.response;
    const Eigen::Matrix3d sigma = r.F * r.S * r.F.transpose() / r.F.determinant() +
                                  c->free_surface_pressure * Eigen::Matrix3d::Identity();
    EXPECT_LT((sigma * c->current_normal).norm(), 1e-9 * mu);
    EXPECT_LT(c->shear_traction, 1e-9 * mu);
    EXPECT_EQ(r.pressure, 123.0);  // the element's p~ is reported, not used
  }
  EXPECT_NE(describe(below).find("has reached Biot's surface instability"), std::string::npos);
  EXPECT_NE(describe(above).find("is stable as a deformed half-space"), std::string::npos);

  // A shear along the surface (x displaced in proportion to the depth y) leaves the surface y = 0
  // in place: its normal stays e_y, while F N would tilt it. The shear loads the surface.
  Eigen::Matrix3d sheared = Eigen::Vector3d(0.8, 1.25, 1.0).asDiagonal();
  sheared(0, 1) = 0.3;
  const SurfaceStabilityCheck shear =
      assess_surface_stability(neo_hookean_point(sheared, Eigen::Vector3d::UnitY()));
  EXPECT_LT((shear.current_normal - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  EXPECT_GT(shear.shear_traction, 0.1 * mu);
  EXPECT_GT(shear.smallest, 0.0);

  // A law without a volumetric split (a St Venant–Kirchhoff solid, S = lambda tr E I + 2 mu E),
  // a point the law could not evaluate: clear errors.
  class WithoutSplit final : public materials::MaterialLaw {
   public:
    std::string name() const override { return "svk"; }
    materials::PointStatus evaluate(const materials::PointInput& in, materials::PointResult& out,
                                    bool) const override {
      const Eigen::Matrix3d E = 0.5 * (in.F.transpose() * in.F - Eigen::Matrix3d::Identity());
      out.S = E.trace() * Eigen::Matrix3d::Identity() + 2.0 * E;
      out.tangent.setZero();
      return materials::PointStatus::ok;
    }
    double shear_modulus() const override { return 1.0; }
    double bulk_modulus() const override { return 1.0; }
  } without_split;
  SurfacePointAt compressible;
  compressible.shear_modulus = 1.0;
  compressible.response = continuum::stepped_response(without_split, Eigen::Matrix3d::Identity(),
                                                      Eigen::Vector3d::UnitX(), {}, 0.0, 0.0, 0.0);
  ASSERT_TRUE(compressible.response.ok);
  EXPECT_FALSE(compressible.response.isochoric);
  EXPECT_THROW(assess_surface_stability(compressible), std::invalid_argument);
  SurfacePointAt inverted =
      neo_hookean_point(Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal(), Eigen::Vector3d::UnitY());
  EXPECT_FALSE(inverted.response.ok);
  EXPECT_THROW(assess_surface_stability(inverted), std::invalid_argument);
}

class SurfacePointOfModel : public ::testing::TestWithParam<std::string> {};

TEST_P(SurfacePointOfModel, FreeBoundaryOfTheClampedBarrelAndTheRayleighWaveAtRest) {
  const std::string discretisation = GetParam();
  const bool tet = discretisation == "tet";
  const std::filesystem::path dir = testing_util::fresh_directory("surface_" + discretisation);
  const std::string text = testing_util::clamped_barrel_scene(discretisation);
  const Scene scene = parse_scene(text, dir / "scene.toml");
  const std::unique_ptr<RunModel> model =
      tet ? make_tet_run_model(scene, 1, dir) : make_iga_run_model(scene, 1, dir);
  if (!tet) {
    // u runs around the axis (a closed seam), v along it, w from the surface to the axis.
    const IgaModel iga = build_iga_model(scene, 1);
    const std::vector<iga::Side> sides =
        traction_free_sides(*iga.space, *iga.dofs, iga.problem->constraints());
    EXPECT_EQ(sides, (std::vector<iga::Side>{iga::Side::v1, iga::Side::w0}));
  }
  // The barrel: z from 0 (clamped) to 0.05 m, radius 8.75 mm at the middle.
  const std::optional<SurfacePointAt> side = model->committed_surface_point({0.02, 0.0, 0.025});
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->surface_position.head<2>().norm(), 0.00875, tet ? 3e-4 : 2e-4);
  EXPECT_GT(side->normal.x(), tet ? 0.97 : 0.99);
  EXPECT_LT((side->position - side->surface_position).norm(), 0.003);
  EXPECT_LT((side->position - side->surface_position).dot(side->normal), 0.0);  // inside
  const std::optional<SurfacePointAt> end = model->committed_surface_point({0.0, 0.001, 0.06});
  ASSERT_TRUE(end);
  EXPECT_NEAR(end->surface_position.z(), 0.05, 1e-9);
  EXPECT_GT(end->normal.z(), 1.0 - 1e-9);
  const std::optional<SurfacePointAt> clamped = model->committed_surface_point({0.0, 0.001, -0.01});
  ASSERT_TRUE(clamped);
  EXPECT_GT(clamped->surface_position.z(), 1e-6);
  EXPECT_LT(std::abs(clamped->normal.z()), 0.99);
  std::printf(
      "%s: side point (%.4g, %.4g, %.4g), normal (%.3f, %.3f, %.3f); near the clamp "
      "(%.4g, %.4g, %.4g)\n",
      discretisation.c_str(), side->surface_position.x(), side->surface_position.y(),
      side->surface_position.z(), side->normal.x(), side->normal.y(), side->normal.z(),
      clamped->surface_position.x(), clamped->surface_position.y(), clamped->surface_position.z());

  // At rest: F = I, no stress, the Rayleigh wave of the incompressible solid.
  const SurfaceStabilityCheck check = assess_surface_stability(*side, 4);
  const double mu = side->shear_modulus;
  EXPECT_NEAR(check.smallest / mu, 0.91262, 5e-4);
  EXPECT_LT((check.current_normal - side->normal).norm(), 1e-12);
  EXPECT_LT(std::abs(check.free_surface_pressure), 1e-9 * mu);
  EXPECT_LT(check.shear_traction, 1e-9 * mu);

  // The run's element tiled along the same surface point (element_layer_check.hpp): NURBS only.
  // At rest it is stable, and so is the same wave on finer elements.
  if (tet) {
    try {
      model->committed_element_layer({0.02, 0.0, 0.025});
      ADD_FAILURE() << "no throw for tetrahedra";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("knot-span elements"), std::string::npos) << e.what();
    }
  } else {
    const ElementLayerCheck layer = model->committed_element_layer({0.02, 0.0, 0.025});
    EXPECT_TRUE(layer.surface_position.isApprox(side->surface_position));
    EXPECT_EQ(layer.layer.degrees, (std::array<int, 3>{2, 2, 2}));  // (u, v) along, w deep
    EXPECT_GT(layer.lowest.eigenvalue, 0.0);
    for (const auto& [r, eigenvalue] : layer.same_wave)
      EXPECT_GT(eigenvalue, 0.0) << r;
    EXPECT_NE(describe(layer).find("the element is stable at this state"), std::string::npos)
        << describe(layer);
  }
}

INSTANTIATE_TEST_SUITE_P(Iga, SurfacePointOfModel, ::testing::Values("iga"));
// Named Gmsh...: its mesh comes from gmsh (tests/CMakeLists.txt).
INSTANTIATE_TEST_SUITE_P(GmshTetrahedra, SurfacePointOfModel, ::testing::Values("tet"));

}  // namespace
}  // namespace isomuscle::io
