// compute_unstable_mode and the FreeDofLayout of both discretisations, at the reference state of
// the barrel clamped at one end (a cantilever). The layout places every free unknown on a node
// once, the clamped end's nodes have none, and the lumped volumes sum to the volume. The tangent
// there is positive definite, so the lowest eigenvalues are positive; the lowest mode of the round
// cantilever is bending, sideways, in a pair of equal eigenvalues (any direction across the axis:
// equal to round-off on the rotationally symmetric NURBS solid, to the mesh's asymmetry on
// tetrahedra: measured 2.64e4 Pa/m^2 twice on the IGA solid, 3.23e4 and 3.28e4 (1.5 % apart) on
// 3 mm 10-node tetrahedra; 6 mm ones, two across the ends, split them by 7 %). The file lists every
// node with a free unknown, scaled to a largest amplitude of 1. The material scan of the same
// state (RunModel::committed_ellipticity) gives the shear modulus at every quadrature point.
#include "io/unstable_mode.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <set>
#include <string>
#include <utility>

#include "io/iga_run_model.hpp"
#include "io/scene_loader.hpp"
#include "io/tet_run_model.hpp"
#include "io_test_util.hpp"

namespace isomuscle::io {
namespace {

class UnstableModeOfModel : public ::testing::TestWithParam<std::string> {};

TEST_P(UnstableModeOfModel, LayoutAndLowestModesAtTheReferenceState) {
  const std::string discretisation = GetParam();
  const bool tet = discretisation == "tet";
  const std::filesystem::path dir = testing_util::fresh_directory(discretisation);
  const std::string text = testing_util::clamped_barrel_scene(discretisation);
  const Scene scene = parse_scene(text, dir / "scene.toml");
  const std::unique_ptr<RunModel> model =
      tet ? make_tet_run_model(scene, 1, dir) : make_iga_run_model(scene, 1, dir);
  solver::NonlinearProblem& problem = model->problem();
  const FreeDofLayout layout = model->free_dof_layout();

  const int n = problem.size();
  const auto nodes = static_cast<int>(layout.node_positions.size());
  ASSERT_EQ(static_cast<int>(layout.node_of.size()), n);
  ASSERT_EQ(static_cast<int>(layout.component_of.size()), n);
  ASSERT_EQ(layout.node_volumes.size(), nodes);
  std::set<std::pair<int, int>> unknowns;
  std::set<int> free_nodes;
  for (int i = 0; i < n; ++i) {
    const int node = layout.node_of[static_cast<std::size_t>(i)];
    const int c = layout.component_of[static_cast<std::size_t>(i)];
    ASSERT_TRUE(node >= 0 && node < nodes && c >= 0 && c < 3) << "unknown " << i;
    EXPECT_TRUE(unknowns.insert({node, c}).second) << "unknown " << i << " placed twice";
    free_nodes.insert(node);
  }
  int clamped = 0;
  for (int node = 0; node < nodes; ++node) {
    if (std::abs(layout.node_positions[static_cast<std::size_t>(node)].z()) < 1e-9) {
      ++clamped;
      EXPECT_FALSE(free_nodes.contains(node)) << "node " << node << " on the clamped end";
    }
  }
  EXPECT_GT(clamped, 0);
  EXPECT_EQ(static_cast<int>(free_nodes.size()) * 3, n);  // the others are wholly free
  EXPECT_GT(layout.node_volumes.minCoeff(), 0.0);
  // Curved 10-node elements: the analysis quadrature's volume, 1e-7 off the mesh's.
  EXPECT_NEAR(layout.node_volumes.sum(), model->reference_volume(),
              (tet ? 1e-5 : 1e-12) * model->reference_volume());

  problem.begin_step(0.1, 0.1);
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
  const UnstableMode mode = compute_unstable_mode(problem, u, layout, dir / "mode.csv");
  ASSERT_TRUE(mode.ok) << mode.message;
  ASSERT_EQ(mode.eigenvalues.size(), 3);
  EXPECT_EQ(mode.negative, 0);
  EXPECT_EQ(mode.shift, 0.0);  // positive definite: no shift needed
  EXPECT_GT(mode.eigenvalues[0], 0.0);
  EXPECT_NEAR(mode.eigenvalues[1], mode.eigenvalues[0], (tet ? 0.05 : 1e-6) * mode.eigenvalues[0]);
  EXPECT_GT(mode.eigenvalues[2], 1.5 * mode.eigenvalues[1]);
  EXPECT_GT(mode.volume_share, 0.0);
  EXPECT_LE(mode.volume_share, 1.0);
  // The bending mode is largest at the free end (z = 5 cm).
  EXPECT_GT(mode.peak_position.z(), 0.045);
  EXPECT_NE(describe(mode, "mode.csv").find("lowest eigenvalue "), std::string::npos);

  const std::string csv = testing_util::read_text(dir / "mode.csv");
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line, "x,y,z,volume,mode_x,mode_y,mode_z");
  int rows = 0;
  double largest = 0.0;
  while (std::getline(lines, line)) {
    ++rows;
    double v[7];
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3],
                          &v[4], &v[5], &v[6]),
              7)
        << line;
    EXPECT_GT(v[3], 0.0) << line;
    largest = std::max(largest, std::sqrt(v[4] * v[4] + v[5] * v[5] + v[6] * v[6]));
  }
  EXPECT_EQ(rows, static_cast<int>(free_nodes.size()));
  EXPECT_NEAR(largest, 1.0, 1e-12);
  // The mode extends along the cantilever from its tip: radius of gyration about the tip 1.4 cm
  // (IGA) and 1.8 cm (tetrahedra) measured.
  EXPECT_GT(mode.radius, 0.01);
  EXPECT_LT(mode.radius, 0.05);
  std::printf(
      "%s: lowest eigenvalues %.6g %.6g %.6g Pa/m^2, peak z %.4g m, radius %.3g m, volume share "
      "%.3g\n",
      discretisation.c_str(), mode.eigenvalues[0], mode.eigenvalues[1], mode.eigenvalues[2],
      mode.peak_position.z(), mode.radius, mode.volume_share);

  // The material scan at the reference state: the isotropic law's smallest isochoric wave
  // stiffness is its shear modulus at every quadrature point, each placed inside the barrel.
  const MaterialEllipticityScan scan = model->committed_ellipticity(96);
  ASSERT_FALSE(scan.points.empty());
  EXPECT_EQ(scan.normals, 96);
  const double mu = scan.shear_modulus;
  EXPECT_GT(mu, 0.0);
  for (const EllipticityAt& p : scan.points) {
    ASSERT_NEAR(p.smallest, mu, 1e-9 * mu);
    EXPECT_GT(p.position.z(), 0.0);
    EXPECT_LT(p.position.z(), 0.05);
    EXPECT_LT(p.position.head<2>().norm(), 0.0088);
  }
}

INSTANTIATE_TEST_SUITE_P(Iga, UnstableModeOfModel, ::testing::Values("iga"));
// Named Gmsh...: its mesh comes from gmsh, whose leaks the sanitizer pass does not check
// (tests/CMakeLists.txt, scripts/test.sh).
INSTANTIATE_TEST_SUITE_P(GmshTetrahedra, UnstableModeOfModel, ::testing::Values("tet"));

}  // namespace
}  // namespace isomuscle::io
