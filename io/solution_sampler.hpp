#pragma once
// Evaluation of a stored solution (solution_file.hpp) at material points: the displacement
// u(X) = sum_a R_a(xi) u_a of the IGA space, with xi found from the reference point X by point
// inversion of the refined solid (geometry/point_inversion.hpp), or given directly as a
// parameter of the stored geometry (exact refinement keeps the parametrisation); for a
// tetrahedral run the nodal field interpolated in the element holding X (tet/tet_locator.hpp),
// a parameter being mapped to X by the stored geometry first.
#include <Eigen/Core>
#include <memory>
#include <optional>

#include "geometry/point_inversion.hpp"
#include "io/solution_file.hpp"
#include "tet/tet_locator.hpp"

namespace isomuscle::io {

class SolutionSampler {
 public:
  // The solution must outlive the sampler.
  explicit SolutionSampler(const StoredSolution& solution);

  // u at the reference point X (m) at step `step`; nullopt when X lies outside the solid (farther
  // than the inversion's inside tolerance, 1e-9 of its size). std::out_of_range for a bad step.
  std::optional<Eigen::Vector3d> at_point(const Eigen::Vector3d& X, std::size_t step) const;
  // u at the parameter xi of the stored geometry (m); nullopt only for a tetrahedral run whose
  // mesh does not hold H(xi) (a chord of the curved boundary).
  std::optional<Eigen::Vector3d> at_parameter(const Eigen::Vector3d& xi, std::size_t step) const;

  const StoredSolution& solution() const { return solution_; }

 private:
  const StoredSolution& solution_;
  std::unique_ptr<geometry::PointInverter> inverter_;
  std::unique_ptr<tet::TetLocator> locator_;
  std::vector<Eigen::VectorXd> nodal_;  // tet: the displacement per step, 3 per node
};

}  // namespace isomuscle::io
