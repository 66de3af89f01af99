#include "solver/cholmod_cholesky.hpp"

#include <cholmod.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace isomuscle::solver {

namespace {

std::string status_text(int status) {
  switch (status) {
    case CHOLMOD_OK:
      return "ok";
    case CHOLMOD_NOT_INSTALLED:
      return "method not installed";
    case CHOLMOD_OUT_OF_MEMORY:
      return "out of memory";
    case CHOLMOD_TOO_LARGE:
      return "integer overflow (problem too large)";
    case CHOLMOD_INVALID:
      return "invalid input";
    case CHOLMOD_GPU_PROBLEM:
      return "GPU error";
    case CHOLMOD_NOT_POSDEF:
      return "matrix not positive definite";
    case CHOLMOD_DSMALL:
      return "diagonal of L tiny";
    default:
      return "status " + std::to_string(status);
  }
}

std::string ordering_name(int ordering) {
  switch (ordering) {
    case CHOLMOD_NATURAL:
      return "natural";
    case CHOLMOD_GIVEN:
      return "given";
    case CHOLMOD_AMD:
      return "AMD";
    case CHOLMOD_METIS:
      return "METIS";
    case CHOLMOD_NESDIS:
      return "NESDIS";
    case CHOLMOD_COLAMD:
      return "COLAMD";
    default:
      return "ordering " + std::to_string(ordering);
  }
}

// A CHOLMOD view of an Eigen CSC matrix (no copy); stype +1 reads the upper triangle only.
cholmod_sparse view_of(const SparseMatrix& a) {
  cholmod_sparse view{};
  view.nrow = static_cast<std::size_t>(a.rows());
  view.ncol = static_cast<std::size_t>(a.cols());
  view.nzmax = static_cast<std::size_t>(a.nonZeros());
  view.p = const_cast<int*>(a.outerIndexPtr());
  view.i = const_cast<int*>(a.innerIndexPtr());
  view.nz = nullptr;
  view.x = const_cast<double*>(a.valuePtr());
  view.z = nullptr;
  view.stype = 1;
  view.itype = CHOLMOD_INT;
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = 1;
  view.packed = 1;
  return view;
}

void check_matrix(const SparseMatrix& a, const char* where) {
  if (a.rows() != a.cols() || !a.isCompressed()) {
    throw std::invalid_argument(
        std::string("CholmodCholesky::") + where +
        ": the matrix must be square and compressed (got " + std::to_string(a.rows()) + " x " +
        std::to_string(a.cols()) +
        (a.isCompressed() ? "" : ", not compressed: call makeCompressed()") + ")");
  }
}

}  // namespace

struct CholmodCholesky::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  cholmod_dense* x = nullptr;  // solve2 workspace, reused
  cholmod_dense* y = nullptr;
  cholmod_dense* e = nullptr;
  bool numeric_ok = false;
  double rcond = 0.0;
  double lnz = 0.0;
  double flops = 0.0;
  int ordering = -1;

  explicit Impl(CholeskyOrdering choice) {
    cholmod_start(&common);
    common.supernodal = CHOLMOD_SUPERNODAL;
    common.final_asis = 1;
    common.quick_return_if_not_posdef = 1;
    common.print = 0;  // failures are reported through the returned status, not printed
    switch (choice) {
      case CholeskyOrdering::Default:
        break;
      case CholeskyOrdering::Amd:
        common.nmethods = 1;
        common.method[0].ordering = CHOLMOD_AMD;
        break;
      case CholeskyOrdering::Metis:
        common.nmethods = 1;
        common.method[0].ordering = CHOLMOD_METIS;
        break;
      case CholeskyOrdering::Nesdis:
        common.nmethods = 1;
        common.method[0].ordering = CHOLMOD_NESDIS;
        break;
    }
  }
  ~Impl() {
    cholmod_free_factor(&factor, &common);
    cholmod_free_dense(&x, &common);
    cholmod_free_dense(&y, &common);
    cholmod_free_dense(&e, &common);
    cholmod_finish(&common);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
};

CholmodCholesky::CholmodCholesky(CholeskyOrdering ordering)
    : impl_(std::make_unique<Impl>(ordering)) {}
CholmodCholesky::~CholmodCholesky() = default;
CholmodCholesky::CholmodCholesky(CholmodCholesky&&) noexcept = default;
CholmodCholesky& CholmodCholesky::operator=(CholmodCholesky&&) noexcept = default;

// Symbolic factorisation: ordering P minimising fill of L in P A P^T = L L^T, elimination tree,
// supernodes (cholmod_analyze).
void CholmodCholesky::analyze(const SparseMatrix& a) {
  check_matrix(a, "analyze");
  Impl& s = *impl_;
  cholmod_free_factor(&s.factor, &s.common);
  s.numeric_ok = false;
  cholmod_sparse view = view_of(a);
  s.factor = cholmod_analyze(&view, &s.common);
  if (s.factor == nullptr || s.common.status < CHOLMOD_OK) {
    cholmod_free_factor(&s.factor, &s.common);
    throw std::runtime_error("CHOLMOD symbolic analysis of a " + std::to_string(a.rows()) + " x " +
                             std::to_string(a.cols()) + " matrix with " +
                             std::to_string(a.nonZeros()) +
                             " entries failed: " + status_text(s.common.status));
  }
  s.lnz = s.common.lnz;
  s.flops = s.common.fl;
  s.ordering = s.factor->ordering;
}

// Numeric factorisation P (A + shift I) P^T = L L^T (cholmod_factorize_p), reusing the symbolic
// analysis.
CholeskyStatus CholmodCholesky::factorize(const SparseMatrix& a, double shift) {
  check_matrix(a, "factorize");
  Impl& s = *impl_;
  if (s.factor == nullptr) {
    throw std::logic_error("CholmodCholesky::factorize called before analyze");
  }
  if (static_cast<std::size_t>(a.rows()) != s.factor->n) {
    throw std::invalid_argument("CholmodCholesky::factorize: matrix has " +
                                std::to_string(a.rows()) + " rows but the analysis was for " +
                                std::to_string(s.factor->n));
  }
  cholmod_sparse view = view_of(a);
  double beta[2] = {shift, 0.0};
  const int ok = cholmod_factorize_p(&view, beta, nullptr, 0, s.factor, &s.common);
  CholeskyStatus status;
  s.numeric_ok = false;
  s.rcond = 0.0;
  if (s.common.status == CHOLMOD_NOT_POSDEF) {
    status.not_positive_definite = true;
    status.failed_column = static_cast<int>(s.factor->minor);
    status.message = "Cholesky factorisation failed: the matrix is not positive definite (pivot " +
                     std::to_string(s.factor->minor) + " of " + std::to_string(s.factor->n) +
                     " in the fill-reducing order is <= 0)";
    return status;
  }
  if (!ok || s.common.status < CHOLMOD_OK) {
    status.message = "Cholesky factorisation failed: CHOLMOD " + status_text(s.common.status);
    return status;
  }
  s.numeric_ok = true;
  s.rcond = cholmod_rcond(s.factor, &s.common);
  status.ok = true;
  status.failed_column = -1;
  return status;
}

// x = A^{-1} b = P^T L^{-T} L^{-1} P b (cholmod_solve2 with reused workspace).
void CholmodCholesky::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  Impl& s = *impl_;
  if (!s.numeric_ok) {
    throw std::logic_error("CholmodCholesky::solve called without a successful factorisation");
  }
  const auto n = static_cast<Eigen::Index>(s.factor->n);
  if (b.size() != n) {
    throw std::invalid_argument("CholmodCholesky::solve: right-hand side has size " +
                                std::to_string(b.size()) + ", the matrix " + std::to_string(n));
  }
  cholmod_dense rhs{};
  rhs.nrow = static_cast<std::size_t>(n);
  rhs.ncol = 1;
  rhs.nzmax = static_cast<std::size_t>(n);
  rhs.d = static_cast<std::size_t>(n);
  rhs.x = const_cast<double*>(b.data());
  rhs.z = nullptr;
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  if (!cholmod_solve2(CHOLMOD_A, s.factor, &rhs, nullptr, &s.x, nullptr, &s.y, &s.e, &s.common)) {
    throw std::runtime_error("CHOLMOD solve failed: " + status_text(s.common.status));
  }
  x.resize(n);
  const auto* values = static_cast<const double*>(s.x->x);
  std::copy(values, values + n, x.data());
}

// cholmod_change_factor to CHOLMOD_PATTERN: a supernodal factor keeps its supernodal symbolic
// structure (only L->x is freed), a simplicial one its permutation and column counts.
void CholmodCholesky::release_numeric() {
  Impl& s = *impl_;
  s.numeric_ok = false;
  if (s.factor == nullptr || s.factor->xtype == CHOLMOD_PATTERN)
    return;
  if (!cholmod_change_factor(CHOLMOD_PATTERN, s.factor->is_ll, s.factor->is_super, 1, 1, s.factor,
                             &s.common)) {
    throw std::runtime_error("CHOLMOD could not free the numeric factor: " +
                             status_text(s.common.status));
  }
}

bool CholmodCholesky::analyzed() const {
  return impl_->factor != nullptr;
}
bool CholmodCholesky::factorized() const {
  return impl_->numeric_ok;
}
double CholmodCholesky::rcond() const {
  return impl_->rcond;
}
double CholmodCholesky::factor_nonzeros() const {
  return impl_->lnz;
}
double CholmodCholesky::factor_flops() const {
  return impl_->flops;
}
std::string CholmodCholesky::ordering_used() const {
  return impl_->factor == nullptr ? "none" : ordering_name(impl_->ordering);
}
std::vector<int> CholmodCholesky::permutation() const {
  const cholmod_factor* factor = impl_->factor;
  if (factor == nullptr || factor->Perm == nullptr) {
    return {};
  }
  const auto* perm = static_cast<const int*>(factor->Perm);
  return std::vector<int>(perm, perm + factor->n);
}

}  // namespace isomuscle::solver
