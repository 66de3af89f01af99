#include "solver/lowest_modes.hpp"

#include <Spectra/SymEigsShiftSolver.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "solver/cholmod_cholesky.hpp"
#include "solver/setting_error.hpp"

namespace isomuscle::solver {

namespace {

// Spectra's shift-solve operator y = (Kt - sigma I)^-1 x, by a CHOLMOD factorisation of
// Kt + beta I (beta = -sigma) made before the solver is built: set_shift only checks that the
// solver asks for the shift that was factorised.
class ShiftedCholeskySolve {
 public:
  using Scalar = double;

  ShiftedCholeskySolve(CholmodCholesky& cholesky, Eigen::Index n, double sigma, int& operations)
      : cholesky_(cholesky), n_(n), sigma_(sigma), operations_(operations) {}
  Eigen::Index rows() const { return n_; }
  Eigen::Index cols() const { return n_; }
  void set_shift(double sigma) {
    if (sigma != sigma_)
      throw std::logic_error("lowest_modes: the shift-solve was factorised for another shift");
  }
  void perform_op(const double* x_in, double* y_out) const {
    x_ = Eigen::Map<const Eigen::VectorXd>(x_in, n_);
    cholesky_.solve(x_, y_);
    Eigen::Map<Eigen::VectorXd>(y_out, n_) = y_;
    ++operations_;
  }

 private:
  CholmodCholesky& cholesky_;
  Eigen::Index n_;
  double sigma_;
  int& operations_;
  mutable Eigen::VectorXd x_, y_;
};

// Kt = W^-1/2 K W^-1/2 on the pattern of K (both triangles scaled alike; only the upper is read).
SparseMatrix scaled_matrix(const SparseMatrix& K, const Eigen::VectorXd& inv_sqrt_w) {
  SparseMatrix kt = K;
  for (int j = 0; j < kt.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(kt, j); it; ++it)
      it.valueRef() *= inv_sqrt_w[it.row()] * inv_sqrt_w[j];
  }
  kt.makeCompressed();
  return kt;
}

// The beta >= 0 of the header: the Cholesky factorisation of Kt + beta I is left in `cholesky`.
// nullopt when no beta of the ladder works.
std::optional<double> working_shift(const SparseMatrix& kt, CholmodCholesky& cholesky,
                                    const LowestModesSettings& s, int& factorizations) {
  const auto works = [&](double beta) {
    ++factorizations;
    return cholesky.factorize(kt, beta).ok;
  };
  if (works(0.0))
    return 0.0;
  const double scale = kt.diagonal().cwiseAbs().mean();
  if (!(scale > 0.0))
    return std::nullopt;
  double failed = 0.0, beta = s.first_shift * scale;
  bool found = false;
  for (int k = 0; k < s.shift_attempts; ++k, beta *= 10.0) {
    if (works(beta)) {
      found = true;
      break;
    }
    failed = beta;
  }
  if (!found)
    return std::nullopt;
  bool factor_is_beta = true;  // the last attempt was the successful one
  if (failed > 0.0) {
    for (int b = 0; b < s.bisections; ++b) {
      const double middle = std::sqrt(failed * beta);
      factor_is_beta = works(middle);
      if (factor_is_beta)
        beta = middle;
      else
        failed = middle;
    }
  }
  if (!factor_is_beta && !works(beta))  // a failed last bisection left no factorisation
    return std::nullopt;
  return beta;
}

}  // namespace

void LowestModesSettings::validate() const {
  if (count < 1)
    throw SettingError("count", "must be >= 1 (got " + std::to_string(count) + ")");
  if (!(relative_tolerance > 0.0 && relative_tolerance < 1.0))
    throw SettingError("relative_tolerance",
                       "must be in (0, 1) (got " + format_number(relative_tolerance) + ")");
  if (max_restarts < 1)
    throw SettingError("max_restarts", "must be >= 1 (got " + std::to_string(max_restarts) + ")");
  if (!(first_shift > 0.0 && std::isfinite(first_shift)))
    throw SettingError("first_shift", "must be > 0 (got " + format_number(first_shift) + ")");
  if (shift_attempts < 1)
    throw SettingError("shift_attempts",
                       "must be >= 1 (got " + std::to_string(shift_attempts) + ")");
  if (bisections < 0)
    throw SettingError("bisections", "must be >= 0 (got " + std::to_string(bisections) + ")");
}

int LowestModes::negative() const {
  return static_cast<int>((eigenvalues.array() < 0.0).count());
}

LowestModes lowest_modes(const SparseMatrix& K, const Eigen::VectorXd& weights,
                         const LowestModesSettings& settings) {
  settings.validate();
  const Eigen::Index n = K.rows();
  if (K.cols() != n || n < 2)
    throw std::invalid_argument("lowest_modes: the matrix must be square with at least 2 rows");
  if (weights.size() != n)
    throw std::invalid_argument("lowest_modes: " + std::to_string(weights.size()) +
                                " weights for a matrix of " + std::to_string(n) + " rows");
  if (!(weights.array() > 0.0).all() || !weights.allFinite())
    throw std::invalid_argument("lowest_modes: the weights must be positive and finite");

  LowestModes result;
  const Eigen::VectorXd inv_sqrt_w = weights.cwiseSqrt().cwiseInverse();
  const SparseMatrix kt = scaled_matrix(K, inv_sqrt_w);
  CholmodCholesky cholesky;
  cholesky.analyze(kt);
  const std::optional<double> beta = working_shift(kt, cholesky, settings, result.factorizations);
  if (!beta) {
    result.message = "no shift made the scaled matrix positive definite (up to " +
                     format_number(settings.first_shift * std::pow(10.0, settings.shift_attempts)) +
                     " mean|K_ii|)";
    return result;
  }
  result.shift = -*beta;

  // Lanczos with ncv vectors: 2 count + 1 at least, 20 when there is room (faster convergence for
  // the clustered low end of a stiffness spectrum).
  const Eigen::Index nev = std::min<Eigen::Index>(settings.count, n - 1);
  const Eigen::Index ncv = std::min<Eigen::Index>(n, std::max<Eigen::Index>(2 * nev + 1, 20));
  ShiftedCholeskySolve op(cholesky, n, result.shift, result.operations);
  Spectra::SymEigsShiftSolver<ShiftedCholeskySolve> eigs(op, nev, ncv, result.shift);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestMagn, settings.max_restarts, settings.relative_tolerance,
               Spectra::SortRule::SmallestAlge);
  if (eigs.info() != Spectra::CompInfo::Successful) {
    result.message = "the Lanczos iteration did not converge in " +
                     std::to_string(settings.max_restarts) + " restarts (" +
                     std::to_string(result.operations) + " solves)";
    return result;
  }
  result.eigenvalues = eigs.eigenvalues();
  const Eigen::MatrixXd psi = eigs.eigenvectors();
  result.vectors.resize(n, psi.cols());
  for (Eigen::Index k = 0; k < psi.cols(); ++k) {
    const Eigen::VectorXd r =
        kt.selfadjointView<Eigen::Upper>() * psi.col(k) - result.eigenvalues[k] * psi.col(k);
    result.max_residual = std::max(result.max_residual, r.norm() / psi.col(k).norm());
    // phi = W^-1/2 psi with phi^T W phi = |psi|^2 = 1; sign: largest entry positive.
    Eigen::VectorXd phi = inv_sqrt_w.cwiseProduct(psi.col(k)) / psi.col(k).norm();
    Eigen::Index at = 0;
    phi.cwiseAbs().maxCoeff(&at);
    if (phi[at] < 0.0)
      phi = -phi;
    result.vectors.col(k) = phi;
  }
  result.ok = true;
  return result;
}

}  // namespace isomuscle::solver
