// Discrete stability of the mixed knot-span element tiled along a free surface
// (iga/periodic_layer_stability.hpp), against the continuum it discretises: a deep layer of
// quadratic elements of a nearly incompressible neo-Hookean solid (kappa / mu = 1e4), its surface
// traction-free, its waves resolved by 8, 16 and 32 spans.
// * At rest the lowest eigenvalue over (k / l)^2 is rho c^2 of the surface wave: it rises to the
//   Rayleigh value of an incompressible solid, 0.91262 mu (materials/surface_stability.hpp).
// * In plane strain along the surface (stretch l) the resolved wave changes sign between l = 0.55
//   and 0.54, about Biot's 0.5437.
// * The under-resolved wave (8 spans) turns unstable already at l = 0.56, where the continuum is
//   stable: the element is softer than the solid for waves it barely resolves, the kind of
//   discrete instability the check exists to tell apart.
#include "iga/periodic_layer_stability.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include "materials/neo_hookean.hpp"

namespace isomuscle::iga {
namespace {

constexpr double kMu = 1.0e3;
constexpr double kKappa = 1.0e7;
constexpr double kSpan = 1.0e-3;  // m

// Plane strain along the surface: stretch l along x, 1 / l along the normal y, and the volume
// change whose pressure kappa (J - 1) makes the surface traction-free (sigma_yy = 0).
Eigen::Matrix3d free_plane_strain(double l) {
  const Eigen::Matrix3d F0 = Eigen::Vector3d(l, 1.0 / l, 1.0).asDiagonal();
  const Eigen::Matrix3d b = F0 * F0.transpose();
  const double sigma_iso_yy = kMu * (b(1, 1) - b.trace() / 3.0);  // mu dev(b), J = 1
  return std::cbrt(1.0 - sigma_iso_yy / kKappa) * F0;
}

// The neo-Hookean solid of these tests in that state (the law outlives the state).
LayerState free_plane_strain_state(const materials::MaterialLaw& law, double l) {
  LayerState state;
  state.law = &law;
  state.F = free_plane_strain(l);
  return state;
}

// Surface directions x and z, depth -y (the body below the surface y = 0).
LayerGeometry layer_of_depth(int spans) {
  LayerGeometry layer;
  layer.edges = {kSpan * Eigen::Vector3d::UnitX(), kSpan * Eigen::Vector3d::UnitZ(),
                 -kSpan * Eigen::Vector3d::UnitY()};
  layer.depth_spans.assign(static_cast<std::size_t>(spans), 1.0);
  return layer;
}

// lambda / (mu k^2), k the current wavenumber of a wave along x of `spans` spans.
double wave_stiffness(const PeriodicLayer& layer, double l, int spans) {
  const double theta = 2.0 * std::numbers::pi / spans;
  const double k = theta / (l * kSpan);
  return layer.lowest_at(Eigen::Vector2d(theta, 0.0)).eigenvalue / (kMu * k * k);
}

TEST(PeriodicLayer, ResolvedSurfaceWavesApproachRayleighAndBiot) {
  const materials::NeoHookean law("neo_hookean", kMu, kKappa);
  // 48 spans: 1.5 wavelengths of the longest wave. The slower of the incompressible Rayleigh
  // wave's two decays, e^{-0.296 k y}, leaves 6 % of it at the clamp (it stiffens that wave a
  // little) and 0.4 % of the 16-span wave.
  const LayerGeometry layer = layer_of_depth(48);
  const auto at = [&](double l) { return PeriodicLayer(layer, free_plane_strain_state(law, l)); };
  const PeriodicLayer rest = at(1.0);
  const double s8 = wave_stiffness(rest, 1.0, 8), s16 = wave_stiffness(rest, 1.0, 16),
               s32 = wave_stiffness(rest, 1.0, 32);
  std::printf("at rest: rho c^2 / mu = %.5f, %.5f, %.5f with 8, 16, 32 spans per wave\n", s8, s16,
              s32);
  EXPECT_LT(s8, s16);
  EXPECT_LT(s16, s32);
  EXPECT_NEAR(s32, 0.91262, 0.01);
  // The surface wave is a surface wave: largest in the surface row, decaying into the depth.
  const BlochMode mode = rest.lowest_at(Eigen::Vector2d(2.0 * std::numbers::pi / 16, 0.0));
  EXPECT_GT(mode.depth_amplitude[0], 0.9);
  for (int row : {10, 20, 30, 40})
    std::printf("16 spans per wave: amplitude %.4f at row %d\n", mode.depth_amplitude[row], row);
  // Under a quarter 1.25 wavelengths deep, under 2 % at 2.5 (the slower decay is 0.10 and 0.01
  // there).
  EXPECT_LT(mode.depth_amplitude[20], 0.25);
  EXPECT_LT(mode.depth_amplitude[40], 0.02);

  const PeriodicLayer above = at(0.55), below = at(0.54), early = at(0.56);
  const double s_above = wave_stiffness(above, 0.55, 32), s_below = wave_stiffness(below, 0.54, 32);
  const double coarse = wave_stiffness(early, 0.56, 8), resolved = wave_stiffness(early, 0.56, 32);
  std::printf(
      "plane strain, 32 spans per wave: %+.5f mu at l = 0.55, %+.5f mu at 0.54; at 0.56: "
      "%+.5f mu with 8 spans, %+.5f mu with 32\n",
      s_above, s_below, coarse, resolved);
  EXPECT_GT(s_above, 0.0);
  EXPECT_LT(s_below, 0.0);
  EXPECT_LT(coarse, 0.0);
  EXPECT_GT(resolved, 0.0);
}

// The frozen layer has no length of its own: with every edge halved its lowest eigenvalue is four
// times larger, at the same angles (the mode follows the mesh).
TEST(PeriodicLayer, LowestEigenvalueScalesAsOneOverTheElementSizeSquared) {
  const materials::NeoHookean law("neo_hookean", kMu, kKappa);
  const LayerState state = free_plane_strain_state(law, 0.7);
  LayerGeometry layer = layer_of_depth(3);
  layer.degrees = {2, 3, 2};
  const BlochMode full = PeriodicLayer(layer, state).lowest(8);
  for (Eigen::Vector3d& edge : layer.edges)
    edge *= 0.5;
  const BlochMode half = PeriodicLayer(layer, state).lowest(8);
  EXPECT_GT(full.eigenvalue, 0.0);
  EXPECT_NEAR(half.eigenvalue, 4.0 * full.eigenvalue, 1e-9 * std::abs(half.eigenvalue));
  for (int d = 0; d < 2; ++d)  // the same wave: equal angles up to a whole turn
    EXPECT_NEAR(std::cos(half.angles[d] - full.angles[d]), 1.0, 1e-12);
}

// Edges given in the other order (a left-handed layer, which the space cannot tabulate as it is)
// give the same layer, its angles exchanged; subdivided() keeps the depth.
TEST(PeriodicLayer, OrderOfTheSurfaceDirectionsAndSubdivision) {
  const materials::NeoHookean law("neo_hookean", kMu, kKappa);
  const LayerState state = free_plane_strain_state(law, 0.8);
  LayerGeometry layer = layer_of_depth(2);
  layer.degrees = {2, 3, 2};
  layer.edges[1] = kSpan * Eigen::Vector3d(0.3, 0.0, 2.0);  // skewed, longer
  LayerGeometry exchanged = layer;
  std::swap(exchanged.edges[0], exchanged.edges[1]);
  std::swap(exchanged.degrees[0], exchanged.degrees[1]);
  const PeriodicLayer a(layer, state), b(exchanged, state);
  for (const Eigen::Vector2d& theta :
       {Eigen::Vector2d(0.4, -1.3), Eigen::Vector2d(3.0, 0.2), Eigen::Vector2d(1.1, 2.5)}) {
    const double ea = a.lowest_at(theta).eigenvalue;
    EXPECT_NEAR(b.lowest_at(Eigen::Vector2d(theta[1], theta[0])).eigenvalue, ea,
                1e-9 * std::abs(ea));
  }
  const LayerGeometry fine = subdivided(layer, 3);
  ASSERT_EQ(fine.depth_spans.size(), 6u);
  EXPECT_DOUBLE_EQ(fine.depth_spans[5], 1.0 / 3.0);
  EXPECT_TRUE(fine.edges[0].isApprox(layer.edges[0] / 3.0));
  EXPECT_TRUE(fine.edges[2].isApprox(layer.edges[2]));
  EXPECT_EQ(PeriodicLayer(fine, state).depth_rows(), 6 + 2);
}

TEST(PeriodicLayer, BadInputIsRefusedClearly) {
  const materials::NeoHookean law("neo_hookean", kMu, kKappa);
  LayerState state;
  state.law = &law;
  const LayerGeometry layer = layer_of_depth(2);
  const auto message = [&](const LayerGeometry& g, const LayerState& s) -> std::string {
    try {
      PeriodicLayer p(g, s);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  };
  LayerState inverted = state;
  inverted.F = Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal();
  EXPECT_NE(message(layer, inverted).find("det F"), std::string::npos);
  LayerGeometry flat = layer;
  flat.edges[2] = flat.edges[0] + flat.edges[1];
  EXPECT_NE(message(flat, state).find("do not span a volume"), std::string::npos);
  LayerGeometry empty = layer;
  empty.depth_spans = {1.0, 0.0};
  EXPECT_NE(message(empty, state).find("not positive"), std::string::npos);
  LayerState history = state;
  history.history = {1.0};
  EXPECT_NE(message(layer, history).find("history"), std::string::npos);
  LayerState no_law;
  EXPECT_NE(message(layer, no_law).find("volumetric split"), std::string::npos);
  EXPECT_THROW(subdivided(layer, 0), std::invalid_argument);

  // A law whose local solve fails at the state: the kernel's failure, named.
  class Failing final : public materials::MaterialLaw {
   public:
    std::string name() const override { return "failing"; }
    materials::PointStatus evaluate(const materials::PointInput&, materials::PointResult&,
                                    bool) const override {
      return materials::PointStatus::local_solve_failed;
    }
    bool has_volumetric_split() const override { return true; }
    materials::PointStatus evaluate_isochoric(const materials::PointInput&, materials::PointResult&,
                                              bool) const override {
      return materials::PointStatus::local_solve_failed;
    }
    Eigen::Vector3d volumetric(double) const override { return Eigen::Vector3d::Zero(); }
    double shear_modulus() const override { return 1.0; }
    double bulk_modulus() const override { return 1.0; }
  } failing;
  LayerState failed = state;
  failed.law = &failing;
  try {
    PeriodicLayer p(layer, failed);
    ADD_FAILURE() << "no throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'failing'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace isomuscle::iga
