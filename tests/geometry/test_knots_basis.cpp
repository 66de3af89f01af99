// Knot vectors and the Cox–de Boor basis (thesis 5.2–5.3): validation, spans, partition of unity,
// non-negativity, agreement with the textbook recursion, derivatives against central differences.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/bspline_basis.hpp"
#include "geometry/knot_vector.hpp"

namespace isomuscle::geometry {
namespace {

// Textbook recursion N_{i,p} (thesis 5.2–5.3) with 0/0 := 0, as an independent reference.
double cox_de_boor(const std::vector<double>& U, int i, int p, double u, bool last_span) {
  if (p == 0) {
    if (U[i] <= u && u < U[i + 1]) {
      return 1.0;
    }
    // The closed right end of a clamped domain belongs to the last non-empty span.
    return (last_span && u == U[i + 1] && U[i] < U[i + 1] && U[i + 1] == U.back()) ? 1.0 : 0.0;
  }
  double value = 0.0;
  if (U[i + p] > U[i]) {
    value += (u - U[i]) / (U[i + p] - U[i]) * cox_de_boor(U, i, p - 1, u, last_span);
  }
  if (U[i + p + 1] > U[i + 1]) {
    value +=
        (U[i + p + 1] - u) / (U[i + p + 1] - U[i + 1]) * cox_de_boor(U, i + 1, p - 1, u, last_span);
  }
  return value;
}

// All n + 1 functions (derivative order k) at u, zero outside the span's p + 1.
std::vector<double> all_functions(const KnotVector& kv, double u, int order) {
  const int p = kv.degree();
  std::vector<double> local(static_cast<std::size_t>((order + 1) * (p + 1)));
  const int span = kv.find_span(u);
  basis_derivatives(kv, span, u, order, local.data());
  std::vector<double> out(static_cast<std::size_t>(kv.num_basis()), 0.0);
  for (int j = 0; j <= p; ++j) {
    out[static_cast<std::size_t>(span - p + j)] =
        local[static_cast<std::size_t>(order * (p + 1) + j)];
  }
  return out;
}

std::vector<KnotVector> test_vectors() {
  std::vector<KnotVector> out;
  for (int p = 0; p <= 5; ++p) {
    out.push_back(KnotVector::uniform_clamped(p, 4, -1.0, 2.0));
    // Non-uniform with repeated interior knots (multiplicity up to p, and p + 1 for p = 1).
    std::vector<double> interior = {0.1, 0.35, 0.7};
    if (p >= 1) {
      interior.push_back(0.35);
    }
    for (int m = 1; m < p; ++m) {
      interior.push_back(0.5);
    }
    out.push_back(KnotVector::clamped(p, interior, 0.0, 1.0));
  }
  out.push_back(KnotVector::clamped(1, {0.4, 0.4}, 0.0, 1.0));  // C^-1 knot for p = 1
  // Unclamped (periodic-style) vectors.
  out.push_back(KnotVector({-3, -2, -1, 0, 1, 2, 3, 4, 5, 6}, 3));
  out.push_back(KnotVector({-0.5, -0.2, 0.0, 0.3, 0.3, 0.9, 1.0, 1.4, 1.5}, 2));
  return out;
}

TEST(KnotVector, RejectsBadInputWithClearMessages) {
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message([] { KnotVector({0, 0, 1, 1}, -1); }).find("degree -1"), std::string::npos);
  EXPECT_NE(message([] {
              KnotVector({0, 0, 0, 0.5, 0.4, 1, 1, 1}, 2);
            }).find("decrease at index 4"),
            std::string::npos);
  EXPECT_NE(message([] {
              KnotVector({0, 0, std::numeric_limits<double>::quiet_NaN(), 1, 1}, 1);
            }).find("not finite"),
            std::string::npos);
  EXPECT_NE(message([] { KnotVector({0, 0, 1, 1}, 2); }).find("too few"), std::string::npos);
  EXPECT_NE(message([] {
              KnotVector({0, 0, 0.5, 0.5, 0.5, 1, 1}, 1);
            }).find("repeated 3 times"),
            std::string::npos);
  EXPECT_NE(message([] {
              KnotVector({0, 1, 1, 1, 1, 2}, 2);
            }).find("repeated 4 times"),
            std::string::npos);
  EXPECT_NE(message([] {
              KnotVector({0, 0, 0, 0, 1, 1}, 2);
            }).find("repeated 4 times"),
            std::string::npos);
  EXPECT_NE(message([] {
              KnotVector({0, 1, 1, 1, 2, 3}, 2);
            }).find("empty parametric domain"),
            std::string::npos);
  EXPECT_NE(message([] { KnotVector::clamped(2, {1.5}); }).find("not strictly inside"),
            std::string::npos);
  EXPECT_NE(message([] { KnotVector::uniform_clamped(2, 0); }).find("n_spans"), std::string::npos);
  EXPECT_NE(message([] {
              KnotVector({0, 0, 1, 1}, kMaxDegree + 1);
            }).find("supported range"),
            std::string::npos);
  EXPECT_THROW(KnotVector::uniform_clamped(2, 3).find_span(std::nan("")), std::invalid_argument);
}

TEST(KnotVector, SpansBreakpointsMultiplicity) {
  const KnotVector kv = KnotVector::clamped(2, {0.25, 0.5, 0.5, 0.75});
  EXPECT_EQ(kv.num_basis(), 7);
  EXPECT_EQ(kv.domain_begin(), 0.0);
  EXPECT_EQ(kv.domain_end(), 1.0);
  EXPECT_TRUE(kv.is_clamped());
  EXPECT_EQ(kv.find_span(-1.0), 2);
  EXPECT_EQ(kv.find_span(0.0), 2);
  EXPECT_EQ(kv.find_span(0.1), 2);
  EXPECT_EQ(kv.find_span(0.25), 3);
  EXPECT_EQ(kv.find_span(0.4999), 3);
  EXPECT_EQ(kv.find_span(0.5), 5);
  EXPECT_EQ(kv.find_span(0.8), 6);
  EXPECT_EQ(kv.find_span(1.0), 6);
  EXPECT_EQ(kv.find_span(7.0), 6);
  EXPECT_EQ(kv.breakpoints(), (std::vector<double>{0.0, 0.25, 0.5, 0.75, 1.0}));
  EXPECT_EQ(kv.multiplicity(0.5), 2);
  EXPECT_EQ(kv.multiplicity(0.0), 3);
  EXPECT_EQ(kv.multiplicity(0.3), 0);

  const KnotVector open({-2, -1, 0, 1, 2, 3, 4, 5}, 2);
  EXPECT_FALSE(open.is_clamped());
  EXPECT_EQ(open.domain_begin(), 0.0);
  EXPECT_EQ(open.domain_end(), 3.0);
  EXPECT_EQ(open.find_span(3.0), 4);
  EXPECT_EQ(open.find_span(-5.0), 2);
  EXPECT_EQ(open.breakpoints(), (std::vector<double>{0, 1, 2, 3}));
  EXPECT_EQ(KnotVector::uniform_clamped(3, 3, 1.0, 4.0).knots(),
            (std::vector<double>{1, 1, 1, 1, 2, 3, 4, 4, 4, 4}));
}

// Partition of unity sum_i N_i = 1 on the domain (thesis 5.3 property), N_i >= 0, and agreement
// with the textbook recursion, at random points and at all breakpoints.
TEST(BsplineBasis, PartitionOfUnityNonNegativityAndRecursion) {
  std::mt19937 rng(11);
  for (const KnotVector& kv : test_vectors()) {
    std::uniform_real_distribution<double> dist(kv.domain_begin(), kv.domain_end());
    std::vector<double> samples = kv.breakpoints();
    for (int s = 0; s < 200; ++s) {
      samples.push_back(dist(rng));
    }
    for (double u : samples) {
      const std::vector<double> N = all_functions(kv, u, 0);
      double sum = 0.0;
      const bool last = u >= kv.domain_end();
      for (int i = 0; i < kv.num_basis(); ++i) {
        EXPECT_GE(N[static_cast<std::size_t>(i)], 0.0);
        sum += N[static_cast<std::size_t>(i)];
        EXPECT_NEAR(N[static_cast<std::size_t>(i)],
                    cox_de_boor(kv.knots(), i, kv.degree(), u, last), 1e-14)
            << "p = " << kv.degree() << ", u = " << u << ", i = " << i;
      }
      EXPECT_NEAR(sum, 1.0, 1e-14) << "p = " << kv.degree() << ", u = " << u;
      // basis_functions (A2.2) and the zeroth row of basis_derivatives (A2.3) agree.
      double direct[kMaxDegree + 1];
      const int span = kv.find_span(u);
      basis_functions(kv, span, u, direct);
      for (int j = 0; j <= kv.degree(); ++j) {
        EXPECT_NEAR(direct[j], N[static_cast<std::size_t>(span - kv.degree() + j)], 1e-15);
      }
    }
  }
}

// First and second derivatives against central differences of the functions and of the first
// derivatives: |FD - exact| <= 1e-7 max_i |exact_i|. Points within 1e-4 of a knot are skipped
// (there the stencil straddles a break in continuity).
TEST(BsplineBasis, DerivativesMatchCentralDifferences) {
  std::mt19937 rng(7);
  for (const KnotVector& kv : test_vectors()) {
    const int p = kv.degree();
    const double len = kv.domain_end() - kv.domain_begin();
    const double h = 1e-6 * len;
    std::uniform_real_distribution<double> dist(kv.domain_begin(), kv.domain_end());
    int checked = 0;
    for (int s = 0; s < 400 && checked < 100; ++s) {
      const double u = dist(rng);
      bool near_knot = false;
      for (double k : kv.knots()) {
        near_knot = near_knot || std::abs(u - k) < 1e-4 * len;
      }
      if (near_knot) {
        continue;
      }
      ++checked;
      for (int order = 1; order <= 2; ++order) {
        const std::vector<double> exact = all_functions(kv, u, order);
        const std::vector<double> plus = all_functions(kv, u + h, order - 1);
        const std::vector<double> minus = all_functions(kv, u - h, order - 1);
        double scale = 0.0;
        for (double e : exact) {
          scale = std::max(scale, std::abs(e));
        }
        if (order > p) {
          for (double e : exact) {
            EXPECT_EQ(e, 0.0);
          }
        }
        scale = std::max(scale, 1.0 / std::pow(len, order));
        for (std::size_t i = 0; i < exact.size(); ++i) {
          const double fd = (plus[i] - minus[i]) / (2.0 * h);
          EXPECT_LE(std::abs(fd - exact[i]), 1e-7 * scale)
              << "p = " << p << ", order " << order << ", u = " << u << ", i = " << i;
        }
      }
    }
    EXPECT_GE(checked, 50);
  }
}

// The cheap first-derivative routine agrees with the general one (A2.3) for every degree.
TEST(BsplineBasis, FirstDerivativesAgreeWithGeneralRoutine) {
  std::mt19937 rng(8);
  for (const KnotVector& kv : test_vectors()) {
    const int p = kv.degree();
    std::uniform_real_distribution<double> dist(kv.domain_begin(), kv.domain_end());
    std::vector<double> samples = kv.breakpoints();
    for (int s = 0; s < 100; ++s) {
      samples.push_back(dist(rng));
    }
    for (double u : samples) {
      const int span = kv.find_span(u);
      double general[2 * (kMaxDegree + 1)];
      double fast[2 * (kMaxDegree + 1)];
      basis_derivatives(kv, span, u, 1, general);
      basis_first_derivatives(kv, span, u, fast);
      double scale = 1.0;
      for (int j = 0; j < 2 * (p + 1); ++j) {
        scale = std::max(scale, std::abs(general[j]));
      }
      for (int j = 0; j < 2 * (p + 1); ++j) {
        EXPECT_NEAR(fast[j], general[j], 1e-14 * scale) << "p = " << p << ", u = " << u;
      }
    }
  }
}

// Orders above p are zero and the buffer layout is out[k (p+1) + j].
TEST(BsplineBasis, HigherOrderDerivativesVanishAboveDegree) {
  const KnotVector kv = KnotVector::clamped(2, {0.3, 0.6});
  double out[5 * 3];
  std::fill(out, out + 15, 99.0);
  basis_derivatives(kv, kv.find_span(0.45), 0.45, 4, out);
  for (int k = 3; k <= 4; ++k) {
    for (int j = 0; j < 3; ++j) {
      EXPECT_EQ(out[k * 3 + j], 0.0);
    }
  }
  // Second derivatives of a quadratic are constant in a span and sum to zero.
  EXPECT_NEAR(out[6] + out[7] + out[8], 0.0, 1e-12);
  EXPECT_NE(out[6], 0.0);
}

}  // namespace
}  // namespace isomuscle::geometry
