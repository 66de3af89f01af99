// TetProblem: patch tests (affine displacement reproduced at every quadrature point), the
// assembled tangent against central differences of the residual for an activated Hill muscle, the
// tangent pass at the last evaluated state reading the trial history, and failure reporting for
// an inverted element.
#include <gtest/gtest.h>

#include <random>

#include "materials/material_factory.hpp"
#include "materials/strong_ellipticity.hpp"
#include "solver/newton.hpp"
#include "tests/support/offer_counting_law.hpp"
#include "tet/tet_fibres.hpp"
#include "tet/tet_mesh.hpp"
#include "tet/tet_problem.hpp"
#include "tet/tet_space.hpp"

namespace isomuscle::tet {
namespace {

// A 3x3x3 box of edge 1 cm with every interior vertex moved randomly by up to 15 % of a cell, so
// that elements are distorted; with curved, interior edge nodes of 10-node elements move off the
// edge midpoints by up to 3 % of a cell.
TetMesh distorted_box(int order, bool curved) {
  TetMesh mesh =
      structured_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(0.01), {3, 3, 3}, order);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  const double h = 0.01 / 3.0;
  const auto interior = [](const Eigen::Vector3d& x) {
    return (x.array() > 1e-12).all() && (x.array() < 0.01 - 1e-12).all();
  };
  const int vertices = 4 * 4 * 4;  // structured_box numbers the grid vertices first
  for (int n = 0; n < vertices; ++n) {
    if (interior(mesh.nodes[n])) {
      mesh.nodes[n] += 0.15 * h * Eigen::Vector3d(d(rng), d(rng), d(rng));
    }
  }
  if (order == 2) {
    constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
    for (int e = 0; e < mesh.num_elements(); ++e) {
      const auto el = mesh.element(e);
      for (int k = 0; k < 6; ++k) {
        mesh.nodes[el[4 + k]] = 0.5 * (mesh.nodes[el[kEdges[k][0]]] + mesh.nodes[el[kEdges[k][1]]]);
      }
    }
    for (int n = vertices; curved && n < mesh.num_nodes(); ++n) {
      if (interior(mesh.nodes[n])) {
        mesh.nodes[n] += 0.03 * h * Eigen::Vector3d(d(rng), d(rng), d(rng));  // curved elements
      }
    }
  }
  mesh.validate();
  return mesh;
}

std::vector<int> all_boundary_nodes(const TetMesh& mesh) {
  std::vector<int> out;
  for (int tag = 1; tag <= 6; ++tag) {
    const auto n = boundary_nodes(mesh, tag);
    out.insert(out.end(), n.begin(), n.end());
  }
  return out;
}

struct PatchCase {
  int order;
  Formulation formulation;
  int pressure_degree;
  bool curved = false;
  int quadrature_degree = 0;
};

class PatchTest : public ::testing::TestWithParam<PatchCase> {};

// u = A X on the boundary; a homogeneous hyperelastic body then has F = I + A everywhere (the
// stress is constant, so every element is in equilibrium): reproduced at every quadrature point.
// Curved (isoparametric) 10-node elements pass only when int dN/dX dV is integrated exactly: the
// integrand adj(dX/dxi)^T dN/dxi is cubic, so the default 4-point rule (degree 2) misses it
// (measured: |F - (I + A)| ~ 4e-4 with 3 % curvature) and the degree-4 rule is used there.
TEST_P(PatchTest, AffineDisplacementReproduced) {
  const PatchCase c = GetParam();
  const TetMesh mesh = distorted_box(c.order, c.curved);
  const TetSpace space(mesh, c.quadrature_degree);
  const auto law = materials::make_material("neo_hookean", {{"C10", 1e4}, {"K", 1e6}});
  Eigen::Matrix3d A;
  A << 0.05, 0.02, -0.01, 0.00, -0.03, 0.04, 0.01, 0.02, 0.06;
  TetDirichlet bc;
  bc.nodes = all_boundary_nodes(mesh);
  bc.value = [A](const Eigen::Vector3d& X, double t) -> Eigen::Vector3d { return t * (A * X); };
  TetProblemOptions opt;
  opt.formulation = c.formulation;
  opt.pressure_degree = c.pressure_degree;
  opt.threads = 1;
  TetProblem problem(space, *law, constant_fibres(space, Eigen::Vector3d::UnitZ()), {bc}, {}, opt);
  EXPECT_EQ(problem.formulation(), c.formulation);
  problem.begin_step(1.0, 1.0);
  solver::NewtonSettings ns;
  ns.relative_residual_tolerance = 1e-14;
  ns.absolute_residual_tolerance = 1e-13;
  ns.absolute_energy_tolerance = 1e-20;
  solver::NewtonSolver newton(ns);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
  // From the linearised Dirichlet predictor, as a run starts (iga's patch test does the same).
  ASSERT_TRUE(problem.predict(u).ok);
  const solver::NewtonResult r = newton.solve(problem, u);
  ASSERT_TRUE(r.converged) << r.message;
  const auto F = problem.deformation_gradients(problem.full_displacement(u));
  double worst = 0.0;
  for (const auto& f : F) {
    worst = std::max(worst, (f - Eigen::Matrix3d::Identity() - A).cwiseAbs().maxCoeff());
  }
  std::printf("order %d %s%s: %d unknowns, %d Newton iterations, max |F - (I + A)| = %.2e\n",
              c.order, to_string(c.formulation), c.curved ? " curved" : "", problem.size(),
              r.iterations, worst);
  EXPECT_LT(worst, 1e-10);
  // The committed state reproduces the law's stress at F = I + A (mixed: p~ = U'(J~) with J~ = J).
  problem.commit_step(u);
  // The smallest and largest J of the committed state: det(I + A) at every point, found during
  // assembly.
  const continuum::JacobianRange& jr = problem.committed_jacobian_range();
  ASSERT_TRUE(jr.found());
  for (const continuum::JacobianAtPoint& j : {jr.smallest, jr.largest}) {
    EXPECT_NEAR(j.value, (Eigen::Matrix3d::Identity() + A).determinant(), 1e-10);
    EXPECT_LT(j.element, space.num_elements());
    EXPECT_LT(j.point, space.points_per_element());
  }
  const TetPointState st = problem.state_at_point(space.num_elements() - 1, 0);
  materials::PointInput in;
  in.F = Eigen::Matrix3d::Identity() + A;
  materials::PointResult out;
  ASSERT_EQ(law->evaluate(in, out, false), materials::PointStatus::ok);
  EXPECT_LT((st.S - out.S).norm(), 1e-9 * out.S.norm());
  EXPECT_NEAR(st.J_bar, in.F.determinant(), 1e-12);
  EXPECT_LT((st.cauchy - st.cauchy.transpose()).norm(), 1e-12 * st.cauchy.norm());
  EXPECT_NEAR(st.fibre_stretch, (in.F * Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  EXPECT_LT((st.displacement - A * st.X).norm(), 1e-12);
  EXPECT_THROW(problem.state_at_point(-1, 0), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Tet, PatchTest,
                         ::testing::Values(PatchCase{1, Formulation::displacement, 0},
                                           PatchCase{2, Formulation::displacement, 0},
                                           PatchCase{2, Formulation::mixed, 0},
                                           PatchCase{2, Formulation::mixed, 1},
                                           PatchCase{2, Formulation::displacement, 0, true, 4},
                                           PatchCase{2, Formulation::mixed, 0, true, 4}));

// dr/du assembled against central differences of the residual: the Lu (2010) Hill muscle,
// activated (t = 20 ms into the activation ramp, dt = 5 ms), fibres varying in direction, a
// displaced state; displacement and condensed mixed formulations.
TEST(TetTangent, MatchesCentralDifferencesForActivatedHillMuscle) {
  for (const PatchCase c :
       {PatchCase{1, Formulation::displacement, 0}, PatchCase{2, Formulation::displacement, 0},
        PatchCase{2, Formulation::mixed, 0}, PatchCase{2, Formulation::mixed, 1}}) {
    const TetMesh mesh = structured_box(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.01, 0.01, 0.02),
                                        {1, 1, 2}, c.order);
    const TetSpace space(mesh);
    const auto law = materials::make_material("lu2010", {{"D", 1e-6}});
    std::vector<Eigen::Vector3d> fibres;
    for (int e = 0; e < space.num_elements(); ++e) {
      for (int q = 0; q < space.points_per_element(); ++q) {
        const Eigen::Vector3d& X = space.position(e, q);
        fibres.push_back(Eigen::Vector3d(20.0 * X[0], 10.0 * X[1], 1.0).normalized());
      }
    }
    TetDirichlet bottom;
    bottom.nodes = nodes_on_plane(mesh, 2, 0.0, 1e-12);
    TetProblemOptions opt;
    opt.formulation = c.formulation;
    opt.pressure_degree = c.pressure_degree;
    opt.threads = 1;
    TetProblem problem(space, *law, fibres, {bottom}, {}, opt);
    problem.begin_step(0.02, 0.005);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> d(-1.0, 1.0);
    Eigen::VectorXd u(problem.size());
    for (int i = 0; i < u.size(); ++i) {
      u[i] = 2e-4 * d(rng);
    }
    Eigen::VectorXd r, rp, rm;
    solver::SparseMatrix K;
    ASSERT_TRUE(problem.evaluate(u, r, &K).ok);
    const Eigen::MatrixXd Kd = Eigen::MatrixXd(K).selfadjointView<Eigen::Upper>();
    Eigen::MatrixXd Kfd(problem.size(), problem.size());
    const double h = 1e-8;
    for (int j = 0; j < u.size(); ++j) {
      Eigen::VectorXd up = u, um = u;
      up[j] += h;
      um[j] -= h;
      ASSERT_TRUE(problem.evaluate(up, rp, nullptr).ok);
      ASSERT_TRUE(problem.evaluate(um, rm, nullptr).ok);
      Kfd.col(j) = (rp - rm) / (2.0 * h);
    }
    const double scale = Kd.cwiseAbs().maxCoeff();
    const double err = (Kfd - Kd).cwiseAbs().maxCoeff() / scale;
    std::printf("order %d %s (p degree %d): %d unknowns, max |K - K_fd| / max |K| = %.2e\n",
                c.order, to_string(c.formulation), c.pressure_degree, problem.size(), err);
    EXPECT_LT(err, 1e-6);
    EXPECT_LT((Kd - Kd.transpose()).cwiseAbs().maxCoeff() / scale, 1e-12);
  }
}

// Evaluated again at the free values of the last evaluation in the same step (Newton's tangent
// pass after its line search, the reaction probes' internal force), the law is offered the trial
// history at every point and nowhere else; the residual, tangent and internal force are bitwise
// those of the same passes with the offer refused.
TEST(TetProblem, TangentPassAtTheLastEvaluatedStateReadsTheTrialHistory) {
  const TetMesh mesh =
      structured_box(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.01, 0.01, 0.02), {1, 1, 2}, 2);
  const TetSpace space(mesh);
  const auto muscle = materials::make_material("tang2009");
  std::vector<Eigen::Vector3d> fibres(
      static_cast<std::size_t>(space.num_elements() * space.points_per_element()),
      Eigen::Vector3d(0.2, 0.1, 1.0).normalized());
  TetDirichlet bottom;
  bottom.nodes = nodes_on_plane(mesh, 2, 0.0, 1e-12);
  TetProblemOptions opt;
  opt.formulation = Formulation::displacement;
  opt.threads = 1;
  test_support::OfferCountingLaw reading(*muscle, false), refusing(*muscle, true);
  TetProblem a(space, reading, fibres, {bottom}, {}, opt),
      b(space, refusing, fibres, {bottom}, {}, opt);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  Eigen::VectorXd u(a.size());
  for (int i = 0; i < u.size(); ++i)
    u[i] = 2e-4 * d(rng);
  const Eigen::VectorXd elsewhere = 0.5 * u;
  Eigen::VectorXd r_a, r_b;
  solver::SparseMatrix K_a, K_b;
  for (TetProblem* p : {&a, &b}) {
    p->begin_step(0.02, 0.005);
    ASSERT_TRUE(p->evaluate(elsewhere, r_a, nullptr).ok);
  }
  ASSERT_TRUE(a.evaluate(u, r_a, &K_a).ok);
  EXPECT_EQ(reading.offered.load(), 0) << "offered after an evaluation at other values";
  for (TetProblem* p : {&a, &b}) {
    p->begin_step(0.025, 0.005);
    ASSERT_TRUE(p->evaluate(u, r_a, nullptr).ok);
  }
  ASSERT_TRUE(a.evaluate(u, r_a, &K_a).ok);
  ASSERT_TRUE(b.evaluate(u, r_b, &K_b).ok);
  const long points = space.num_elements() * space.points_per_element();
  EXPECT_EQ(reading.offered.load(), points);
  EXPECT_EQ(refusing.offered.load(), points);
  EXPECT_EQ(r_a, r_b);
  EXPECT_EQ(Eigen::MatrixXd(K_a), Eigen::MatrixXd(K_b));
  // The reaction probes' internal force at the same state reads it too.
  Eigen::VectorXd f_a, f_b;
  ASSERT_TRUE(a.internal_force(u, f_a).ok);
  ASSERT_TRUE(b.internal_force(u, f_b).ok);
  EXPECT_EQ(reading.offered.load(), 2 * points);
  EXPECT_EQ(f_a, f_b);
}

TEST(TetProblem, InvertedElementIsNamed) {
  const TetMesh mesh =
      structured_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(0.01), {1, 1, 1}, 1);
  const TetSpace space(mesh);
  const auto law = materials::make_material("neo_hookean");
  TetDirichlet top;
  top.nodes = nodes_on_plane(mesh, 2, 0.01, 1e-12);
  top.components = {false, false, true};
  top.value = [](const Eigen::Vector3d&, double t) -> Eigen::Vector3d {
    return Eigen::Vector3d(0.0, 0.0, -0.02 * t);
  };
  TetDirichlet bottom;
  bottom.nodes = nodes_on_plane(mesh, 2, 0.0, 1e-12);
  TetProblem problem(space, *law, constant_fibres(space, Eigen::Vector3d::UnitZ()), {top, bottom});
  problem.begin_step(1.0, 1.0);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size()), r;
  const solver::EvaluationStatus s = problem.evaluate(u, r, nullptr);
  ASSERT_FALSE(s.ok);
  EXPECT_NE(s.message.find("tetrahedron"), std::string::npos) << s.message;
  EXPECT_NE(s.message.find("<= 0"), std::string::npos) << s.message;
  EXPECT_THROW(TetProblem(space, *law, {}, {top}), std::invalid_argument);
}

// The lumped volumes of the unstable mode's metric (diagonal scaling): on distorted, curved
// 10-node elements, where row sums would give the vertices negative volumes, every node gets a
// positive share, and the shares sum to the volume; likewise on 4-node elements.
TEST(TetProblem, LumpedVolumesArePositiveAndSumToTheVolume) {
  for (int order : {1, 2}) {
    const TetMesh mesh = distorted_box(order, order == 2);
    const TetSpace space(mesh);
    const auto law = materials::make_material("neo_hookean");
    TetDirichlet bottom;
    bottom.nodes = nodes_on_plane(mesh, 2, 0.0, 1e-12);
    const TetProblem problem(space, *law, constant_fibres(space, Eigen::Vector3d::UnitZ()),
                             {bottom});
    const Eigen::VectorXd v = problem.lumped_volumes();
    ASSERT_EQ(v.size(), mesh.num_nodes());
    EXPECT_GT(v.minCoeff(), 0.0) << "order " << order;
    // The element volumes are those of the analysis quadrature, which on the curved elements
    // differ from mesh_volume's by the quadrature error (1.2e-7 relative here).
    double quadrature_volume = 0.0;
    for (int e = 0; e < space.num_elements(); ++e)
      for (int q = 0; q < space.points_per_element(); ++q)
        quadrature_volume += space.dv(e)[q];
    EXPECT_NEAR(v.sum(), quadrature_volume, 1e-12 * quadrature_volume) << "order " << order;
    EXPECT_NEAR(v.sum(), mesh_volume(mesh), 1e-6 * mesh_volume(mesh)) << "order " << order;
  }
}

// The strong-ellipticity scan of a committed state (TetProblem::committed_ellipticity): distorted,
// curved 10-node elements deformed homogeneously (a linear field, reproduced exactly), the active
// tang2009 muscle after one step. Every quadrature point gives what the law's isochoric part gives
// at that F and the pre-step history (iga's EllipticityScan test is the same check on a NURBS
// block).
TEST(TetProblem, EllipticityScanGivesTheLawsValueAtEveryPoint) {
  const TetMesh mesh = distorted_box(2, true);
  const TetSpace space(mesh);
  const auto law = materials::make_material("tang2009");
  const std::vector<Eigen::Vector3d> fibres = constant_fibres(space, Eigen::Vector3d(0, 0.6, 0.8));
  TetProblem problem(space, *law, fibres, {});
  ASSERT_EQ(problem.size(), 3 * mesh.num_nodes());
  Eigen::Matrix3d F;
  F << 1.05, 0.04, 0.0, 0.0, 0.85, 0.02, 0.03, 0.0, 1.1;
  Eigen::VectorXd u(problem.size());
  for (int node = 0; node < mesh.num_nodes(); ++node)
    for (int c = 0; c < 3; ++c)
      u[problem.free_index(node, c)] = ((F - Eigen::Matrix3d::Identity()) * mesh.nodes[node])[c];
  const double dt = 2.5e-3;
  problem.begin_step(dt, dt);
  Eigen::VectorXd residual;
  ASSERT_TRUE(problem.evaluate(u, residual, nullptr).ok);
  problem.commit_step(u);

  const std::vector<continuum::PointEllipticity> scan = problem.committed_ellipticity();
  ASSERT_EQ(scan.size(), fibres.size());
  ASSERT_EQ(scan.size(),
            static_cast<std::size_t>(space.num_elements() * space.points_per_element()));
  std::vector<double> history(static_cast<std::size_t>(law->history_size())), trial(history);
  law->initial_history(history);
  for (std::size_t p = 0; p < scan.size(); ++p) {
    materials::PointInput in;
    in.F = F;
    in.fibre = fibres[p];
    in.time = dt;
    in.dt = dt;
    in.history = history;
    materials::PointResult result;
    result.history = trial;
    ASSERT_EQ(law->evaluate_isochoric(in, result, true), materials::PointStatus::ok);
    ASSERT_NEAR(scan[p].smallest,
                materials::refined_isochoric_ellipticity(F, result.S, result.tangent).smallest,
                1e-9 * law->shear_modulus())
        << "point " << p;
  }
}

}  // namespace
}  // namespace isomuscle::tet
