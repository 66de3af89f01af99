// Evaluation of NURBS curves, surfaces and volumes (thesis 5.6, 5.11, 5.13): exact conics,
// partition of unity and non-negativity of the rational bases, first (and second, for curves)
// derivatives against central differences, the volume basis used by IGA assembly.
#include <gtest/gtest.h>

#include <Eigen/LU>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/nurbs_curve.hpp"
#include "geometry/nurbs_surface.hpp"
#include "geometry/nurbs_volume.hpp"

namespace isomuscle::geometry {
namespace {

const double kS = std::sqrt(0.5);

// Full circle of radius r in the xy-plane: 9 poles, weights 1, sqrt(2)/2 alternating, double
// interior knots (The NURBS Book Ex. 7.2).
NurbsCurve full_circle(double r) {
  std::vector<Eigen::Vector3d> pts = {{r, 0, 0},   {r, r, 0},  {0, r, 0},  {-r, r, 0}, {-r, 0, 0},
                                      {-r, -r, 0}, {0, -r, 0}, {r, -r, 0}, {r, 0, 0}};
  std::vector<double> w = {1, kS, 1, kS, 1, kS, 1, kS, 1};
  return NurbsCurve(KnotVector::clamped(2, {0.25, 0.25, 0.5, 0.5, 0.75, 0.75}), pts, w);
}

// Thick cylindrical shell sector r in [r0, r1], angle [0, pi/2], z in [0, h]: linear in u
// (radius), quadratic rational in v (angle), linear in w (height), right-handed; a few poles and
// weights perturbed when distort.
NurbsVolume shell_sector(double r0, double r1, double h, bool distort) {
  std::vector<Eigen::Vector3d> pts;
  std::vector<double> w;
  const double wv[3] = {1.0, kS, 1.0};
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 2; ++i) {
        const double r = i == 0 ? r0 : r1;
        const Eigen::Vector3d arc[3] = {{r, 0, 0}, {r, r, 0}, {0, r, 0}};
        pts.push_back(arc[j] + Eigen::Vector3d(0, 0, k * h));
        w.push_back(wv[j]);
      }
    }
  }
  NurbsVolume vol(
      {KnotVector::clamped(1, {}), KnotVector::clamped(2, {}), KnotVector::clamped(1, {})}, pts, w);
  if (!distort) {
    return vol;
  }
  std::vector<Eigen::Vector3d> p2 = vol.points();
  std::vector<double> w2 = vol.weights();
  p2[static_cast<std::size_t>(vol.index(1, 1, 1))] += Eigen::Vector3d(0.2, -0.1, 0.3);
  p2[static_cast<std::size_t>(vol.index(0, 0, 1))] += Eigen::Vector3d(0.1, 0.05, -0.1);
  w2[static_cast<std::size_t>(vol.index(0, 1, 0))] = 0.5;
  w2[static_cast<std::size_t>(vol.index(1, 2, 1))] = 1.7;
  return NurbsVolume(vol.all_knots(), p2, w2);
}

// A general volume with degrees (p, q, r), repeated interior knots, random weights in [0.5, 2] and
// a smooth distortion of a box, to exercise every index path of the basis.
NurbsVolume general_volume(int p, int q, int r, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> wdist(0.5, 2.0);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  const std::array<KnotVector, 3> kv = {KnotVector::clamped(p, {0.3, 0.3, 0.6}),
                                        KnotVector::clamped(q, {0.5}, -1.0, 1.0),
                                        KnotVector::clamped(r, {0.2, 0.7, 0.7}, 0.0, 2.0)};
  std::vector<Eigen::Vector3d> pts;
  std::vector<double> w;
  for (int k = 0; k < kv[2].num_basis(); ++k) {
    for (int j = 0; j < kv[1].num_basis(); ++j) {
      for (int i = 0; i < kv[0].num_basis(); ++i) {
        const double x = static_cast<double>(i) / (kv[0].num_basis() - 1);
        const double y = static_cast<double>(j) / (kv[1].num_basis() - 1);
        const double z = static_cast<double>(k) / (kv[2].num_basis() - 1);
        pts.emplace_back(x + 0.2 * y * z + jitter(rng), y + 0.1 * x * x + jitter(rng),
                         2.0 * z + 0.3 * x * y + jitter(rng));
        w.push_back(wdist(rng));
      }
    }
  }
  return NurbsVolume(kv, pts, w);
}

double random_in(std::mt19937& rng, const std::array<double, 2>& dom) {
  return std::uniform_real_distribution<double>(dom[0], dom[1])(rng);
}

TEST(NurbsCurve, ExactCircleAndRationalBasis) {
  const NurbsCurve c = full_circle(2.0);
  std::mt19937 rng(1);
  for (int s = 0; s < 200; ++s) {
    const double u = random_in(rng, c.domain());
    EXPECT_NEAR(c.evaluate(u).norm(), 2.0, 1e-14);
    EXPECT_EQ(c.evaluate(u).z(), 0.0);
  }
  EXPECT_NEAR((c.evaluate(0.25) - Eigen::Vector3d(0, 2, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((c.evaluate(1.0) - Eigen::Vector3d(2, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_TRUE(c.is_rational());
  // R_k(u) is the curve whose only non-zero pole is e_x at k: partition of unity, non-negative.
  for (int s = 0; s < 100; ++s) {
    const double u = random_in(rng, c.domain());
    double sum = 0.0;
    for (int k = 0; k < c.count(); ++k) {
      std::vector<Eigen::Vector3d> pts(static_cast<std::size_t>(c.count()),
                                       Eigen::Vector3d::Zero());
      pts[static_cast<std::size_t>(k)] = Eigen::Vector3d::UnitX();
      const double Rk = NurbsCurve(c.knots(), pts, c.weights()).evaluate(u).x();
      EXPECT_GE(Rk, 0.0);
      sum += Rk;
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
  }
}

// dC/du and d2C/du2 (NURBS Book eq. 4.8) against central differences, relative 1e-7.
TEST(NurbsCurve, DerivativesMatchCentralDifferences) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> wdist(0.3, 3.0);
  std::vector<NurbsCurve> curves = {full_circle(1.5)};
  for (int p = 1; p <= 4; ++p) {
    const KnotVector kv = KnotVector::clamped(p, {0.2, 0.5, 0.5, 0.8}, -1.0, 3.0);
    std::vector<Eigen::Vector3d> pts;
    std::vector<double> w;
    for (int i = 0; i < kv.num_basis(); ++i) {
      pts.push_back(Eigen::Vector3d::Random());
      w.push_back(wdist(rng));
    }
    curves.emplace_back(kv, pts, w);
  }
  for (const NurbsCurve& c : curves) {
    const double len = c.domain()[1] - c.domain()[0];
    const double h = 1e-6 * len;
    int checked = 0;
    for (int s = 0; s < 200; ++s) {
      const double u = random_in(rng, c.domain());
      bool near_knot = false;
      for (double k : c.knots().knots()) {
        near_knot = near_knot || std::abs(u - k) < 1e-4 * len;
      }
      if (near_knot) {
        continue;
      }
      ++checked;
      const std::vector<Eigen::Vector3d> d = c.derivatives(u, 2);
      EXPECT_LE((d[0] - c.evaluate(u)).norm(), 1e-15 * (1.0 + d[0].norm()));
      EXPECT_LE((d[1] - c.derivative(u)).norm(), 1e-14 * (1.0 + d[1].norm()));
      const Eigen::Vector3d fd1 = (c.evaluate(u + h) - c.evaluate(u - h)) / (2 * h);
      const Eigen::Vector3d fd2 = (c.derivative(u + h) - c.derivative(u - h)) / (2 * h);
      EXPECT_LE((fd1 - d[1]).norm(), 1e-7 * d[1].norm()) << "p = " << c.degree() << " u = " << u;
      if (c.degree() >= 2 || c.is_rational()) {
        EXPECT_LE((fd2 - d[2]).norm(), 1e-7 * d[2].norm()) << "p = " << c.degree() << " u = " << u;
      }
    }
    EXPECT_GE(checked, 100);
  }
}

TEST(NurbsCurve, RejectsBadControlNet) {
  const KnotVector kv = KnotVector::clamped(2, {});
  const std::vector<Eigen::Vector3d> pts(3, Eigen::Vector3d::Zero());
  EXPECT_THROW(NurbsCurve(kv, {pts[0], pts[1]}, {1, 1}), std::invalid_argument);
  EXPECT_THROW(NurbsCurve(kv, pts, {1, -1, 1}), std::invalid_argument);
  EXPECT_THROW(NurbsCurve(kv, pts, {1, std::nan(""), 1}), std::invalid_argument);
  std::vector<Eigen::Vector3d> bad = pts;
  bad[1].y() = INFINITY;
  EXPECT_THROW(NurbsCurve(kv, bad, {1, 1, 1}), std::invalid_argument);
  EXPECT_THROW(NurbsCurve(kv, pts, {1, 1, 1}).derivatives(0.5, -1), std::invalid_argument);
}

// Cylinder of radius 1 and height 3 closed in u: exact radius, derivatives by central differences,
// rational basis partition of unity and positivity, closedness, transposition.
TEST(NurbsSurface, CylinderExactDerivativesAndBasis) {
  const NurbsCurve circle = full_circle(1.0);
  std::vector<Eigen::Vector3d> pts;
  std::vector<double> w;
  const std::vector<double> heights = {0.0, 1.0, 1.5, 3.0};
  for (double z : heights) {
    for (int i = 0; i < circle.count(); ++i) {
      pts.push_back(circle.point(i) + Eigen::Vector3d(0, 0, z));
      w.push_back(circle.weight(i) * (1.0 + 0.3 * z));  // scaling a column keeps the geometry
    }
  }
  const NurbsSurface s(circle.knots(), KnotVector::clamped(2, {0.4}), pts, w);
  EXPECT_TRUE(s.is_closed(0));
  EXPECT_FALSE(s.is_closed(1));
  EXPECT_THROW(s.is_closed(2), std::invalid_argument);
  const NurbsSurface t = s.transposed();
  std::mt19937 rng(3);
  const double h = 1e-6;
  for (int n = 0; n < 200; ++n) {
    const double u = random_in(rng, {0, 1});
    const double v = random_in(rng, {0, 1});
    const Eigen::Vector3d x = s.evaluate(u, v);
    EXPECT_NEAR(x.head<2>().norm(), 1.0, 1e-14);
    EXPECT_LE((t.evaluate(v, u) - x).norm(), 1e-15);
    Eigen::Vector3d p;
    Eigen::Matrix<double, 3, 2> d;
    s.evaluate_derivatives(u, v, p, d);
    const Eigen::Vector3d fu = (s.evaluate(u + h, v) - s.evaluate(u - h, v)) / (2 * h);
    const Eigen::Vector3d fv = (s.evaluate(u, v + h) - s.evaluate(u, v - h)) / (2 * h);
    if (std::abs(u - 0.25) > 1e-4 && std::abs(u - 0.5) > 1e-4 && std::abs(u - 0.75) > 1e-4 &&
        std::abs(v - 0.4) > 1e-4) {
      EXPECT_LE((fu - d.col(0)).norm(), 1e-7 * d.norm());
      EXPECT_LE((fv - d.col(1)).norm(), 1e-7 * d.norm());
    }
    // Rational basis R_ij through unit-pole surfaces.
    double sum = 0.0;
    for (std::size_t a = 0; a < pts.size(); a += 1) {
      std::vector<Eigen::Vector3d> unit(pts.size(), Eigen::Vector3d::Zero());
      unit[a] = Eigen::Vector3d::UnitZ();
      const double R = NurbsSurface(s.knots_u(), s.knots_v(), unit, w).evaluate(u, v).z();
      EXPECT_GE(R, 0.0);
      sum += R;
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
  }
}

TEST(NurbsSurface, RejectsBadControlNet) {
  const KnotVector kv = KnotVector::clamped(1, {});
  std::vector<Eigen::Vector3d> pts(4, Eigen::Vector3d::Zero());
  EXPECT_THROW(NurbsSurface(kv, kv, {pts[0]}, {1}), std::invalid_argument);
  EXPECT_THROW(NurbsSurface(kv, kv, pts, {1, 1, 0, 1}), std::invalid_argument);
  pts[2].x() = NAN;
  EXPECT_THROW(NurbsSurface(kv, kv, pts, {1, 1, 1, 1}), std::invalid_argument);
}

// Rational trivariate basis (thesis 5.13): sum R = 1, R >= 0, sum dR = 0, dR against central
// differences of R (relative 1e-7), H = sum R P, dH = sum P dR^T, dH against central
// differences of H, for several degree combinations with repeated interior knots.
TEST(NurbsVolume, RationalBasisAndJacobian) {
  std::mt19937 rng(4);
  const int degrees[][3] = {{1, 1, 1}, {2, 2, 2}, {3, 3, 3}, {2, 1, 3}, {4, 2, 1}};
  unsigned seed = 10;
  for (const auto& deg : degrees) {
    const NurbsVolume vol = general_volume(deg[0], deg[1], deg[2], seed++);
    VolumeBasis basis;
    VolumeBasis plus;
    VolumeBasis minus;
    for (int n = 0; n < 100; ++n) {
      const Eigen::Vector3d xi(random_in(rng, vol.domain(0)), random_in(rng, vol.domain(1)),
                               random_in(rng, vol.domain(2)));
      vol.evaluate_basis(xi, basis);
      const std::size_t nen = static_cast<std::size_t>((deg[0] + 1) * (deg[1] + 1) * (deg[2] + 1));
      ASSERT_EQ(basis.value.size(), nen);
      double sum = 0.0;
      Eigen::Vector3d dsum = Eigen::Vector3d::Zero();
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      Eigen::Matrix3d jac = Eigen::Matrix3d::Zero();
      double dscale = 0.0;
      for (std::size_t a = 0; a < nen; ++a) {
        EXPECT_GE(basis.value[a], 0.0);
        sum += basis.value[a];
        dsum += basis.derivative[a];
        x += basis.value[a] * vol.points()[static_cast<std::size_t>(basis.index[a])];
        jac += vol.points()[static_cast<std::size_t>(basis.index[a])] *
               basis.derivative[a].transpose();
        dscale = std::max(dscale, basis.derivative[a].norm());
      }
      EXPECT_NEAR(sum, 1.0, 1e-14);
      EXPECT_LE(dsum.norm(), 1e-12 * dscale);
      Eigen::Vector3d hx;
      Eigen::Matrix3d hj;
      vol.evaluate_with_jacobian(xi, hx, hj);
      EXPECT_LE((hx - x).norm(), 1e-14 * (1.0 + x.norm()));
      EXPECT_LE((hj - jac).norm(), 1e-13 * jac.norm());
      EXPECT_LE((vol.evaluate(xi) - hx).norm(), 1e-15 * (1.0 + hx.norm()));
      EXPECT_LE((vol.jacobian(xi) - hj).norm(), 0.0);
      // Central differences inside the same span.
      const std::array<int, 3> span = {vol.knots(0).find_span(xi[0]), vol.knots(1).find_span(xi[1]),
                                       vol.knots(2).find_span(xi[2])};
      for (int d = 0; d < 3; ++d) {
        const double h = 1e-6 * (vol.domain(d)[1] - vol.domain(d)[0]);
        const double lo = vol.knots(d)[span[d]];
        const double hi = vol.knots(d)[span[d] + 1];
        if (xi[d] - h < lo || xi[d] + h > hi) {
          continue;
        }
        Eigen::Vector3d xp = xi;
        Eigen::Vector3d xm = xi;
        xp[d] += h;
        xm[d] -= h;
        vol.evaluate_basis_in_span(span, xp, plus);
        vol.evaluate_basis_in_span(span, xm, minus);
        for (std::size_t a = 0; a < nen; ++a) {
          const double fd = (plus.value[a] - minus.value[a]) / (2 * h);
          EXPECT_LE(std::abs(fd - basis.derivative[a][d]), 1e-7 * dscale)
              << "degrees " << deg[0] << deg[1] << deg[2] << " dir " << d;
        }
        const Eigen::Vector3d fdx = (vol.evaluate(xp) - vol.evaluate(xm)) / (2 * h);
        EXPECT_LE((fdx - hj.col(d)).norm(), 1e-7 * hj.norm());
      }
    }
  }
}

// On an element boundary, evaluate_basis_in_span uses the given element's functions: for a C^0
// knot the values agree from both sides, the derivatives differ, and each equals the one-sided
// limit of its element.
TEST(NurbsVolume, BasisInGivenSpanAtElementBoundary) {
  const NurbsVolume vol = general_volume(2, 2, 2, 99);
  // u = 0.3 has multiplicity 2 = p: C^0 there.
  const Eigen::Vector3d xi(0.3, 0.1, 0.5);
  const int right = vol.knots(0).find_span(0.3);
  const int left = right - 2;  // the span [0.0, 0.3) lies two indices lower (double knot)
  ASSERT_EQ(vol.knots(0)[left + 1], 0.3);
  const std::array<int, 3> sr = {right, vol.knots(1).find_span(0.1), vol.knots(2).find_span(0.5)};
  const std::array<int, 3> sl = {left, sr[1], sr[2]};
  VolumeBasis br;
  VolumeBasis bl;
  VolumeBasis lim;
  vol.evaluate_basis_in_span(sr, xi, br);
  vol.evaluate_basis_in_span(sl, xi, bl);
  Eigen::Vector3d xr = Eigen::Vector3d::Zero();
  Eigen::Vector3d xl = Eigen::Vector3d::Zero();
  for (std::size_t a = 0; a < br.value.size(); ++a) {
    xr += br.value[a] * vol.points()[static_cast<std::size_t>(br.index[a])];
    xl += bl.value[a] * vol.points()[static_cast<std::size_t>(bl.index[a])];
  }
  EXPECT_LE((xr - xl).norm(), 1e-14);
  vol.evaluate_basis_in_span(sl, xi - Eigen::Vector3d(1e-9, 0, 0), lim);
  for (std::size_t a = 0; a < bl.value.size(); ++a) {
    EXPECT_LE((lim.derivative[a] - bl.derivative[a]).norm(), 1e-6 * (1 + bl.derivative[a].norm()));
  }
  EXPECT_THROW(vol.evaluate_basis_in_span({1, sr[1], sr[2]}, xi, br), std::out_of_range);
  EXPECT_THROW(vol.evaluate_basis_in_span({vol.count(0), sr[1], sr[2]}, xi, br), std::out_of_range);
}

// Exact thick shell sector: every point lies at a radius in [r0, r1]; corners are exact.
TEST(NurbsVolume, ShellSectorIsExact) {
  const NurbsVolume vol = shell_sector(1.0, 1.5, 2.0, false);
  std::mt19937 rng(5);
  for (int n = 0; n < 300; ++n) {
    const double u = random_in(rng, {0, 1});
    const double v = random_in(rng, {0, 1});
    const double w = random_in(rng, {0, 1});
    const Eigen::Vector3d x = vol.evaluate({u, v, w});
    EXPECT_NEAR(x.head<2>().norm(), 1.0 + 0.5 * u, 1e-14);
    EXPECT_GT(vol.jacobian({u, v, w}).determinant(), 0.0);
    EXPECT_NEAR(x.z(), 2.0 * w, 1e-14);
  }
  const auto box = vol.bounding_box();
  EXPECT_EQ(box.first, Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(box.second, Eigen::Vector3d(1.5, 1.5, 2.0));
  EXPECT_GT(shell_sector(1.0, 1.5, 2.0, true).jacobian({0.5, 0.5, 0.5}).determinant(), 0.0);
}

TEST(NurbsVolume, RejectsBadControlNet) {
  const KnotVector kv = KnotVector::clamped(1, {});
  std::vector<Eigen::Vector3d> pts(8, Eigen::Vector3d::Zero());
  std::vector<double> w(8, 1.0);
  EXPECT_THROW(NurbsVolume({kv, kv, kv}, {pts[0]}, w), std::invalid_argument);
  w[5] = 0.0;
  EXPECT_THROW(NurbsVolume({kv, kv, kv}, pts, w), std::invalid_argument);
  w[5] = 1.0;
  pts[7].z() = NAN;
  EXPECT_THROW(NurbsVolume({kv, kv, kv}, pts, w), std::invalid_argument);
  EXPECT_THROW(NurbsVolume({kv, KnotVector(), kv}, pts, w), std::invalid_argument);
}

// The IGA hot path: reusing a VolumeBasis never reallocates (buffers stay put), and a quick
// timing of evaluate_basis for p = 2 and 3 (printed; benchmarks live in bench/).
TEST(NurbsVolume, BasisReuseDoesNotReallocateAndTiming) {
  for (int p = 2; p <= 3; ++p) {
    const NurbsVolume vol = general_volume(p, p, p, 50 + static_cast<unsigned>(p));
    VolumeBasis basis;
    vol.evaluate_basis({0.5, 0.0, 1.0}, basis);
    const int* index_data = basis.index.data();
    const double* value_data = basis.value.data();
    const Eigen::Vector3d* deriv_data = basis.derivative.data();
    std::mt19937 rng(6);
    const int n = 5000;
    std::vector<Eigen::Vector3d> xis;
    for (int s = 0; s < n; ++s) {
      xis.emplace_back(random_in(rng, vol.domain(0)), random_in(rng, vol.domain(1)),
                       random_in(rng, vol.domain(2)));
    }
    double checksum = 0.0;
    const auto t0 = std::chrono::steady_clock::now();
    for (const Eigen::Vector3d& xi : xis) {
      vol.evaluate_basis(xi, basis);
      checksum += basis.derivative[0][0];
    }
    const auto t1 = std::chrono::steady_clock::now();
    EXPECT_EQ(basis.index.data(), index_data);
    EXPECT_EQ(basis.value.data(), value_data);
    EXPECT_EQ(basis.derivative.data(), deriv_data);
    EXPECT_TRUE(std::isfinite(checksum));
    const double ns = std::chrono::duration<double, std::nano>(t1 - t0).count() / n;
    std::printf("[ timing ] NurbsVolume::evaluate_basis p = %d (%d functions): %.0f ns per point\n",
                p, (p + 1) * (p + 1) * (p + 1), ns);
  }
}

}  // namespace
}  // namespace isomuscle::geometry
