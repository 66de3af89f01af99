#pragma once
// Univariate kernels of exact refinement (The NURBS Book A5.4, A5.9 and knot insertion to full
// multiplicity), written once for a bundle of control polygons: row i of Line::P holds the
// homogeneous coordinates (w x, w y, w z, w) of every control line at index i along one parametric
// direction. refinement.cpp applies them to curves, surfaces and volumes; nothing else should need
// this header.
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace isomuscle::geometry::detail {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct Line {
  std::vector<double> U;
  int p = 0;
  RowMatrix P;  // count() rows
  int count() const { return static_cast<int>(U.size()) - p - 1; }
  double begin() const { return U[static_cast<std::size_t>(p)]; }
  double end() const { return U[static_cast<std::size_t>(count())]; }
  int multiplicity(double u) const;
};

// Throws std::invalid_argument("<where>: <what>").
[[noreturn]] void fail(const std::string& where, const std::string& what);

// Inserts all values of X (any order), each in [u_p, u_{n+1}], final multiplicities <= p + 1.
Line refine_line(const Line& in, std::vector<double> X, const std::string& where);
// Clamped representation of the same geometry on [u_p, u_{n+1}].
Line clamp_line(const Line& in);
// The pieces over [u_p, u] and [u, u_{n+1}], u strictly inside.
std::pair<Line, Line> split_line(const Line& in, double u, const std::string& where);
// The clamped piece over [a, b].
Line extract_line(const Line& in, double a, double b, const std::string& where);
// Degree elevation by t >= 0 of a clamped line without interior discontinuities.
Line elevate_line(const Line& in, int t, const std::string& where);

}  // namespace isomuscle::geometry::detail
