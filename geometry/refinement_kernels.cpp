// Univariate kernels of exact refinement on homogeneous control polygons (thesis 5.3; The NURBS
// Book A5.4, A5.9). See refinement_kernels.hpp.
#include "geometry/refinement_kernels.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "geometry/bspline_basis.hpp"

namespace isomuscle::geometry::detail {

int Line::multiplicity(double u) const {
  return static_cast<int>(std::count(U.begin(), U.end(), u));
}

void fail(const std::string& where, const std::string& what) {
  throw std::invalid_argument(where + ": " + what);
}

namespace {

std::string num(double x) {
  std::ostringstream os;
  os.precision(17);
  os << x;
  return os.str();
}

// Built with a stream: GCC 12 warns falsely (-Wrestrict) on "[" + std::string&&.
std::string domain_text(const Line& l) {
  std::ostringstream os;
  os.precision(17);
  os << "[" << l.begin() << ", " << l.end() << "]";
  return os.str();
}

// Largest k in [p, n] with U_k <= u for u in [u_p, u_{n+1}) (NURBS Book A2.1 without the end rule).
int raw_span(const Line& l, double u) {
  const auto first = l.U.begin() + l.p;
  const auto last = l.U.begin() + l.count();
  return static_cast<int>(std::upper_bound(first, last, u) - l.U.begin()) - 1;
}

// Reparametrisation u -> -u: U'_i = -U_{m-i}, poles in reverse order. The same geometry.
Line reversed(const Line& in) {
  Line out;
  out.p = in.p;
  out.U.resize(in.U.size());
  std::transform(in.U.rbegin(), in.U.rend(), out.U.begin(), [](double u) { return -u; });
  out.P = in.P.colwise().reverse();
  return out;
}

// Knot refinement (NURBS Book A5.4): inserts the sorted values X, all in [u_p, u_{n+1}), at once.
// Q_i = alpha Q_{i-1} + (1 - alpha) Q_i on homogeneous points, so rational geometry is exact.
Line refine_core(const Line& in, const std::vector<double>& X) {
  if (X.empty()) {
    return in;
  }
  const int p = in.p;
  const int n = in.count() - 1;
  const int m = n + p + 1;
  const int r = static_cast<int>(X.size()) - 1;
  const int a = raw_span(in, X.front());
  const int b = raw_span(in, X.back()) + 1;
  const std::vector<double>& U = in.U;
  Line out;
  out.p = p;
  out.U.assign(static_cast<std::size_t>(m + r + 2), 0.0);
  out.P.resize(n + r + 2, in.P.cols());
  std::vector<double>& Ub = out.U;
  RowMatrix& Q = out.P;
  for (int j = 0; j <= a - p; ++j) {
    Q.row(j) = in.P.row(j);
  }
  for (int j = b - 1; j <= n; ++j) {
    Q.row(j + r + 1) = in.P.row(j);
  }
  for (int j = 0; j <= a; ++j) {
    Ub[static_cast<std::size_t>(j)] = U[static_cast<std::size_t>(j)];
  }
  for (int j = b + p; j <= m; ++j) {
    Ub[static_cast<std::size_t>(j + r + 1)] = U[static_cast<std::size_t>(j)];
  }
  int i = b + p - 1;
  int k = b + p + r;
  for (int j = r; j >= 0; --j) {
    const double x = X[static_cast<std::size_t>(j)];
    while (x <= U[static_cast<std::size_t>(i)] && i > a) {
      Q.row(k - p - 1) = in.P.row(i - p - 1);
      Ub[static_cast<std::size_t>(k)] = U[static_cast<std::size_t>(i)];
      --k;
      --i;
    }
    Q.row(k - p - 1) = Q.row(k - p);
    for (int l = 1; l <= p; ++l) {
      const int ind = k - p + l;
      double alpha = Ub[static_cast<std::size_t>(k + l)] - x;
      if (alpha == 0.0) {
        Q.row(ind - 1) = Q.row(ind);
      } else {
        alpha /= Ub[static_cast<std::size_t>(k + l)] - U[static_cast<std::size_t>(i - p + l)];
        Q.row(ind - 1) = alpha * Q.row(ind - 1) + (1.0 - alpha) * Q.row(ind);
      }
    }
    Ub[static_cast<std::size_t>(k)] = x;
    --k;
  }
  return out;
}

}  // namespace

// Validated knot refinement: values in [u_p, u_{n+1}], final multiplicities <= p + 1. Values at
// u_{n+1} (only possible for unclamped vectors) are inserted on the reversed line.
Line refine_line(const Line& in, std::vector<double> X, const std::string& where) {
  std::sort(X.begin(), X.end());
  for (std::size_t j = 0; j < X.size(); ++j) {
    const double x = X[j];
    if (!(x >= in.begin() && x <= in.end())) {
      fail(where, "knot " + num(x) + " is outside the parametric domain " + domain_text(in));
    }
    if (j == 0 || x != X[j - 1]) {
      const int added = static_cast<int>(std::count(X.begin(), X.end(), x));
      if (in.multiplicity(x) + added > in.p + 1) {
        fail(where, "inserting knot " + num(x) + " " + std::to_string(added) +
                        " time(s) gives multiplicity " +
                        std::to_string(in.multiplicity(x) + added) +
                        " > degree + 1 = " + std::to_string(in.p + 1));
      }
    }
  }
  const auto at_end = std::lower_bound(X.begin(), X.end(), in.end());
  const std::vector<double> inner(X.begin(), at_end);
  Line out = refine_core(in, inner);
  const std::vector<double> end_knots(static_cast<std::size_t>(X.end() - at_end), -in.end());
  if (!end_knots.empty()) {
    out = reversed(refine_core(reversed(out), end_knots));
  }
  return out;
}

namespace {

// Inserts u_p to multiplicity p + 1 and drops the poles and knots before it (clamping the start).
Line clamp_start(const Line& in) {
  const double a = in.begin();
  if (in.U.front() == a) {
    return in;
  }
  const int s = in.multiplicity(a);
  const Line full = refine_core(in, std::vector<double>(static_cast<std::size_t>(in.p + 1 - s), a));
  const int k =
      static_cast<int>(std::lower_bound(full.U.begin(), full.U.end(), a) - full.U.begin());
  Line out;
  out.p = full.p;
  out.U.assign(full.U.begin() + k, full.U.end());
  out.P = full.P.bottomRows(full.count() - k);
  return out;
}

}  // namespace

// Clamped representation of the same geometry on [u_p, u_{n+1}] (both ends).
Line clamp_line(const Line& in) {
  return reversed(clamp_start(reversed(clamp_start(in))));
}

// Inserts u to multiplicity p + 1 and separates the two pieces [.., u] and [u, ..].
std::pair<Line, Line> split_line(const Line& in, double u, const std::string& where) {
  if (!(u > in.begin() && u < in.end())) {
    fail(where,
         "split parameter " + num(u) + " must lie strictly inside the domain " + domain_text(in));
  }
  const int s = in.multiplicity(u);
  const Line full = refine_core(in, std::vector<double>(static_cast<std::size_t>(in.p + 1 - s), u));
  const int k =
      static_cast<int>(std::lower_bound(full.U.begin(), full.U.end(), u) - full.U.begin());
  Line left;
  Line right;
  left.p = right.p = full.p;
  left.U.assign(full.U.begin(), full.U.begin() + k + full.p + 1);
  left.P = full.P.topRows(k);
  right.U.assign(full.U.begin() + k, full.U.end());
  right.P = full.P.bottomRows(full.count() - k);
  return {std::move(left), std::move(right)};
}

Line extract_line(const Line& in, double a, double b, const std::string& where) {
  if (!(a >= in.begin() && a < b && b <= in.end())) {
    fail(where, "sub-domain [" + num(a) + ", " + num(b) + "] must satisfy begin <= a < b <= end " +
                    "within the domain " + domain_text(in));
  }
  Line out = clamp_line(in);
  if (a > out.begin()) {
    out = split_line(out, a, where).second;
  }
  if (b < out.end()) {
    out = split_line(out, b, where).first;
  }
  return out;
}

namespace {

double binomial(int n, int k) {
  double b = 1.0;
  for (int i = 1; i <= k; ++i) {
    b = b * static_cast<double>(n - k + i) / static_cast<double>(i);
  }
  return b;
}

}  // namespace

// Degree elevation by t (NURBS Book A5.9): each Bézier segment is extracted by knot insertion,
// elevated with the coefficients C(p,j) C(t,i-j) / C(p+t,i) (eq. 5.36), and the superfluous knots
// between segments are removed again, so every multiplicity grows by exactly t.
Line elevate_line(const Line& in, int t, const std::string& where) {
  if (t < 0) {
    fail(where, "degree increase t = " + std::to_string(t) + " must be >= 0");
  }
  if (t == 0) {
    return in;
  }
  const int p = in.p;
  const int ph = p + t;
  if (ph > kMaxDegree) {
    fail(where, "elevated degree " + std::to_string(ph) + " exceeds the supported maximum " +
                    std::to_string(kMaxDegree));
  }
  const std::vector<double>& U = in.U;
  const int n = in.count() - 1;
  const int m = n + p + 1;
  if (U.front() != U[static_cast<std::size_t>(p)] ||
      U.back() != U[static_cast<std::size_t>(m - p)]) {
    fail(where, "degree elevation needs a clamped knot vector; call make_clamped first");
  }
  int segments = 0;
  for (int i = p; i < m - p; ++i) {
    if (U[static_cast<std::size_t>(i)] != U[static_cast<std::size_t>(i + 1)]) {
      ++segments;
    }
    if (i > p && in.multiplicity(U[static_cast<std::size_t>(i)]) > p) {
      fail(where, "interior knot " + num(U[static_cast<std::size_t>(i)]) +
                      " has multiplicity degree + 1 (a discontinuity); split there first");
    }
  }
  const int cols = static_cast<int>(in.P.cols());
  double bezalfs[kMaxDegree + 1][kMaxDegree + 1] = {};
  bezalfs[0][0] = bezalfs[ph][p] = 1.0;
  const int ph2 = ph / 2;
  for (int i = 1; i <= ph2; ++i) {
    const double inv = 1.0 / binomial(ph, i);
    for (int j = std::max(0, i - t); j <= std::min(p, i); ++j) {
      bezalfs[i][j] = inv * binomial(p, j) * binomial(t, i - j);
    }
  }
  for (int i = ph2 + 1; i <= ph - 1; ++i) {
    for (int j = std::max(0, i - t); j <= std::min(p, i); ++j) {
      bezalfs[i][j] = bezalfs[ph - i][p - j];
    }
  }
  Line out;
  out.p = ph;
  out.U.assign(U.size() + static_cast<std::size_t>(t * (segments + 1)), 0.0);
  out.P.setZero(n + 1 + t * segments, cols);
  std::vector<double>& Uh = out.U;
  RowMatrix& Qw = out.P;
  RowMatrix bpts(p + 1, cols);
  RowMatrix ebpts(ph + 1, cols);
  RowMatrix next_bpts(std::max(p - 1, 1), cols);
  double alfs[kMaxDegree + 1];

  int mh = ph;
  int kind = ph + 1;
  int r = -1;
  int a = p;
  int b = p + 1;
  int cind = 1;
  double ua = U[0];
  Qw.row(0) = in.P.row(0);
  for (int i = 0; i <= ph; ++i) {
    Uh[static_cast<std::size_t>(i)] = ua;
  }
  bpts = in.P.topRows(p + 1);
  auto knot = [&U](int i) { return U[static_cast<std::size_t>(i)]; };
  while (b < m) {
    const int i0 = b;
    while (b < m && knot(b) == knot(b + 1)) {
      ++b;
    }
    const int mul = b - i0 + 1;
    mh += mul + t;
    const double ub = knot(b);
    const int oldr = r;
    r = p - mul;
    const int lbz = oldr > 0 ? (oldr + 2) / 2 : 1;
    const int rbz = r > 0 ? ph - (r + 1) / 2 : ph;
    if (r > 0) {  // insert ub r times to obtain the Bézier segment [ua, ub]
      const double numer = ub - ua;
      for (int k = p; k > mul; --k) {
        alfs[k - mul - 1] = numer / (knot(a + k) - ua);
      }
      for (int j = 1; j <= r; ++j) {
        const int save = r - j;
        const int s = mul + j;
        for (int k = p; k >= s; --k) {
          bpts.row(k) = alfs[k - s] * bpts.row(k) + (1.0 - alfs[k - s]) * bpts.row(k - 1);
        }
        next_bpts.row(save) = bpts.row(p);
      }
    }
    for (int i = lbz; i <= ph; ++i) {  // degree-elevate the Bézier segment
      ebpts.row(i).setZero();
      for (int j = std::max(0, i - t); j <= std::min(p, i); ++j) {
        ebpts.row(i) += bezalfs[i][j] * bpts.row(j);
      }
    }
    if (oldr > 1) {  // remove knot ua oldr - 1 times
      int first = kind - 2;
      int last = kind;
      const double den = ub - ua;
      const double bet = (ub - Uh[static_cast<std::size_t>(kind - 1)]) / den;
      for (int tr = 1; tr < oldr; ++tr) {
        int i = first;
        int j = last;
        int kj = j - kind + 1;
        while (j - i > tr) {
          if (i < cind) {
            const double alf =
                (ub - Uh[static_cast<std::size_t>(i)]) / (ua - Uh[static_cast<std::size_t>(i)]);
            Qw.row(i) = alf * Qw.row(i) + (1.0 - alf) * Qw.row(i - 1);
          }
          if (j >= lbz) {
            if (j - tr <= kind - ph + oldr) {
              const double gam = (ub - Uh[static_cast<std::size_t>(j - tr)]) / den;
              ebpts.row(kj) = gam * ebpts.row(kj) + (1.0 - gam) * ebpts.row(kj + 1);
            } else {
              ebpts.row(kj) = bet * ebpts.row(kj) + (1.0 - bet) * ebpts.row(kj + 1);
            }
          }
          ++i;
          --j;
          --kj;
        }
        --first;
        ++last;
      }
    }
    if (a != p) {  // load the knot ua
      for (int i = 0; i < ph - oldr; ++i) {
        Uh[static_cast<std::size_t>(kind)] = ua;
        ++kind;
      }
    }
    for (int j = lbz; j <= rbz; ++j) {  // load the control points
      Qw.row(cind) = ebpts.row(j);
      ++cind;
    }
    if (b < m) {  // set up the next segment
      for (int j = 0; j < r; ++j) {
        bpts.row(j) = next_bpts.row(j);
      }
      for (int j = r; j <= p; ++j) {
        bpts.row(j) = in.P.row(b - p + j);
      }
      a = b;
      ++b;
      ua = ub;
    } else {
      for (int i = 0; i <= ph; ++i) {
        Uh[static_cast<std::size_t>(kind + i)] = ub;
      }
    }
  }
  if (mh + 1 != static_cast<int>(Uh.size()) || cind != out.count()) {
    throw std::logic_error(where + ": internal error in degree elevation (knot count " +
                           std::to_string(mh + 1) + " vs " + std::to_string(Uh.size()) + ")");
  }
  return out;
}

}  // namespace isomuscle::geometry::detail
