// Cook's membrane on tetrahedra (the benchmark of examples/cook/README.md, there on IGA): the
// trapezoid (0,0), (48,44), (48,60), (0,44), thickness 1, clamped at x = 0, a dead shear traction
// 0.05 per unit reference area along +y on x = 48 (tet_surface_loads.hpp) ramped over 4 steps,
// plane strain (u_z = 0 at every node), neo-Hookean mu = 1, kappa = 1e5 mu. Structured n x n x 1
// cells of six tetrahedra each, mapped by the bilinear map of the trapezoid (the 10-node elements
// are then isoparametric, their diagonal edges slightly curved). Reference corner UY = 4.7011
// (Mueller 2015, as quoted by the Elmer test suite): the condensed u-p-J 10-node tetrahedron
// converges to it from below (measured 4.2790 / 4.5733 / 4.6622 at n = 4 / 8 / 16, -0.83 %; the
// Richardson limit of the three, 4.701, is the reference), the 4-node displacement tetrahedron
// locks (1.3869 at n = 16, -70 %), and the clamp carries the applied 0.8.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "materials/material_factory.hpp"
#include "solver/time_stepper.hpp"
#include "tet/tet_fibres.hpp"
#include "tet/tet_mesh.hpp"
#include "tet/tet_problem.hpp"
#include "tet/tet_space.hpp"
#include "tet/tet_surface_loads.hpp"

namespace isomuscle::tet {
namespace {

constexpr double kReference = 4.7011;

// The unit box mapped onto the trapezoid: X = (1-s)(1-t) A + s(1-t) B + (1-s) t D + s t C.
TetMesh cook_mesh(int n, int order) {
  TetMesh mesh = structured_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), {n, n, 1}, order);
  const Eigen::Vector2d A(0, 0), B(48, 44), C(48, 60), D(0, 44);
  for (Eigen::Vector3d& x : mesh.nodes) {
    const double s = x.x(), t = x.y();
    const Eigen::Vector2d p = (1 - s) * (1 - t) * A + s * (1 - t) * B + (1 - s) * t * D + s * t * C;
    x = Eigen::Vector3d(p.x(), p.y(), x.z());
  }
  mesh.validate();
  return mesh;
}

struct CookResult {
  double uy = 0.0;
  double clamp_force_y = 0.0;
  double loaded_area = 0.0;
};

CookResult cook(int n, int order, Formulation formulation) {
  const TetMesh mesh = cook_mesh(n, order);
  const TetSpace space(mesh);
  const auto law = materials::make_material("neo_hookean", {{"C10", 0.5}, {"K", 1e5}});
  TetDirichlet clamp;
  clamp.nodes = boundary_nodes(mesh, 1);  // x = 0 (the box's face s = 0)
  TetDirichlet plane_strain;
  for (int i = 0; i < mesh.num_nodes(); ++i)
    plane_strain.nodes.push_back(i);
  plane_strain.components = {false, false, true};
  TetProblemOptions opt;
  opt.formulation = formulation;
  opt.threads = 1;
  TetProblem problem(space, *law, constant_fibres(space, Eigen::Vector3d::UnitX()),
                     {clamp, plane_strain}, {}, opt);
  std::vector<int> loaded;
  for (int f = 0; f < mesh.num_boundary_faces(); ++f)
    if (mesh.boundary_tag[f] == 2)  // x = 48 (s = 1)
      loaded.push_back(f);
  CookResult r;
  r.loaded_area = faces_area(mesh, loaded);
  problem.set_surface_loads(
      {{"shear traction x = 48", loaded, [](const Eigen::Vector3d&, double t) -> Eigen::Vector3d {
          return Eigen::Vector3d(0.0, 0.05 * t, 0.0);
        }}});
  // As the IGA test: four load steps, Newton without the Armijo search on |r| (the first full step
  // of an increment raises |r| before the quadratic convergence), tolerances above the residual's
  // round-off floor (kappa eps V_e).
  solver::TimeStepperSettings ts;
  ts.initial_dt = 0.25;
  ts.max_dt = 0.25;
  ts.min_dt = 1e-3;
  solver::NewtonSettings newton;
  newton.max_iterations = 30;
  newton.relative_residual_tolerance = 1e-7;
  newton.relative_energy_tolerance = 1e-7;
  newton.absolute_residual_tolerance = 1e-9;
  newton.absolute_energy_tolerance = 1e-20;
  newton.line_search = false;
  solver::TimeStepper stepper(ts, newton);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
  const solver::TimeStepperResult run = stepper.run(problem, u);
  EXPECT_TRUE(run.completed) << run.message;
  const Eigen::VectorXd full = problem.committed_displacement();
  int corner = 0;
  for (int i = 1; i < mesh.num_nodes(); ++i)
    if ((mesh.nodes[i] - Eigen::Vector3d(48, 60, 0)).norm() <
        (mesh.nodes[corner] - Eigen::Vector3d(48, 60, 0)).norm())
      corner = i;
  r.uy = full[3 * corner + 1];
  Eigen::VectorXd f_int;
  EXPECT_TRUE(problem.internal_force(u, f_int).ok);
  r.clamp_force_y = problem.sum_over_nodes(f_int - problem.external_force(), clamp.nodes)[1];
  return r;
}

TEST(SlowTetCook, TenNodeMixedConvergesToTheReferenceFourNodeLocks) {
  std::printf("Cook's membrane on tetrahedra, corner UY (reference %.4f):\n", kReference);
  CookResult mixed;
  double previous = 0.0;
  for (int n : {4, 8, 16}) {
    mixed = cook(n, 2, Formulation::mixed);
    std::printf("  10-node mixed, n = %2d: %.4f (%+.2f %%)\n", n, mixed.uy,
                100.0 * (mixed.uy / kReference - 1.0));
    std::fflush(stdout);
    EXPECT_NEAR(mixed.loaded_area, 16.0, 1e-12);  // the edge x = 48 from y = 44 to 60, depth 1
    EXPECT_NEAR(mixed.clamp_force_y, -0.05 * 16.0, 1e-6);
    if (n > 4) {
      EXPECT_LT(std::abs(mixed.uy - kReference), std::abs(previous - kReference));
    }
    previous = mixed.uy;
  }
  EXPECT_NEAR(mixed.uy, kReference, 0.01 * kReference);
  const CookResult linear = cook(16, 1, Formulation::displacement);
  std::printf("  4-node displacement, n = 16: %.4f (%+.2f %%)\n", linear.uy,
              100.0 * (linear.uy / kReference - 1.0));
  EXPECT_LT(linear.uy, 0.5 * kReference);  // locked
}

}  // namespace
}  // namespace isomuscle::tet
