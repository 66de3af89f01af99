// The body's own column of elements through the depth (io/element_column_check.hpp), tiled along a
// free surface, against what it must reproduce:
// * its element tangents are the run's: scattered over the body they sum to the tangent Newton
//   assembles, at a state that varies through the body;
// * on an affine box deformed homogeneously its interior columns are the uniform layer of
//   iga/periodic_layer_stability.hpp (uniform interior B-splines, the same state), so the Bloch
//   eigenvalues agree at every wave, for each side the surface may be (top, bottom, a lateral
//   face) and for a homogeneous state other than the committed one.
#include "io/element_column_check.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include "geometry/knot_vector.hpp"
#include "geometry/nurbs_volume.hpp"
#include "iga/dof_map.hpp"
#include "iga/fibre_directions.hpp"
#include "iga/problem.hpp"
#include "io/element_layer_check.hpp"
#include "io/iga_surface_point.hpp"
#include "materials/material_factory.hpp"

namespace isomuscle::io {
namespace {

// The box [0, size] of the given degrees and elements per direction, uniform except in direction
// `graded`, whose interior breakpoints (m) are `breaks` when given; its control points at the
// Greville abscissae: an affine B-spline map (linear precision holds for any knots).
geometry::NurbsVolume box(const Eigen::Vector3d& size, const std::array<int, 3>& degrees,
                          const std::array<int, 3>& elements, int graded = -1,
                          const std::vector<double>& breaks = {}) {
  std::array<geometry::KnotVector, 3> knots;
  std::array<std::vector<double>, 3> greville;
  for (int d = 0; d < 3; ++d) {
    knots[d] = d == graded
                   ? geometry::KnotVector::clamped(degrees[d], breaks, 0.0, size[d])
                   : geometry::KnotVector::uniform_clamped(degrees[d], elements[d], 0.0, size[d]);
    for (int i = 0; i < knots[d].num_basis(); ++i) {
      double sum = 0.0;
      for (int l = 1; l <= degrees[d]; ++l)
        sum += knots[d][i + l];
      greville[d].push_back(sum / degrees[d]);
    }
  }
  std::vector<Eigen::Vector3d> points;
  for (double z : greville[2])
    for (double y : greville[1])
      for (double x : greville[0])
        points.emplace_back(x, y, z);
  std::vector<double> weights(points.size(), 1.0);
  return geometry::NurbsVolume(knots, std::move(points), std::move(weights));
}

// The active muscle (tang2009, with history) on a box, one step of 2.5 ms committed at the
// displacement u_of(X): the law, the solid and the problem live together.
struct CommittedBox {
  CommittedBox(const Eigen::Vector3d& size, const std::array<int, 3>& degrees,
               const std::array<int, 3>& elements, int graded = -1,
               const std::vector<double>& breaks = {})
      : volume(box(size, degrees, elements, graded, breaks)),
        space(volume),
        dofs(volume),
        law(materials::make_material("tang2009")),
        problem(space, dofs, *law, iga::fibre_directions(space, iga::FibreSpec::isocurve(1)),
                iga::DirichletConditions{}, {}, mixed()) {}

  static iga::ProblemOptions mixed() {
    iga::ProblemOptions options;
    options.formulation = iga::Formulation::mixed;
    return options;
  }

  // One step to u(X); returns the tangent Newton assembles there (all DOFs are free).
  template <class Displacement>
  solver::SparseMatrix commit(const Displacement& u_of) {
    Eigen::VectorXd u(problem.size());
    for (int node = 0; node < dofs.num_nodes(); ++node)
      u.segment<3>(3 * node) = u_of(dofs.position(node));
    problem.begin_step(2.5e-3, 2.5e-3);
    Eigen::VectorXd residual;
    solver::SparseMatrix K;
    EXPECT_TRUE(problem.evaluate(u, residual, &K).ok);
    problem.commit_step(u);
    return K;
  }

  geometry::NurbsVolume volume;
  iga::Space space;
  iga::DofMap dofs;
  std::unique_ptr<materials::MaterialLaw> law;
  iga::Problem problem;
};

// Shortening along y (the fibres' mean direction) by 20 % with a shear, volume kept.
Eigen::Matrix3d shortened() {
  Eigen::Matrix3d F;
  F << 1.0 / std::sqrt(0.8), 0.04, 0.0,  //
      0.0, 0.8, 0.0,                     //
      0.03, 0.0, 1.0 / std::sqrt(0.8);
  return F;
}

TEST(ElementColumn, ElementTangentsSumToTheAssembledTangent) {
  CommittedBox box({2e-3, 3e-3, 1.5e-3}, {2, 3, 2}, {2, 3, 2});
  const Eigen::Matrix3d G = shortened() - Eigen::Matrix3d::Identity();
  // Varying through the body: the homogeneous part and a bend of a tenth of the size.
  const solver::SparseMatrix assembled = box.commit([&](const Eigen::Vector3d& X) {
    return Eigen::Vector3d(
        G * X + Eigen::Vector3d(30.0 * X.z() * X.z(), 20.0 * X.x() * X.z(), -15.0 * X.x() * X.x()));
  });
  const iga::Space& space = box.space;
  Eigen::MatrixXd summed = Eigen::MatrixXd::Zero(box.problem.size(), box.problem.size());
  for (int e = 0; e < space.num_elements(); ++e) {
    const Eigen::MatrixXd Ke = box.problem.committed_element_tangent(e);
    const auto cps = space.control_points(e);
    ASSERT_EQ(Ke.rows(), 3 * static_cast<Eigen::Index>(cps.size()));
    for (std::size_t a = 0; a < cps.size(); ++a)
      for (std::size_t b = 0; b < cps.size(); ++b)
        summed.block<3, 3>(3 * box.dofs.node(cps[a]), 3 * box.dofs.node(cps[b])) +=
            Ke.block<3, 3>(3 * static_cast<Eigen::Index>(a), 3 * static_cast<Eigen::Index>(b));
  }
  // The assembled tangent keeps the upper triangle (solver/matrix_storage.hpp).
  const Eigen::MatrixXd upper(assembled);
  const Eigen::MatrixXd dense =
      upper + upper.transpose() - Eigen::MatrixXd(upper.diagonal().asDiagonal());
  EXPECT_LT((summed - dense).norm(), 1e-10 * dense.norm());
  // The same element at a homogeneous state given from outside is a different tangent.
  const iga::LayerState point = box.problem.committed_layer_state(0, 0);
  EXPECT_GT(
      (box.problem.committed_element_tangent(0, &point) - box.problem.committed_element_tangent(0))
          .norm(),
      1e-3 * dense.norm());
}

TEST(ElementColumn, OnAnAffineBoxItIsTheUniformLayer) {
  // 9 uniform spans along the surface directions leave uniform interior B-splines at the middle
  // one for degrees 2 and 3 alike. Through the depth the spans are graded (0.4, 0.8, 1.8 mm), so
  // that rows counted from the wrong side would show.
  struct Case {
    Eigen::Vector3d size;
    std::array<int, 3> elements;
    int depth;  // the graded direction
    std::vector<double> breaks;
    Eigen::Vector3d near;
    int end;
  };
  const Eigen::Vector3d flat(9e-3, 4.5e-3, 3e-3), tall(3e-3, 4.5e-3, 9e-3);
  for (const Case& c : {Case{flat, {9, 9, 3}, 2, {0.4e-3, 1.2e-3}, {4.5e-3, 2.25e-3, 3.5e-3}, 1},
                        Case{flat, {9, 9, 3}, 2, {0.4e-3, 1.2e-3}, {4.5e-3, 2.25e-3, -1e-3}, 0},
                        Case{tall, {3, 9, 9}, 0, {1.8e-3, 2.6e-3}, {4e-3, 2.25e-3, 4.5e-3}, 1}}) {
    CommittedBox box(c.size, {2, 3, 2}, c.elements, c.depth, c.breaks);
    const Eigen::Matrix3d F = shortened();
    box.commit([&](const Eigen::Vector3d& X) {
      return Eigen::Vector3d((F - Eigen::Matrix3d::Identity()) * X);
    });
    iga::LayerState other = box.problem.committed_layer_state(0, 0);
    other.F = Eigen::Vector3d(1.1, 0.75, 1.0 / 0.825).asDiagonal();
    const std::optional<SurfaceLocation> where = locate_surface_point(box.problem, c.near);
    ASSERT_TRUE(where);
    ASSERT_EQ(where->side_direction, c.depth);
    ASSERT_EQ(where->side_end, c.end);
    const iga::LayerGeometry layer = element_layer_at(box.problem, *where);
    const iga::LayerState state = box.problem.committed_layer_state(where->element, where->point);
    for (const iga::LayerState* given : {static_cast<const iga::LayerState*>(nullptr),
                                         static_cast<const iga::LayerState*>(&other)}) {
      const iga::PeriodicLayer uniform(layer, given ? *given : state);
      const iga::PeriodicLayer column = element_column_at(box.problem, *where, given);
      ASSERT_EQ(column.depth_rows(), uniform.depth_rows());
      for (const Eigen::Vector2d& theta : {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.7, 0.0),
                                           Eigen::Vector2d(0.3, -1.9), Eigen::Vector2d(3.1, 2.2)}) {
        const iga::BlochMode a = column.lowest_at(theta), b = uniform.lowest_at(theta);
        // Round-off: the tangent's volumetric entries are kappa / mu ~ 1e6 times the lowest
        // eigenvalue's scale (1.6e-9 relative seen at theta = 0).
        EXPECT_NEAR(a.eigenvalue, b.eigenvalue, 1e-8 * std::abs(b.eigenvalue))
            << "side " << c.depth << "/" << c.end << ", theta (" << theta.transpose() << ")";
        for (std::size_t r = 0; r < b.depth_amplitude.size(); ++r)
          EXPECT_NEAR(a.depth_amplitude[r], b.depth_amplitude[r], 1e-6);
      }
    }
  }
}

TEST(ElementColumn, TheLogSaysWhichReadingHolds) {
  ElementColumnCheck check;
  check.elements = 4;
  check.lowest.eigenvalue = 2.0e6;
  check.homogeneous.eigenvalue = 3.0e6;
  check.lowest.angles = {0.0, std::numbers::pi / 2};
  const double mu = 1.0e3;
  std::string text = describe(check, mu);
  EXPECT_NE(text.find("column of 4 elements"), std::string::npos) << text;
  EXPECT_NE(text.find("+2e+06 Pa/m^2 (+0.002 mu/mm^2) for a wave of inf x 4 spans"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("needs variation along the surface too"), std::string::npos) << text;
  check.lowest.eigenvalue = -1.0e5;
  text = describe(check, mu);
  EXPECT_NE(text.find("the variation of the state through the depth makes it"), std::string::npos)
      << text;
  check.homogeneous.eigenvalue = -2.0e5;
  text = describe(check, mu);
  EXPECT_NE(text.find("the shapes of the body's elements through the depth make it"),
            std::string::npos)
      << text;
}

TEST(ElementColumn, BadInputIsRefusedClearly) {
  EXPECT_THROW(iga::PeriodicLayer({}, Eigen::VectorXd::Ones(3)), std::invalid_argument);
  iga::ColumnElement element;
  element.row = {0, 1};
  element.offset = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  element.tangent = Eigen::MatrixXd::Identity(5, 5);
  EXPECT_THROW(iga::PeriodicLayer({element}, Eigen::VectorXd::Ones(2)), std::invalid_argument);
  element.tangent = Eigen::MatrixXd::Identity(6, 6);
  element.row = {0, 2};
  EXPECT_THROW(iga::PeriodicLayer({element}, Eigen::VectorXd::Ones(2)), std::invalid_argument);
  element.row = {0, 1};
  EXPECT_THROW(iga::PeriodicLayer({element}, Eigen::Vector2d(0.0, 1.0)), std::invalid_argument);
  EXPECT_NO_THROW(iga::PeriodicLayer({element}, Eigen::Vector2d(1.0, 0.0)));

  CommittedBox box({2e-3, 3e-3, 1.5e-3}, {2, 2, 2}, {2, 2, 2});
  box.commit([](const Eigen::Vector3d&) { return Eigen::Vector3d::Zero(); });
  SurfaceLocation nowhere;  // a tetrahedral location: no side
  EXPECT_THROW(element_column_at(box.problem, nowhere), std::invalid_argument);
  iga::LayerState short_history = box.problem.committed_layer_state(0, 0);
  short_history.history.pop_back();
  EXPECT_THROW(box.problem.committed_element_tangent(0, &short_history), std::invalid_argument);
  EXPECT_THROW(box.problem.committed_element_tangent(box.space.num_elements()),
               std::invalid_argument);
  iga::LayerState inverted = box.problem.committed_layer_state(0, 0);
  inverted.F = Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal();
  try {
    box.problem.committed_element_tangent(0, &inverted);
    ADD_FAILURE() << "no throw for an inverted state";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("homogeneous state on the element's geometry"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace isomuscle::io
