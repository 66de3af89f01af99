// B-spline basis functions by the Cox–de Boor recursion (thesis 5.2–5.3; The NURBS Book A2.2,
// A2.3). Everything lives in fixed-size stack arrays of size kMaxDegree + 1: no heap allocation.
#include "geometry/bspline_basis.hpp"

#include <cassert>

namespace isomuscle::geometry {

// N_{i,0}(u) = 1 on [u_i, u_{i+1}), N_{i,p} = (u - u_i)/(u_{i+p} - u_i) N_{i,p-1}
//   + (u_{i+p+1} - u)/(u_{i+p+1} - u_{i+1}) N_{i+1,p-1} (thesis 5.2–5.3), computed for the p + 1
// non-zero functions in the triangular scheme of A2.2. Dimensionless.
void basis_functions(const KnotVector& kv, int span, double u, double* out) {
  const int p = kv.degree();
  assert(span >= p && span < kv.num_basis());
  const double* U = kv.knots().data();
  double left[kMaxDegree + 1];
  double right[kMaxDegree + 1];
  out[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - U[span + 1 - j];
    right[j] = U[span + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = out[r] / (right[r + 1] + left[j - r]);
      out[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    out[j] = saved;
  }
}

// Derivatives d^k N_{i,p}/du^k, k = 0..n (The NURBS Book eq. 2.9 evaluated by A2.3): the table
// ndu holds the functions (upper triangle) and knot differences (lower triangle); the derivative
// coefficients a_{k,j} are built in two alternating rows. Units: 1/[u]^k.
void basis_derivatives(const KnotVector& kv, int span, double u, int n, double* out) {
  const int p = kv.degree();
  assert(span >= p && span < kv.num_basis());
  assert(n >= 0);
  const double* U = kv.knots().data();
  double ndu[kMaxDegree + 1][kMaxDegree + 1];
  double left[kMaxDegree + 1];
  double right[kMaxDegree + 1];
  double a[2][kMaxDegree + 1];

  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - U[span + 1 - j];
    right[j] = U[span + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];  // lower triangle: knot differences
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;  // upper triangle: functions
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  const int stride = p + 1;
  for (int j = 0; j <= p; ++j) {
    out[j] = ndu[j][p];
  }
  const int nd = n < p ? n : p;
  for (int r = 0; r <= p; ++r) {
    int s1 = 0;
    int s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= nd; ++k) {
      double d = 0.0;
      const int rk = r - k;
      const int pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      out[k * stride + r] = d;
      const int t = s1;
      s1 = s2;
      s2 = t;
    }
  }
  // Multiply by p!/(p-k)!.
  double factor = static_cast<double>(p);
  for (int k = 1; k <= nd; ++k) {
    for (int j = 0; j <= p; ++j) {
      out[k * stride + j] *= factor;
    }
    factor *= static_cast<double>(p - k);
  }
  for (int k = nd + 1; k <= n; ++k) {
    for (int j = 0; j <= p; ++j) {
      out[k * stride + j] = 0.0;
    }
  }
}

// N'_{k,p} = p N_{k,p-1} / (u_{k+p} - u_k) - p N_{k+1,p-1} / (u_{k+p+1} - u_{k+1}) (NURBS Book
// eq. 2.7): the triangle of A2.2 up to degree p - 1, then one last step that yields the values and
// the derivatives together. Units: 1 and 1/[u].
void basis_first_derivatives(const KnotVector& kv, int span, double u, double* out) {
  const int p = kv.degree();
  assert(span >= p && span < kv.num_basis());
  double* d = out + p + 1;
  if (p == 0) {
    out[0] = 1.0;
    d[0] = 0.0;
    return;
  }
  const double* U = kv.knots().data();
  double left[kMaxDegree + 1];
  double right[kMaxDegree + 1];
  double N[kMaxDegree + 1];
  N[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - U[span + 1 - j];
    right[j] = U[span + j] - u;
  }
  for (int j = 1; j < p; ++j) {
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = N[r] / (right[r + 1] + left[j - r]);
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
  double saved = 0.0;
  double dsaved = 0.0;
  const double pd = static_cast<double>(p);
  for (int r = 0; r < p; ++r) {
    const double temp = N[r] / (right[r + 1] + left[p - r]);
    out[r] = saved + right[r + 1] * temp;
    saved = left[p - r] * temp;
    d[r] = dsaved - pd * temp;
    dsaved = pd * temp;
  }
  out[p] = saved;
  d[p] = dsaved;
}

}  // namespace isomuscle::geometry
