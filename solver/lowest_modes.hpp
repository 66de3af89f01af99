#pragma once
// The lowest eigenpairs of the generalised symmetric problem
//
//   K phi = lambda W phi,      W = diag(w), w > 0,
//
// for a sparse symmetric K that may be indefinite: at an unstable equilibrium the eigenvector of
// the smallest (negative) lambda is the direction along which the potential energy falls, the
// buckling or bifurcation mode. W is a lumped (diagonal) mass per unit density, so the modes do not
// depend on how the unknowns are scaled (their size and spacing) and lambda has the units of K per
// unit volume; lambda / rho is the square of the mode's angular frequency, negative past the loss
// of stability.
//
// Method: shift-and-invert Lanczos (Spectra's SymEigsShiftSolver, implicitly restarted) on the
// scaled matrix Kt = W^-1/2 K W^-1/2, whose eigenvalues are those of the pencil and whose
// eigenvectors are psi = W^1/2 phi. The shift sigma is put just below the smallest eigenvalue, so
// that Kt - sigma I is positive definite and factorised by CHOLMOD's Cholesky, and the wanted
// eigenvalues are the ones nearest sigma, which Lanczos on (Kt - sigma I)^-1 finds first:
//   sigma = 0 when Kt itself is positive definite; otherwise -beta, beta the smallest of
//   first_shift mean|Kt_ii| 10^k (k = 0, 1, ...) for which the Cholesky of Kt + beta I succeeds,
//   then refined by bisection of log(beta) between the last failure and the success, so that
//   -sigma exceeds -lambda_min by at most the factor 10^(2^-bisections) and lambda_min is well
//   separated from the rest in the transformed spectrum.
// Only the upper triangle of K is read.
#include <Eigen/Core>
#include <string>

#include "solver/nonlinear_problem.hpp"

namespace isomuscle::solver {

struct LowestModesSettings {
  int count = 3;                     // eigenpairs wanted (fewer when the matrix is smaller)
  double relative_tolerance = 1e-8;  // Spectra's convergence tolerance of the Ritz values
  int max_restarts = 1000;
  double first_shift = 1e-12;  // of mean|Kt_ii|, the first beta tried when Kt is indefinite
  int shift_attempts = 16;     // growing beta by 10 each: up to 1e3 mean|Kt_ii|
  int bisections = 3;          // refinements of the working beta

  // Throws SettingError naming the bad setting.
  void validate() const;
};

struct LowestModes {
  bool ok = false;
  std::string message;  // why not ok
  // Ascending eigenvalues lambda (units of K per unit of w), and the eigenvectors phi as columns,
  // normalised to phi^T W phi = 1 with the largest entry of each positive.
  Eigen::VectorXd eigenvalues;
  Eigen::MatrixXd vectors;
  double shift = 0.0;      // sigma
  int factorizations = 0;  // Cholesky attempts, successful or not
  int operations = 0;      // solves with Kt - sigma I
  // Largest |Kt psi - lambda psi| over the pairs (|psi| = 1; units of lambda): the accuracy of the
  // eigenvalues.
  double max_residual = 0.0;

  // Number of negative eigenvalues among those found.
  int negative() const;
};

// The settings.count lowest eigenpairs of K phi = lambda W phi. K: square, compressed, symmetric
// (upper triangle read); weights: w, positive and finite. Throws std::invalid_argument for sizes
// or weights out of range; failures of the method (no shift works, Lanczos does not converge) are
// reported in the result.
LowestModes lowest_modes(const SparseMatrix& K, const Eigen::VectorXd& weights,
                         const LowestModesSettings& settings = {});

}  // namespace isomuscle::solver
