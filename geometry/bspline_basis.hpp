#pragma once
// B-spline basis functions and their derivatives by the Cox–de Boor recursion (thesis 5.2–5.3;
// Piegl & Tiller, The NURBS Book, A2.2 and A2.3).
#include "geometry/knot_vector.hpp"

namespace isomuscle::geometry {

// Largest degree supported by the fixed-size scratch buffers used in hot loops.
inline constexpr int kMaxDegree = 10;

// Values of the p + 1 basis functions N_{span-p..span,p}(u): out[0..p].
void basis_functions(const KnotVector& kv, int span, double u, double* out);

// Derivatives up to order n (n <= p allowed; higher ones are zero) of the p + 1 non-zero functions:
// out[k * (p + 1) + j] = d^k N_{span-p+j,p} / du^k (u), k = 0..n. No heap allocation.
void basis_derivatives(const KnotVector& kv, int span, double u, int n, double* out);

// Values and first derivatives only, same layout as basis_derivatives with n = 1 (out[0..p] values,
// out[p+1..2p+1] derivatives), cheaper than the general recursion: the hot path of volumes.
void basis_first_derivatives(const KnotVector& kv, int span, double u, double* out);

}  // namespace isomuscle::geometry
