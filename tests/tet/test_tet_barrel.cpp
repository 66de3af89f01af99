// End to end on tetrahedra: barrel.igs meshed by gmsh (10-node), fibres from the NURBS shrink
// solid by point inversion, the Lu (2010) Hill muscle activated with both ends held (isometric),
// the condensed mixed formulation, Newton over a few time steps.
#include <gtest/gtest.h>

#include <filesystem>

#include "geometry/iges.hpp"
#include "geometry/shrink.hpp"
#include "materials/material_factory.hpp"
#include "solver/newton.hpp"
#include "tet/tet_fibres.hpp"
#include "tet/tet_meshing.hpp"
#include "tet/tet_problem.hpp"

namespace isomuscle::tet {
namespace {

// Measured: 499 elements, 2820 unknowns; 21, 19, 10 Newton iterations (the Armijo search on |r|
// crawls while second-order volumetric terms times kappa = 2e9 Pa dominate the residual, then
// Newton converges quadratically); volume change 6e-7; mean fibre stretch in the belly 0.9945.
// A whole run: Slow suite (about 10 s of CPU).
TEST(SlowTetBarrel, IsometricActivationConvergesAndKeepsVolume) {
  const std::filesystem::path file =
      std::filesystem::path(ISOMUSCLE_SOURCE_DIR) / "examples/geometry/barrel.igs";
  const geometry::NurbsVolume solid =
      geometry::shrink_to_centreline(geometry::read_iges_surfaces(file).at(0).surface, 0);
  MeshingOptions mo;
  mo.element_size = 5e-3;
  mo.order = 2;
  const TetMesh mesh = mesh_iges(file, mo);
  const TetSpace space(mesh);
  const auto law = materials::make_material("lu2010", {{"ramp_time", 0.005}});
  TetDirichlet ends;
  ends.nodes = nodes_on_plane(mesh, 2, 0.0, 1e-9);
  const auto top = nodes_on_plane(mesh, 2, 0.05, 1e-9);
  ASSERT_FALSE(ends.nodes.empty());
  ASSERT_FALSE(top.empty());
  ends.nodes.insert(ends.nodes.end(), top.begin(), top.end());
  TetProblemOptions opt;
  opt.threads = 1;
  TetProblem problem(space, *law, nurbs_fibres(space, solid, 1), {ends}, {}, opt);
  EXPECT_EQ(problem.formulation(), Formulation::mixed);
  solver::NewtonSettings ns;
  ns.absolute_residual_tolerance = 1e-9;  // N (above the round-off floor of kappa = 2e9 Pa)
  ns.absolute_energy_tolerance = 1e-18;
  ns.max_iterations = 60;
  solver::NewtonSolver newton(ns);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
  const double v0 = problem.current_volume(problem.full_displacement(u));
  const double dt = 0.001;
  for (int step = 1; step <= 3; ++step) {
    problem.begin_step(step * dt, dt);
    const solver::NewtonResult r = newton.solve(problem, u);
    ASSERT_TRUE(r.converged) << "step " << step << ": " << r.message;
    problem.commit_step(u);
    std::printf("t = %.4f s: %d Newton iterations, |u|_max = %.3e m\n", step * dt, r.iterations,
                u.cwiseAbs().maxCoeff());
  }
  const double v = problem.current_volume(problem.committed_displacement());
  std::printf("%d elements, %d unknowns; volume change %.2e\n", mesh.num_elements(), problem.size(),
              v / v0 - 1.0);
  EXPECT_GT(u.cwiseAbs().maxCoeff(), 1e-6);  // the active muscle deforms
  EXPECT_LT(std::abs(v / v0 - 1.0), 1e-3);
  // Fibres shorten in the middle of the muscle (the ends are held, the belly contracts).
  double mean_stretch = 0.0;
  int n = 0;
  for (int e = 0; e < space.num_elements(); ++e) {
    const TetPointState st = problem.state_at_point(e, 0);
    if (std::abs(st.X[2] - 0.025) < 0.005) {
      mean_stretch += st.fibre_stretch;
      ++n;
    }
  }
  ASSERT_GT(n, 0);
  std::printf("mean fibre stretch in the belly: %.5f\n", mean_stretch / n);
  EXPECT_LT(mean_stretch / n, 0.999);
}

}  // namespace
}  // namespace isomuscle::tet
