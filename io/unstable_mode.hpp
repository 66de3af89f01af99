#pragma once
// The mode of an unstable equilibrium: at the first converged step whose tangent is not positive
// definite (StepRecord::unstable), the tangent is assembled again AT the equilibrium and its lowest
// eigenpairs are computed for the lumped reference volumes as the metric (solver::lowest_modes):
//
//   K phi = lambda M phi,   M = diag(lumped volume of the unknown's node)   (FreeDofLayout)
//
// lambda (Pa/m^2: N/m per m^3) is lambda_rho / rho for a density rho, the square of the mode's
// angular frequency in the dynamics the quasi-static run neglects; a negative one is a direction
// along which the potential energy falls, which the muscle's mass or the smallest imperfection
// would follow away from the computed path. The eigenvector of the smallest lambda is the mode:
// where it sits (the node of its largest amplitude, the share of the volume it occupies) tells a
// buckling of the whole body from a mode of a singular layer (a clamped edge), which refinement
// makes ever softer.
//
// The share of the volume is the participation ratio of the mode's mass-weighted square: with
// e_n = V_n |phi_n|^2 (summing to 1 over the nodes n),
//   share = 1 / (V sum_n e_n^2 / V_n),
// which is 1 for a uniform mode and v / V for a mode spread evenly over a part of volume v. Its
// extent is the radius of gyration of e_n about the peak, radius^2 = sum_n e_n |X_n - X_peak|^2.
#include <Eigen/Core>
#include <filesystem>
#include <string>

#include "io/run_model.hpp"
#include "solver/nonlinear_problem.hpp"

namespace isomuscle::io {

struct UnstableMode {
  bool ok = false;
  std::string message;                                      // why no mode was found
  Eigen::VectorXd eigenvalues;                              // the lowest, ascending, Pa/m^2
  int negative = 0;                                         // how many of them are negative
  double shift = 0.0;                                       // the Lanczos shift used (Pa/m^2)
  Eigen::Vector3d peak_position = Eigen::Vector3d::Zero();  // reference position (m)
  double volume_share = 0.0;                                // in (0, 1]
  double radius = 0.0;                                      // about the peak, m
  int factorizations = 0;
  int solves = 0;
  double seconds = 0.0;
};

// Assembles the tangent of `problem` at the free values u (the converged state of the step under
// way, before its commit) and writes the lowest mode to csv_path: one row per node with a free
// unknown, its reference position x, y, z (m), its lumped volume (m^3; volume |mode|^2 is the
// node's share of the mode's mass-weighted square) and the mode's components mode_x, mode_y,
// mode_z scaled to a largest nodal amplitude of 1 (prescribed components 0). count: eigenpairs
// computed.
// Failures (the tangent cannot be evaluated, the eigensolver does not converge) are reported in
// the result, not thrown; std::runtime_error when the file cannot be written.
UnstableMode compute_unstable_mode(solver::NonlinearProblem& problem, const Eigen::VectorXd& u,
                                   const FreeDofLayout& layout,
                                   const std::filesystem::path& csv_path, int count = 3);

// "lowest eigenvalue -1.03e+05 Pa/m^2 (2 of the 3 lowest negative); the mode is largest at
// (x, y, z) m, extends 0.012 m about it and occupies 69 % of the volume (unstable_mode.csv,
// 0.0179 s)", or "no mode: " and why, for the log.
std::string describe(const UnstableMode& mode, const std::string& csv_name);

}  // namespace isomuscle::io
