#pragma once
// What the stepping loop of a run (scene_run.hpp) needs from a discretisation: the discrete
// problem, the scales of its Newton floors, the probes, the field and solution output, and the
// key results of the committed state. Implemented by the isogeometric model (iga_run_model.hpp)
// and the tetrahedral one (tet_run_model.hpp), so that both runs step, log, cut back and write
// their folders in exactly the same way.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "continuum/point_ellipticity.hpp"
#include "io/element_layer_check.hpp"
#include "io/run_summary.hpp"
#include "io/surface_location.hpp"
#include "solver/nonlinear_problem.hpp"

namespace isomuscle::io {

// A J = det F of a state and the reference position (m) of its quadrature point.
struct JacobianAt {
  double value = 0.0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

// The smallest and the largest J of a state.
struct JacobianRangeAt {
  JacobianAt smallest, largest;
};

// The committed state's J range of a discretisation's problem (iga::Problem, tet::TetProblem:
// committed_jacobian_range() and space().position(element, point)) as a JacobianRangeAt.
template <class Problem>
std::optional<JacobianRangeAt> committed_jacobian_range_of(const Problem& problem) {
  const auto& r = problem.committed_jacobian_range();
  if (!r.found())
    return std::nullopt;
  const auto at = [&](const auto& p) {
    return JacobianAt{p.value, problem.space().position(p.element, p.point)};
  };
  return JacobianRangeAt{at(r.smallest), at(r.largest)};
}

// The free unknowns of a problem as points of the mesh, for showing a vector over them (the mode of
// an unstable equilibrium, unstable_mode.hpp): per node its reference position (m) and lumped
// reference volume (m^3, the diagonal mass per unit density: iga::Problem::lumped_volumes,
// tet::TetProblem::lumped_volumes); per free unknown i its node node_of[i] and displacement
// component component_of[i].
struct FreeDofLayout {
  std::vector<Eigen::Vector3d> node_positions;
  Eigen::VectorXd node_volumes;
  std::vector<int> node_of, component_of;
};

// The law's strong ellipticity at the quadrature points of a state
// (continuum/point_ellipticity.hpp) with their reference positions (m), and the law's shear modulus
// mu (Pa) to measure it by.
struct EllipticityAt {
  double smallest = 0.0;  // e, Pa (NaN: not evaluated)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

struct MaterialEllipticityScan {
  std::vector<EllipticityAt> points;
  double shear_modulus = 0.0;
  int normals = 0;
};

// The committed state's scan of a discretisation's problem (iga::Problem, tet::TetProblem:
// committed_ellipticity(normals), space().position(element, point), law()).
template <class Problem>
MaterialEllipticityScan committed_ellipticity_of(const Problem& problem, int normals) {
  const auto points = problem.committed_ellipticity(normals);
  const int nqp = problem.space().points_per_element();
  MaterialEllipticityScan scan;
  scan.points.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int e = static_cast<int>(i) / nqp, q = static_cast<int>(i) % nqp;
    scan.points.push_back({points[i].smallest, points[i].normal, problem.space().position(e, q)});
  }
  scan.shear_modulus = problem.law().shear_modulus();
  scan.normals = normals;
  return scan;
}

// The committed state at a SurfaceLocation: the law's response at its quadrature point as the
// step evaluated it (continuum::SteppedResponse), the local state whose free surface
// surface_stability_check.hpp tests as a deformed half-space.
struct SurfacePointAt {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();          // quadrature point, reference, m
  Eigen::Vector3d surface_position = Eigen::Vector3d::Zero();  // boundary point, reference, m
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // outward unit normal there, reference
  continuum::SteppedResponse response;
  double shear_modulus = 0.0;  // mu of the law, Pa
};

// The committed state of a discretisation's problem (iga::Problem, tet::TetProblem:
// committed_response(e, q), space().position(e, q), law()) at a location.
template <class Problem>
SurfacePointAt surface_point_at(const Problem& problem, const SurfaceLocation& where) {
  SurfacePointAt out;
  out.position = problem.space().position(where.element, where.point);
  out.surface_position = where.surface_position;
  out.normal = where.normal;
  out.response = problem.committed_response(where.element, where.point);
  out.shear_modulus = problem.law().shear_modulus();
  return out;
}

// The same where a location was found (nullopt passed on).
template <class Problem>
std::optional<SurfacePointAt> surface_point_at(const Problem& problem,
                                               const std::optional<SurfaceLocation>& where) {
  if (!where)
    return std::nullopt;
  return surface_point_at(problem, *where);
}

class RunModel {
 public:
  virtual ~RunModel() = default;

  // The problem stepped in time (its predict() is used while there is no velocity to extrapolate).
  virtual solver::NonlinearProblem& problem() = 0;
  // Scales of the round-off floors of the Newton tolerances: the reference volume (m^3) and the
  // largest modulus of the law, max(kappa, mu) (Pa).
  virtual double reference_volume() const = 0;
  virtual double modulus_scale() const = 0;

  // Sizes and discretisation-specific keys written into the summary at set-up, one log line that
  // says what was built, and the decisions a user should know about.
  virtual void describe(RunSummary& summary) const = 0;
  virtual std::string setup_line() const = 0;
  virtual const std::vector<std::string>& notes() const = 0;
  // Appended to the reason when the run fails (e.g. why this set-up is hard); may be empty.
  virtual const std::string& failure_hint() const = 0;

  // Probes (probes.csv): the columns, a hook on the converged free values before they are
  // committed (reactions, pre-step histories), the values of the committed state.
  virtual const std::vector<std::string>& probe_columns() const = 0;
  virtual void before_commit(const Eigen::VectorXd& u) = 0;
  virtual void probe_values(std::vector<double>& out) = 0;
  // Reference position (m) of every point probe, by name.
  virtual std::vector<std::pair<std::string, Eigen::Vector3d>> probe_points() const = 0;

  // Output of the committed state: fields.xdmf (when fields were asked for) and solution.h5.
  virtual void write_fields() = 0;
  virtual std::size_t field_steps() const = 0;  // 0 when no fields are written
  virtual void write_solution() = 0;
  virtual std::size_t solution_steps() const = 0;
  virtual double solution_last_time() const = 0;  // s

  // The committed state.
  virtual double committed_time() const = 0;
  virtual double current_volume() const = 0;    // m^3
  virtual double max_displacement() const = 0;  // m, over the output points
  // Smallest and largest J over the quadrature points of the committed state; nullopt before the
  // first commit.
  virtual std::optional<JacobianRangeAt> committed_jacobian_range() const = 0;
  // The free unknowns as mesh points (computed when called).
  virtual FreeDofLayout free_dof_layout() const = 0;
  // The law's strong ellipticity at every quadrature point of the committed state (normals: the
  // coarse set of the search; computed when called).
  virtual MaterialEllipticityScan committed_ellipticity(int normals) const = 0;
  // The surface point of the committed state nearest `near` (reference, m); nullopt when the body
  // has no traction-free boundary.
  virtual std::optional<SurfacePointAt> committed_surface_point(
      const Eigen::Vector3d& near) const = 0;
  // The run's element tiled along the surface nearest `near` at the committed state
  // (element_layer_check.hpp). Throws (std::runtime_error, std::invalid_argument) saying why where
  // there is no such check (tetrahedra, the displacement formulation, no traction-free boundary)
  // or the element fails at the state.
  virtual ElementLayerCheck committed_element_layer(const Eigen::Vector3d& near) const = 0;
};

}  // namespace isomuscle::io
