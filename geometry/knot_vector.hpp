#pragma once
// Knot vectors of B-spline bases (thesis 5.2): a non-decreasing sequence U = {u_0 ... u_m} with
// degree p and n + 1 = m - p basis functions. Clamped ("open") vectors repeat the end knots p + 1
// times; periodic (unclamped) vectors are converted to clamped form exactly by knot insertion
// (see refinement.hpp), so everything downstream may assume clamped vectors.
#include <vector>

namespace isomuscle::geometry {

class KnotVector {
 public:
  KnotVector() = default;
  // Throws std::invalid_argument when degree < 0, the sequence decreases, is not finite, or is too
  // short for the degree (needs at least 2(p + 1) knots).
  KnotVector(std::vector<double> knots, int degree);

  // Clamped vector on [a, b] with the given interior knots (each listed once per multiplicity).
  static KnotVector clamped(int degree, const std::vector<double>& interior, double a = 0.0,
                            double b = 1.0);
  // Clamped vector with n_spans equal spans on [a, b].
  static KnotVector uniform_clamped(int degree, int n_spans, double a = 0.0, double b = 1.0);

  int degree() const { return degree_; }
  const std::vector<double>& knots() const { return knots_; }
  double operator[](int i) const { return knots_[i]; }
  int size() const { return static_cast<int>(knots_.size()); }
  int num_basis() const { return size() - degree_ - 1; }

  // Parametric domain [u_p, u_{n+1}].
  double domain_begin() const { return knots_[degree_]; }
  double domain_end() const { return knots_[num_basis()]; }

  // Span index i with u_i <= u < u_{i+1}, p <= i <= n (u at the end of the domain maps to the last
  // non-empty span). u is clamped to the domain.
  int find_span(double u) const;
  // Distinct knot values within the domain (the element boundaries), ascending.
  std::vector<double> breakpoints() const;
  // Number of times u occurs (exact comparison).
  int multiplicity(double u) const;
  bool is_clamped() const;

 private:
  std::vector<double> knots_;
  int degree_ = 0;
};

}  // namespace isomuscle::geometry
