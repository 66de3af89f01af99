// Exact refinement of NURBS curves, surfaces and volumes (thesis 5.3; The NURBS Book A5.4, A5.9).
// The univariate kernels (refinement_kernels.hpp) work on a bundle of control polygons ("Line": row
// i holds the homogeneous coordinates of every control line at index i along the direction); here
// they are applied to curves, surfaces and volumes by packing the net along one direction.
#include "geometry/refinement.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <stdexcept>
#include <string>

#include "geometry/bspline_basis.hpp"
#include "geometry/refinement_kernels.hpp"

namespace isomuscle::geometry {

namespace {

using detail::clamp_line;
using detail::elevate_line;
using detail::extract_line;
using detail::fail;
using detail::Line;
using detail::refine_line;
using detail::split_line;

// ---- Packing curves, surfaces and volumes into lines along one direction ----

struct Tensor {
  int dims = 1;
  std::array<std::vector<double>, 3> U;
  std::array<int, 3> p = {0, 0, 0};
  std::array<int, 3> n = {1, 1, 1};
  std::vector<Eigen::Vector4d> H;  // (w x, w y, w z, w), index i + n0 (j + n1 k)
};

Eigen::Vector4d homogeneous(const Eigen::Vector3d& x, double w) {
  return Eigen::Vector4d(w * x.x(), w * x.y(), w * x.z(), w);
}

void check_dir(int dir, int dims, const std::string& where) {
  if (dir < 0 || dir >= dims) {
    fail(where, "direction " + std::to_string(dir) + " must be in 0.." + std::to_string(dims - 1) +
                    (dims == 2 ? " (u, v)" : " (u, v, w)"));
  }
}

Line take_line(const Tensor& T, int d) {
  Line l;
  l.U = T.U[d];
  l.p = T.p[d];
  const int others = static_cast<int>(T.H.size()) / T.n[d];
  l.P.resize(T.n[d], 4 * others);
  for (int k = 0; k < T.n[2]; ++k) {
    for (int j = 0; j < T.n[1]; ++j) {
      for (int i = 0; i < T.n[0]; ++i) {
        const int along = d == 0 ? i : (d == 1 ? j : k);
        const int other = d == 0 ? j + T.n[1] * k : (d == 1 ? i + T.n[0] * k : i + T.n[0] * j);
        l.P.block<1, 4>(along, 4 * other) =
            T.H[static_cast<std::size_t>(i + T.n[0] * (j + T.n[1] * k))].transpose();
      }
    }
  }
  return l;
}

Tensor put_line(const Tensor& T, int d, const Line& l) {
  Tensor out = T;
  out.U[d] = l.U;
  out.p[d] = l.p;
  out.n[d] = l.count();
  out.H.assign(static_cast<std::size_t>(out.n[0] * out.n[1] * out.n[2]), Eigen::Vector4d::Zero());
  for (int k = 0; k < out.n[2]; ++k) {
    for (int j = 0; j < out.n[1]; ++j) {
      for (int i = 0; i < out.n[0]; ++i) {
        const int along = d == 0 ? i : (d == 1 ? j : k);
        const int other =
            d == 0 ? j + out.n[1] * k : (d == 1 ? i + out.n[0] * k : i + out.n[0] * j);
        out.H[static_cast<std::size_t>(i + out.n[0] * (j + out.n[1] * k))] =
            l.P.block<1, 4>(along, 4 * other).transpose();
      }
    }
  }
  return out;
}

void cartesian(const Tensor& T, std::vector<Eigen::Vector3d>& pts, std::vector<double>& w) {
  pts.resize(T.H.size());
  w.resize(T.H.size());
  for (std::size_t a = 0; a < T.H.size(); ++a) {
    w[a] = T.H[a][3];
    pts[a] = T.H[a].head<3>() / T.H[a][3];
  }
}

Tensor to_tensor(const NurbsCurve& c) {
  Tensor T;
  T.dims = 1;
  T.U[0] = c.knots().knots();
  T.p[0] = c.degree();
  T.n[0] = c.count();
  for (int i = 0; i < c.count(); ++i) {
    T.H.push_back(homogeneous(c.point(i), c.weight(i)));
  }
  return T;
}

Tensor to_tensor(const NurbsSurface& s) {
  Tensor T;
  T.dims = 2;
  T.U[0] = s.knots_u().knots();
  T.U[1] = s.knots_v().knots();
  T.p = {s.knots_u().degree(), s.knots_v().degree(), 0};
  T.n = {s.count_u(), s.count_v(), 1};
  for (std::size_t a = 0; a < s.points().size(); ++a) {
    T.H.push_back(homogeneous(s.points()[a], s.weights()[a]));
  }
  return T;
}

Tensor to_tensor(const NurbsVolume& v) {
  Tensor T;
  T.dims = 3;
  for (int d = 0; d < 3; ++d) {
    T.U[d] = v.knots(d).knots();
    T.p[d] = v.degree(d);
    T.n[d] = v.count(d);
  }
  for (std::size_t a = 0; a < v.points().size(); ++a) {
    T.H.push_back(homogeneous(v.points()[a], v.weights()[a]));
  }
  return T;
}

template <class Geometry>
Geometry from_tensor(const Tensor& T);

template <>
NurbsCurve from_tensor<NurbsCurve>(const Tensor& T) {
  std::vector<Eigen::Vector3d> pts;
  std::vector<double> w;
  cartesian(T, pts, w);
  return NurbsCurve(KnotVector(T.U[0], T.p[0]), std::move(pts), std::move(w));
}

template <>
NurbsSurface from_tensor<NurbsSurface>(const Tensor& T) {
  std::vector<Eigen::Vector3d> pts;
  std::vector<double> w;
  cartesian(T, pts, w);
  return NurbsSurface(KnotVector(T.U[0], T.p[0]), KnotVector(T.U[1], T.p[1]), std::move(pts),
                      std::move(w));
}

template <>
NurbsVolume from_tensor<NurbsVolume>(const Tensor& T) {
  std::vector<Eigen::Vector3d> pts;
  std::vector<double> w;
  cartesian(T, pts, w);
  return NurbsVolume(
      {KnotVector(T.U[0], T.p[0]), KnotVector(T.U[1], T.p[1]), KnotVector(T.U[2], T.p[2])},
      std::move(pts), std::move(w));
}

std::string kind_name(int dims) {
  return dims == 1 ? "curve" : (dims == 2 ? "surface" : "volume");
}

// Applies a line operation along direction dir of a curve, surface or volume.
template <class Geometry, class Op>
Geometry along(const Geometry& g, int dir, const char* name, Op&& op) {
  const Tensor T = to_tensor(g);
  const std::string where = std::string(name) + " (" + kind_name(T.dims) +
                            (T.dims > 1 ? ", direction " + std::to_string(dir) : "") + ")";
  check_dir(dir, T.dims, where);
  return from_tensor<Geometry>(put_line(T, dir, op(take_line(T, dir), where)));
}

template <class Geometry>
std::pair<Geometry, Geometry> split_along(const Geometry& g, int dir, double u) {
  const Tensor T = to_tensor(g);
  const std::string where = "split (" + kind_name(T.dims) +
                            (T.dims > 1 ? ", direction " + std::to_string(dir) : "") + ")";
  check_dir(dir, T.dims, where);
  const auto pieces = split_line(take_line(T, dir), u, where);
  return {from_tensor<Geometry>(put_line(T, dir, pieces.first)),
          from_tensor<Geometry>(put_line(T, dir, pieces.second))};
}

auto refine_op(const std::vector<double>& X) {
  return [&X](const Line& l, const std::string& where) { return refine_line(l, X, where); };
}

std::vector<double> repeated(double u, int times, const char* name) {
  if (times < 1 || times > kMaxDegree + 1) {
    throw std::invalid_argument(std::string(name) + ": times = " + std::to_string(times) +
                                " must be in 1..degree + 1 (at most " +
                                std::to_string(kMaxDegree + 1) + ")");
  }
  return std::vector<double>(static_cast<std::size_t>(times), u);
}

auto uniform_op(int n_per_span) {
  return [n_per_span](const Line& l, const std::string& where) {
    if (n_per_span < 0) {
      fail(where, "n_per_span = " + std::to_string(n_per_span) + " must be >= 0");
    }
    return refine_line(l, uniform_refinement_knots(KnotVector(l.U, l.p), n_per_span), where);
  };
}

auto elevate_op(int t) {
  return [t](const Line& l, const std::string& where) { return elevate_line(l, t, where); };
}

auto clamp_op() {
  return [](const Line& l, const std::string&) { return clamp_line(l); };
}

auto extract_op(double a, double b) {
  return [a, b](const Line& l, const std::string& where) { return extract_line(l, a, b, where); };
}

}  // namespace

// Every non-empty span [u_i, u_{i+1}] gets the knots u_i + (u_{i+1} - u_i) k / (n + 1), k = 1..n.
std::vector<double> uniform_refinement_knots(const KnotVector& kv, int n_per_span) {
  if (n_per_span < 0) {
    throw std::invalid_argument(
        "uniform_refinement_knots: n_per_span = " + std::to_string(n_per_span) + " must be >= 0");
  }
  const std::vector<double> bp = kv.breakpoints();
  std::vector<double> out;
  for (std::size_t s = 0; s + 1 < bp.size(); ++s) {
    for (int k = 1; k <= n_per_span; ++k) {
      out.push_back(bp[s] + (bp[s + 1] - bp[s]) * static_cast<double>(k) / (n_per_span + 1));
    }
  }
  return out;
}

// ---- Curves ----
NurbsCurve insert_knot(const NurbsCurve& c, double u, int times) {
  return along(c, 0, "insert_knot", refine_op(repeated(u, times, "insert_knot")));
}
NurbsCurve refine_knots(const NurbsCurve& c, const std::vector<double>& X) {
  return along(c, 0, "refine_knots", refine_op(X));
}
NurbsCurve refine_uniform(const NurbsCurve& c, int n) {
  return along(c, 0, "refine_uniform", uniform_op(n));
}
NurbsCurve elevate_degree(const NurbsCurve& c, int t) {
  return along(c, 0, "elevate_degree", elevate_op(t));
}
NurbsCurve make_clamped(const NurbsCurve& c) {
  return along(c, 0, "make_clamped", clamp_op());
}
std::pair<NurbsCurve, NurbsCurve> split(const NurbsCurve& c, double u) {
  return split_along(c, 0, u);
}
NurbsCurve extract(const NurbsCurve& c, double a, double b) {
  return along(c, 0, "extract", extract_op(a, b));
}

// ---- Surfaces ----
NurbsSurface insert_knot(const NurbsSurface& s, int dir, double u, int times) {
  return along(s, dir, "insert_knot", refine_op(repeated(u, times, "insert_knot")));
}
NurbsSurface refine_knots(const NurbsSurface& s, int dir, const std::vector<double>& X) {
  return along(s, dir, "refine_knots", refine_op(X));
}
NurbsSurface refine_uniform(const NurbsSurface& s, int dir, int n) {
  return along(s, dir, "refine_uniform", uniform_op(n));
}
NurbsSurface elevate_degree(const NurbsSurface& s, int dir, int t) {
  return along(s, dir, "elevate_degree", elevate_op(t));
}
NurbsSurface make_clamped(const NurbsSurface& s, int dir) {
  return along(s, dir, "make_clamped", clamp_op());
}
NurbsSurface make_clamped(const NurbsSurface& s) {
  return make_clamped(make_clamped(s, 0), 1);
}
std::pair<NurbsSurface, NurbsSurface> split(const NurbsSurface& s, int dir, double u) {
  return split_along(s, dir, u);
}
NurbsSurface extract(const NurbsSurface& s, int dir, double a, double b) {
  return along(s, dir, "extract", extract_op(a, b));
}

// ---- Volumes ----
NurbsVolume insert_knot(const NurbsVolume& v, int dir, double u, int times) {
  return along(v, dir, "insert_knot", refine_op(repeated(u, times, "insert_knot")));
}
NurbsVolume refine_knots(const NurbsVolume& v, int dir, const std::vector<double>& X) {
  return along(v, dir, "refine_knots", refine_op(X));
}
NurbsVolume refine_uniform(const NurbsVolume& v, int dir, int n) {
  return along(v, dir, "refine_uniform", uniform_op(n));
}
NurbsVolume refine_uniform(const NurbsVolume& v, const std::array<int, 3>& n) {
  return refine_uniform(refine_uniform(refine_uniform(v, 0, n[0]), 1, n[1]), 2, n[2]);
}
NurbsVolume elevate_degree(const NurbsVolume& v, int dir, int t) {
  return along(v, dir, "elevate_degree", elevate_op(t));
}
NurbsVolume elevate_to(const NurbsVolume& v, const std::array<int, 3>& degrees) {
  NurbsVolume out = v;
  for (int d = 0; d < 3; ++d) {
    out = elevate_degree(out, d, std::max(0, degrees[d] - out.degree(d)));
  }
  return out;
}
NurbsVolume make_clamped(const NurbsVolume& v, int dir) {
  return along(v, dir, "make_clamped", clamp_op());
}
NurbsVolume make_clamped(const NurbsVolume& v) {
  return make_clamped(make_clamped(make_clamped(v, 0), 1), 2);
}
std::pair<NurbsVolume, NurbsVolume> split(const NurbsVolume& v, int dir, double u) {
  return split_along(v, dir, u);
}
NurbsVolume extract(const NurbsVolume& v, int dir, double a, double b) {
  return along(v, dir, "extract", extract_op(a, b));
}

}  // namespace isomuscle::geometry
