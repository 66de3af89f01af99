// Knot vectors of B-spline bases (thesis 5.2; Piegl & Tiller, The NURBS Book, 2nd ed., 2.2).
#include "geometry/knot_vector.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "geometry/bspline_basis.hpp"

namespace isomuscle::geometry {

namespace {

std::string describe(const std::vector<double>& knots) {
  std::ostringstream os;
  os << "{";
  const std::size_t shown = std::min<std::size_t>(knots.size(), 24);
  for (std::size_t i = 0; i < shown; ++i) {
    os << (i ? ", " : "") << knots[i];
  }
  if (shown < knots.size()) {
    os << ", ... (" << knots.size() << " knots)";
  }
  os << "}";
  return os.str();
}

}  // namespace

// Validates U = {u_0 <= ... <= u_m} for degree p (NURBS Book 2.2): m + 1 >= 2(p + 1), every knot
// finite, no knot repeated more than p + 1 times (such a function would vanish identically), and
// a non-empty parametric domain [u_p, u_{m-p}]. Parameters are dimensionless.
KnotVector::KnotVector(std::vector<double> knots, int degree)
    : knots_(std::move(knots)), degree_(degree) {
  if (degree_ < 0 || degree_ > kMaxDegree) {
    throw std::invalid_argument("KnotVector: degree " + std::to_string(degree_) +
                                " is outside the supported range 0.." + std::to_string(kMaxDegree));
  }
  const int m = static_cast<int>(knots_.size());
  if (m < 2 * (degree_ + 1)) {
    throw std::invalid_argument("KnotVector: " + std::to_string(m) + " knots " + describe(knots_) +
                                " are too few for degree " + std::to_string(degree_) +
                                " (need at least " + std::to_string(2 * (degree_ + 1)) + ")");
  }
  for (int i = 0; i < m; ++i) {
    if (!std::isfinite(knots_[i])) {
      throw std::invalid_argument("KnotVector: knot " + std::to_string(i) + " is not finite in " +
                                  describe(knots_));
    }
    if (i > 0 && knots_[i] < knots_[i - 1]) {
      throw std::invalid_argument("KnotVector: knots decrease at index " + std::to_string(i) +
                                  " in " + describe(knots_) + "; knots must be non-decreasing");
    }
  }
  for (int i = 0; i < m;) {
    int j = i;
    while (j + 1 < m && knots_[j + 1] == knots_[i]) {
      ++j;
    }
    if (j - i + 1 > degree_ + 1) {
      std::ostringstream os;
      os << "KnotVector: knot " << knots_[i] << " is repeated " << (j - i + 1) << " times in "
         << describe(knots_) << "; at most degree + 1 = " << (degree_ + 1) << " is allowed";
      throw std::invalid_argument(os.str());
    }
    i = j + 1;
  }
  if (!(domain_begin() < domain_end())) {
    throw std::invalid_argument("KnotVector: empty parametric domain [u_p, u_{n+1}] = [" +
                                std::to_string(domain_begin()) + ", " +
                                std::to_string(domain_end()) + "] in " + describe(knots_));
  }
}

// Open knot vector {a x (p+1), interior..., b x (p+1)} (NURBS Book eq. 2.13).
KnotVector KnotVector::clamped(int degree, const std::vector<double>& interior, double a,
                               double b) {
  if (!(std::isfinite(a) && std::isfinite(b) && a < b)) {
    throw std::invalid_argument("KnotVector::clamped: need finite a < b, got [" +
                                std::to_string(a) + ", " + std::to_string(b) + "]");
  }
  if (degree < 0) {
    throw std::invalid_argument("KnotVector::clamped: degree " + std::to_string(degree) +
                                " must be >= 0");
  }
  std::vector<double> sorted = interior;
  std::sort(sorted.begin(), sorted.end());
  for (double u : sorted) {
    if (!(u > a && u < b)) {
      throw std::invalid_argument("KnotVector::clamped: interior knot " + std::to_string(u) +
                                  " is not strictly inside (" + std::to_string(a) + ", " +
                                  std::to_string(b) + ")");
    }
  }
  std::vector<double> knots(static_cast<std::size_t>(degree + 1), a);
  knots.insert(knots.end(), sorted.begin(), sorted.end());
  knots.insert(knots.end(), static_cast<std::size_t>(degree + 1), b);
  return KnotVector(std::move(knots), degree);
}

// Open knot vector with n_spans equal spans on [a, b].
KnotVector KnotVector::uniform_clamped(int degree, int n_spans, double a, double b) {
  if (n_spans < 1) {
    throw std::invalid_argument(
        "KnotVector::uniform_clamped: n_spans = " + std::to_string(n_spans) + " must be >= 1");
  }
  std::vector<double> interior;
  interior.reserve(static_cast<std::size_t>(n_spans - 1));
  for (int i = 1; i < n_spans; ++i) {
    interior.push_back(a + (b - a) * static_cast<double>(i) / static_cast<double>(n_spans));
  }
  return clamped(degree, interior, a, b);
}

// Span search (NURBS Book A2.1) by bisection over u_p..u_{n+1}; u outside the domain is clamped
// to it, u = u_{n+1} maps to the last non-empty span.
int KnotVector::find_span(double u) const {
  if (std::isnan(u)) {
    throw std::invalid_argument("KnotVector::find_span: parameter is NaN");
  }
  const int n = num_basis() - 1;
  const double end = knots_[n + 1];
  if (u >= end) {
    int i = n;
    while (knots_[i] == end) {
      --i;
    }
    return i;
  }
  u = std::max(u, knots_[degree_]);
  const auto first = knots_.begin() + degree_;
  const auto last = knots_.begin() + n + 2;
  return static_cast<int>(std::upper_bound(first, last, u) - knots_.begin()) - 1;
}

// Distinct knot values in [u_p, u_{n+1}], ascending.
std::vector<double> KnotVector::breakpoints() const {
  std::vector<double> out;
  const int n = num_basis() - 1;
  for (int i = degree_; i <= n + 1; ++i) {
    if (out.empty() || knots_[i] != out.back()) {
      out.push_back(knots_[i]);
    }
  }
  return out;
}

int KnotVector::multiplicity(double u) const {
  return static_cast<int>(std::count(knots_.begin(), knots_.end(), u));
}

// Clamped ("open"): u_0 = ... = u_p and u_{m-p} = ... = u_m.
bool KnotVector::is_clamped() const {
  const int m = size() - 1;
  return knots_[0] == knots_[degree_] && knots_[m - degree_] == knots_[m];
}

}  // namespace isomuscle::geometry
